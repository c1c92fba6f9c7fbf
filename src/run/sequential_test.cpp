#include "gpfd/run/sequential_test.hpp"

#include <array>
#include <cmath>
#include <stdexcept>

namespace gpfd::run {
namespace {

// C(K) of O'Brien-Fleming boundaries for K = 1..5 equally spaced looks, two-sided level 0.05
// (Jennison & Turnbull 2000, Table 2.3).
constexpr std::array<double, kMaxLooks> kConstant{1.960, 1.977, 2.004, 2.024, 2.040};

void checkLook(int look, int looks) {
  if (looks < 1 || looks > kMaxLooks || look < 1 || look > looks) {
    throw std::invalid_argument("look out of range");
  }
}

}  // namespace

int seedsAtLook(int seeds, int look, int looks) {
  checkLook(look, looks);
  return (look * seeds + looks - 1) / looks;
}

double nominalLevel(int look, int looks) {
  checkLook(look, looks);
  const double z = kConstant[static_cast<std::size_t>(looks - 1)] *
                   std::sqrt(static_cast<double>(looks) / static_cast<double>(look));
  return std::erfc(z / std::sqrt(2.0));  // 2 (1 - Phi(z)).
}

bool endsAtLook(const PairedComparison& difference, int look, int looks) {
  return look == looks || difference.p < nominalLevel(look, looks);
}

bool confirmationEndsAtLook(const PairedComparison& vsOriginal,
                            const PairedComparison* vsNoLearning, int look, int looks) {
  if (look == looks) return true;
  if (!endsAtLook(vsOriginal, look, looks)) return false;
  return vsNoLearning == nullptr || vsOriginal.meanDifference < 0.0 ||
         endsAtLook(*vsNoLearning, look, looks);
}

}  // namespace gpfd::run
