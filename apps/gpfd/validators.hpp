// Checks of the commands' flag values (CLI11 validators). Each states its bound in --help
// ("in [1, 100000]") and refuses a value with a message that names the value and the bound; the
// parse-error handler (cli_errors.hpp) adds the command and the flag.
#pragma once

#include <CLI/CLI.hpp>
#include <charconv>
#include <string>
#include <vector>

namespace gpfd::app {

// An integer in [lo, hi].
CLI::Validator bounded(long long lo, long long hi);
// A seed: any integer in [0, 2^64 - 1].
CLI::Validator seedValue();
// One of `choices`, with a did-you-mean for a near miss.
CLI::Validator oneOf(std::vector<std::string> choices);
// A registered environment's name (see `gpfd envs`), with a did-you-mean.
CLI::Validator environmentName();

// Every --threads: 0 (all cores) up to a sane bound; more than the cores is clamped (threads()).
inline CLI::Validator threadCount() { return bounded(0, 4096); }
// The bounds of the flags that several commands share.
inline constexpr long long kMaxPopulation = 1000000;  // Also the config's gp.population bound.
inline constexpr long long kMaxGenerations = 1000000;
inline constexpr long long kMaxRuns = 100000;     // assess --runs, as the config's assess.runs.
inline constexpr long long kMaxSteps = 10000000;  // simulate --steps: its CSV is built in memory.
inline constexpr long long kMaxBudget = 1000000;  // Policy updates or lambda-PI iterations.

}  // namespace gpfd::app
