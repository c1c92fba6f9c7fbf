#include "lockstep_kernels.hpp"

#include "gpfd/util/lanes.hpp"

namespace gpfd::rl::lockstep {
namespace {

using lanes::loadAs;
using lanes::store;

// Bit k set where lane l + k has a value in rows [0, count) that is not finite.
template <class T>
unsigned notFiniteBits(const Rows& rows, const double* values, std::size_t count, std::size_t l) {
  lanes::MaskOf<T> bad = lanes::noLane<T>();
  for (std::size_t j = 0; j < count; ++j) {
    const T x = loadAs<T>(values + j * rows.stride + l);
    // inf - inf and NaN - NaN are NaN.
    bad = bad || lanes::isNan(x - x);  // NOLINT(misc-redundant-expression)
  }
  return lanes::bitsOf(bad);
}

template <class T>
void flagNotFiniteT(const Rows& rows, const double* values, std::size_t count, std::uint8_t* flags,
                    const double* values2, std::size_t count2) {
  for (std::size_t l = 0; l < rows.lanes; l += lanes::kWidth<T>) {
    const unsigned bits =
        notFiniteBits<T>(rows, values, count, l) | notFiniteBits<T>(rows, values2, count2, l);
    if (bits == 0) continue;
    for (std::size_t k = 0; k < lanes::kWidth<T>; ++k) flags[l + k] |= (bits >> k) & 1u;
  }
}

template <class T>
void checkAndNormaliseT(const Rows& rows, double* phi, std::size_t dim, const double* shift,
                        const double* scale, std::uint8_t* failed) {
  for (std::size_t l = 0; l < rows.lanes; l += lanes::kWidth<T>) {
    const unsigned bits = notFiniteBits<T>(rows, phi, dim, l);
    for (std::size_t k = 0; k < lanes::kWidth<T>; ++k) failed[l + k] = (bits >> k) & 1u;
    if (shift == nullptr) continue;
    for (std::size_t j = 0; j < dim; ++j) {
      double* p = phi + j * rows.stride + l;
      store(p, (loadAs<T>(p) - loadAs<T>(shift + j * rows.stride + l)) /
                   loadAs<T>(scale + j * rows.stride + l));
    }
  }
}

// Lane rows <-> lane blocks; `toRows` chooses the direction. With AVX2 (T = Lanes4) a block row
// is one 32-byte load and store, so that the JIT kernel's 32-byte load of it is forwarded from
// one store.
template <class T>
void copyBlocksT(const Rows& rows, const double* from, std::size_t dim, double* to, bool toRows) {
  for (std::size_t l = 0; l < rows.lanes; l += 4) {
    for (std::size_t i = 0; i < dim; ++i) {
      // l is a multiple of 4: lane block l / 4 starts at l * dim.
      const std::size_t row = i * rows.stride + l, block = l * dim + 4 * i;
      const double* src = from + (toRows ? block : row);
      double* dst = to + (toRows ? row : block);
      for (std::size_t k = 0; k < 4; k += lanes::kWidth<T>) store(dst + k, loadAs<T>(src + k));
    }
  }
}

template <class T>
void linearOutputsT(const Rows& rows, const double* w, std::size_t outputs, std::size_t dim,
                    const double* phi, double* mu) {
  for (std::size_t l = 0; l < rows.lanes; l += lanes::kWidth<T>) {
    for (std::size_t i = 0; i < outputs; ++i) {
      T acc = 0.0;
      for (std::size_t j = 0; j < dim; ++j) {
        acc +=
            loadAs<T>(w + (i * dim + j) * rows.stride + l) * loadAs<T>(phi + j * rows.stride + l);
      }
      store(mu + i * rows.stride + l, acc);
    }
  }
}

template <class T>
void gaussianActionsT(const Rows& rows, const double* mu, const double* eps, const double* sd,
                      double centre, double half, double* action, double* coefficient,
                      double* stdGradient) {
  for (std::size_t l = 0; l < rows.lanes; l += lanes::kWidth<T>) {
    const T e = loadAs<T>(eps + l), deviation = loadAs<T>(sd + l);
    const T u = loadAs<T>(mu + l) + deviation * e;
    store(action + l, centre + half * u);
    store(coefficient + l, e / deviation);
    if (stdGradient != nullptr) store(stdGradient + l, loadAs<T>(stdGradient + l) + (e * e - 1.0));
  }
}

template <class T>
void addGradientT(const Rows& rows, double* eligibility, std::size_t row, const double* coefficient,
                  const double* phi, std::size_t dim) {
  for (std::size_t l = 0; l < rows.lanes; l += lanes::kWidth<T>) {
    const T c = loadAs<T>(coefficient + l);
    for (std::size_t j = 0; j < dim; ++j) {
      double* e = eligibility + (row + j) * rows.stride + l;
      store(e, loadAs<T>(e) + c * loadAs<T>(phi + j * rows.stride + l));
    }
  }
}

GPFD_AVX2_KERNEL void checkAndNormaliseAvx2(const Rows& rows, double* phi, std::size_t dim,
                                            const double* shift, const double* scale,
                                            std::uint8_t* failed) {
  checkAndNormaliseT<lanes::Lanes4>(rows, phi, dim, shift, scale, failed);
}
GPFD_AVX2_KERNEL void flagNotFiniteAvx2(const Rows& rows, const double* values, std::size_t count,
                                        std::uint8_t* flags, const double* values2,
                                        std::size_t count2) {
  flagNotFiniteT<lanes::Lanes4>(rows, values, count, flags, values2, count2);
}
GPFD_AVX2_KERNEL void copyBlocksAvx2(const Rows& rows, const double* from, std::size_t dim,
                                     double* to, bool toRows) {
  copyBlocksT<lanes::Lanes4>(rows, from, dim, to, toRows);
}
GPFD_AVX2_KERNEL void linearOutputsAvx2(const Rows& rows, const double* w, std::size_t outputs,
                                        std::size_t dim, const double* phi, double* mu) {
  linearOutputsT<lanes::Lanes4>(rows, w, outputs, dim, phi, mu);
}
GPFD_AVX2_KERNEL void gaussianActionsAvx2(const Rows& rows, const double* mu, const double* eps,
                                          const double* sd, double centre, double half,
                                          double* action, double* coefficient,
                                          double* stdGradient) {
  gaussianActionsT<lanes::Lanes4>(rows, mu, eps, sd, centre, half, action, coefficient,
                                  stdGradient);
}
GPFD_AVX2_KERNEL void addGradientAvx2(const Rows& rows, double* eligibility, std::size_t row,
                                      const double* coefficient, const double* phi,
                                      std::size_t dim) {
  addGradientT<lanes::Lanes4>(rows, eligibility, row, coefficient, phi, dim);
}

}  // namespace

void checkAndNormalise(const Rows& rows, double* phi, std::size_t dim, const double* shift,
                       const double* scale, std::uint8_t* failed) {
  if (rows.avx2) return checkAndNormaliseAvx2(rows, phi, dim, shift, scale, failed);
  checkAndNormaliseT<double>(rows, phi, dim, shift, scale, failed);
}

void flagNotFinite(const Rows& rows, const double* values, std::size_t count, std::uint8_t* flags,
                   const double* values2, std::size_t count2) {
  if (rows.avx2) return flagNotFiniteAvx2(rows, values, count, flags, values2, count2);
  flagNotFiniteT<double>(rows, values, count, flags, values2, count2);
}

void toLaneBlocks(const Rows& rows, const double* soa, std::size_t dim, double* blocks) {
  if (rows.avx2) return copyBlocksAvx2(rows, soa, dim, blocks, false);
  copyBlocksT<double>(rows, soa, dim, blocks, false);
}

void fromLaneBlocks(const Rows& rows, const double* blocks, std::size_t dim, double* soa) {
  if (rows.avx2) return copyBlocksAvx2(rows, blocks, dim, soa, true);
  copyBlocksT<double>(rows, blocks, dim, soa, true);
}

void linearOutputs(const Rows& rows, const double* w, std::size_t outputs, std::size_t dim,
                   const double* phi, double* mu) {
  if (rows.avx2) return linearOutputsAvx2(rows, w, outputs, dim, phi, mu);
  linearOutputsT<double>(rows, w, outputs, dim, phi, mu);
}

void gaussianActions(const Rows& rows, const double* mu, const double* eps, const double* sd,
                     double centre, double half, double* action, double* coefficient,
                     double* stdGradient) {
  if (rows.avx2) {
    return gaussianActionsAvx2(rows, mu, eps, sd, centre, half, action, coefficient, stdGradient);
  }
  gaussianActionsT<double>(rows, mu, eps, sd, centre, half, action, coefficient, stdGradient);
}

void addGradient(const Rows& rows, double* eligibility, std::size_t row, const double* coefficient,
                 const double* phi, std::size_t dim) {
  if (rows.avx2) return addGradientAvx2(rows, eligibility, row, coefficient, phi, dim);
  addGradientT<double>(rows, eligibility, row, coefficient, phi, dim);
}

}  // namespace gpfd::rl::lockstep
