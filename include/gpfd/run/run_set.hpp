// run: independent discovery runs of one config: the unit behind a claim about the method
// (`gpfd evolve --runs N`, `gpfd reproduce --gp-runs N`). Run r (1-based) of a set with seed S
// uses runSeed(S, r): run 1 is the single run with seed S, the others seeds derived from S.
//
// A set's directory: config.toml (the base config), runs.json (seed and count), run-01 ...
// (each a discovery run, see discovery.hpp) and runs.csv (one row per finished run).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "gpfd/run/discovery.hpp"
#include "gpfd/run/statistics.hpp"
#include "gpfd/run/validation.hpp"

namespace gpfd::run {

std::uint64_t runSeed(std::uint64_t seed, int run);
// "run-01", ... (three digits from 100 runs on).
std::string runDirName(int run, int runs);

// What one finished run returned, as validation measured it.
struct RunOutcome {
  int run = 0;
  std::uint64_t seed = 0;
  double gpBest = 0.0;     // The GP's best fitness in the last generation (a biased number).
  bool validated = false;  // Without validation the GP's best is returned and the rest is empty.
  bool originalWon = false;
  bool confirmed = false;       // The scores below are the confirmation's (else validation's).
  Summary winner, original;     // Reported scores of the returned set and the original variables.
  PairedComparison vsOriginal;  // winner - original on the same seeds.
  std::size_t features = 0, size = 0;
  NoLearningVerdict noLearning;  // Against the no-learning reference (validated runs).
};
RunOutcome outcomeOf(const Discovery& discovery, int run);

std::string formatRunsCsv(const std::vector<RunOutcome>& outcomes);

// The set's runs.json: the base seed and the number of runs.
std::string formatRunsJson(std::uint64_t seed, int runs);
// InputError naming `source` when the text is not a runs.json.
void parseRunsJson(const std::string& text, const std::string& source, std::uint64_t& seed,
                   int& runs);

}  // namespace gpfd::run
