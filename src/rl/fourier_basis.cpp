#include "gpfd/rl/fourier_basis.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <stdexcept>

namespace gpfd::rl {

FourierBasis::FourierBasis(std::vector<StateRange> ranges, int order, Coupling coupling)
    : ranges_(std::move(ranges)), order_(order), coupling_(coupling) {
  const std::size_t d = ranges_.size();
  if (d == 0 || order < 1) throw std::invalid_argument("FourierBasis needs d >= 1 and order >= 1");
  if (coupling == Coupling::Full) {
    // Every c in {0..order}^d, counting in base order + 1.
    std::vector<int> c(d, 0);
    for (;;) {
      for (int v : c) coefficients_.push_back(v);
      std::size_t i = 0;
      while (i < d && c[i] == order) c[i++] = 0;
      if (i == d) break;
      ++c[i];
    }
  } else {
    coefficients_.assign(d, 0.0);  // The constant term.
    for (std::size_t i = 0; i < d; ++i) {
      for (int k = 1; k <= order; ++k) {
        std::vector<double> c(d, 0.0);
        c[i] = k;
        coefficients_.insert(coefficients_.end(), c.begin(), c.end());
      }
    }
  }
}

FourierBasis FourierBasis::automatic(std::vector<StateRange> ranges, int order, int maxTerms) {
  const double full = std::pow(order + 1.0, static_cast<double>(ranges.size()));
  return FourierBasis(std::move(ranges), order,
                      full <= maxTerms ? Coupling::Full : Coupling::Independent);
}

void FourierBasis::evaluate(const double* state, double* features) const {
  const std::size_t d = ranges_.size();
  double x[64];
  std::vector<double> heap;
  double* scaled = x;
  if (d > 64) {
    heap.resize(d);
    scaled = heap.data();
  }
  for (std::size_t i = 0; i < d; ++i) {
    const double v = (state[i] - ranges_[i].low) / (ranges_[i].high - ranges_[i].low);
    scaled[i] = std::isnan(v) ? 0.5 : std::clamp(v, 0.0, 1.0);
  }
  const std::size_t terms = outputDim();
  if (coupling_ == Coupling::Full) {
    // cos(pi c.x) = Re prod_i exp(i pi c_i x_i): the terms in the order of the constructor (the
    // first variable's coefficient fastest) are the tensor product of the per-variable factors
    // exp(i pi k x_i), k = 0..order, built one variable at a time: (order + 1)^d complex products
    // instead of as many cosines.
    const auto base = static_cast<std::size_t>(order_) + 1;
    thread_local std::vector<std::complex<double>> product, factor;  // No allocation per call.
    product.resize(terms);
    factor.resize(base);
    std::size_t size = 1;
    product[0] = 1.0;
    for (std::size_t i = 0; i < d; ++i) {
      for (std::size_t k = 0; k < base; ++k) {
        factor[k] = std::polar(1.0, std::numbers::pi * static_cast<double>(k) * scaled[i]);
      }
      // Blocks for k = base-1 .. 1 first, so that block 0 (k = 0, factor 1) is read last.
      for (std::size_t k = base; k-- > 1;) {
        for (std::size_t j = 0; j < size; ++j) product[k * size + j] = product[j] * factor[k];
      }
      size *= base;
    }
    for (std::size_t t = 0; t < terms; ++t) features[t] = product[t].real();
    return;
  }
  for (std::size_t t = 0; t < terms; ++t) {
    const double* c = &coefficients_[t * d];
    double dot = 0.0;
    for (std::size_t i = 0; i < d; ++i) dot += c[i] * scaled[i];
    features[t] = std::cos(std::numbers::pi * dot);
  }
}

}  // namespace gpfd::rl
