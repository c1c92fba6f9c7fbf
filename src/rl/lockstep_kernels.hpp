// rl: the lane arithmetic of the lockstep player (lockstep_episodes.cpp), on rows of `stride`
// lanes (structure of arrays), four lanes at a time with AVX2 or one at a time. Each function does,
// per lane, the operations of FeaturePipeline::transform or LinearPolicy::sample in their order,
// with each lane's own parameters (lanes may belong to different learning runs). Lanes are
// processed up to the next multiple of 4, so rows must have that much room (scratch).
#pragma once

#include <cstddef>
#include <cstdint>

namespace gpfd::rl::lockstep {

struct Rows {
  std::size_t stride = 0;  // Distance between rows (a multiple of 4).
  std::size_t lanes = 0;   // Lanes computed: [0, lanes), rounded up to a multiple of 4.
  bool avx2 = false;       // Only where cpuHasAvx2().
};

// phi rows j < dim: the finite-check of transform. failed[l] = 1 when a value of lane l is not
// finite, else 0; then, when `shift` is given, phi_j = (phi_j - shift_j) / scale_j (rows j).
void checkAndNormalise(const Rows& rows, double* phi, std::size_t dim, const double* shift,
                       const double* scale, std::uint8_t* failed);

// flags[l] = 1 where a value of lane l in rows [0, count) of `values` or rows [0, count2) of
// `values2` is not finite; other flags are left as they are.
void flagNotFinite(const Rows& rows, const double* values, std::size_t count, std::uint8_t* flags,
                   const double* values2 = nullptr, std::size_t count2 = 0);

// Between the lane rows (structure of arrays: variable i of lane l at soa[i * stride + l]) and
// the feature map's lane blocks (FeatureMap::evaluateLaneBlocks: blocks[(l / 4 * dim + i) * 4 +
// l % 4]), for lanes [0, rows.lanes).
void toLaneBlocks(const Rows& rows, const double* soa, std::size_t dim, double* blocks);
void fromLaneBlocks(const Rows& rows, const double* blocks, std::size_t dim, double* soa);

// mu rows i < outputs = sum over j in order of w rows (i * dim + j) times phi rows j
// (LinearPolicy's outputs).
void linearOutputs(const Rows& rows, const double* w, std::size_t outputs, std::size_t dim,
                   const double* phi, double* mu);

// The Gaussian action of one output from its draws eps and standard deviations sd (rows):
// action = centre + half (mu + sd eps), coefficient = eps / sd, and, when `stdGradient` is given,
// stdGradient += eps^2 - 1.
void gaussianActions(const Rows& rows, const double* mu, const double* eps, const double* sd,
                     double centre, double half, double* action, double* coefficient,
                     double* stdGradient);

// eligibility rows [row, row + dim) += coefficient * phi rows [0, dim).
void addGradient(const Rows& rows, double* eligibility, std::size_t row, const double* coefficient,
                 const double* phi, std::size_t dim);

}  // namespace gpfd::rl::lockstep
