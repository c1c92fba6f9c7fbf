// python: an array returned by a Python vector environment, read in place (vector_hub.cpp).
#pragma once

#include <cstdint>

#include "bindings.hpp"

namespace gpfd::python {

// An array returned by the vector environment, read in place: float64, float32, bool or a
// 32/64-bit integer, any strides.
class ReadView {
 public:
  // False when `value` is not such an array of `ndim` dimensions with `rows` rows (and `cols`
  // columns for two).
  bool bind(nb::handle value, std::size_t ndim, std::size_t rows, std::size_t cols = 1) {
    if (!nb::try_cast(value, array_, false) || array_.ndim() != ndim) return false;
    raw_ = array_.data();
    if (array_.shape(0) != rows || (ndim == 2 && array_.shape(1) != cols)) return false;
    const nb::dlpack::dtype type = array_.dtype();
    if (type == nb::dtype<double>()) {
      kind_ = Kind::F64;
    } else if (type == nb::dtype<float>()) {
      kind_ = Kind::F32;
    } else if (type == nb::dtype<bool>()) {
      kind_ = Kind::Bool;
    } else if (type == nb::dtype<std::int64_t>()) {
      kind_ = Kind::I64;
    } else if (type == nb::dtype<std::int32_t>()) {
      kind_ = Kind::I32;
    } else {
      return false;
    }
    rowStride_ = array_.stride(0);
    colStride_ = ndim == 2 ? array_.stride(1) : 0;
    return true;
  }
  // A C++ array of `rows` x `cols`, row-major (gpfd's own vector environment's buffers).
  void bindRaw(const double* data, std::size_t cols) {
    raw_ = data;
    kind_ = Kind::F64;
    rowStride_ = static_cast<std::int64_t>(cols);
    colStride_ = 1;
  }
  void bindRaw(const bool* data) {
    raw_ = data;
    kind_ = Kind::Bool;
    rowStride_ = 1;
    colStride_ = 0;
  }
  bool isBool() const { return kind_ == Kind::Bool; }
  bool isFloat() const { return kind_ == Kind::F64 || kind_ == Kind::F32; }

  double at(std::size_t row, std::size_t col = 0) const {
    const std::int64_t i =
        static_cast<std::int64_t>(row) * rowStride_ + static_cast<std::int64_t>(col) * colStride_;
    switch (kind_) {
      case Kind::F64:
        return static_cast<const double*>(raw_)[i];
      case Kind::F32:
        return static_cast<const float*>(raw_)[i];
      case Kind::Bool:
        return static_cast<const bool*>(raw_)[i] ? 1.0 : 0.0;
      case Kind::I64:
        return static_cast<double>(static_cast<const std::int64_t*>(raw_)[i]);
      case Kind::I32:
        return static_cast<const std::int32_t*>(raw_)[i];
    }
    return 0.0;
  }

 private:
  enum class Kind { F64, F32, Bool, I64, I32 };
  nb::ndarray<nb::ro, nb::device::cpu> array_;
  const void* raw_ = nullptr;
  Kind kind_ = Kind::F64;
  std::int64_t rowStride_ = 0, colStride_ = 0;
};

}  // namespace gpfd::python
