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
    bad = bad || lanes::isNan(x - x);  // inf - inf and NaN - NaN are NaN.
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

// The 4 x 4 block of lanes [l, l + 4) and variables [i, i + 4), transposed.
inline void transpose4(lanes::RawLanes v[4]) {
  const lanes::RawLanes t0 = __builtin_shufflevector(v[0], v[1], 0, 4, 2, 6);
  const lanes::RawLanes t1 = __builtin_shufflevector(v[0], v[1], 1, 5, 3, 7);
  const lanes::RawLanes t2 = __builtin_shufflevector(v[2], v[3], 0, 4, 2, 6);
  const lanes::RawLanes t3 = __builtin_shufflevector(v[2], v[3], 1, 5, 3, 7);
  v[0] = __builtin_shufflevector(t0, t2, 0, 1, 4, 5);
  v[1] = __builtin_shufflevector(t1, t3, 0, 1, 4, 5);
  v[2] = __builtin_shufflevector(t0, t2, 2, 3, 6, 7);
  v[3] = __builtin_shufflevector(t1, t3, 2, 3, 6, 7);
}

// Lane-major <-> structure of arrays; `toLanes` chooses the direction. Whole 4 x 4 blocks with
// AVX2 (T = Lanes4), the remaining variables one by one.
template <class T>
void transposeT(const Rows& rows, const double* from, std::size_t dim, double* to, bool toLanes) {
  std::size_t first = 0;
  if constexpr (lanes::kWidth<T> == 4) {
    first = dim / 4 * 4;
    for (std::size_t l = 0; l < rows.lanes; l += 4) {
      for (std::size_t i = 0; i < first; i += 4) {
        lanes::RawLanes v[4];
        for (std::size_t k = 0; k < 4; ++k) {
          v[k] = loadAs<T>(toLanes ? from + (l + k) * dim + i : from + (i + k) * rows.stride + l).v;
        }
        transpose4(v);
        for (std::size_t k = 0; k < 4; ++k) {
          store(toLanes ? to + (i + k) * rows.stride + l : to + (l + k) * dim + i, T(v[k]));
        }
      }
    }
  }
  for (std::size_t l = 0; l < rows.lanes; ++l) {
    for (std::size_t i = first; i < dim; ++i) {
      if (toLanes) {
        to[i * rows.stride + l] = from[l * dim + i];
      } else {
        to[l * dim + i] = from[i * rows.stride + l];
      }
    }
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
GPFD_AVX2_KERNEL void transposeAvx2(const Rows& rows, const double* from, std::size_t dim,
                                    double* to, bool toLanes) {
  transposeT<lanes::Lanes4>(rows, from, dim, to, toLanes);
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

void toLaneMajor(const Rows& rows, const double* soa, std::size_t dim, double* aos) {
  if (rows.avx2) return transposeAvx2(rows, soa, dim, aos, false);
  transposeT<double>(rows, soa, dim, aos, false);
}

void fromLaneMajor(const Rows& rows, const double* aos, std::size_t dim, double* soa) {
  if (rows.avx2) return transposeAvx2(rows, aos, dim, soa, true);
  transposeT<double>(rows, aos, dim, soa, true);
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
