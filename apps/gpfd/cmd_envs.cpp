// `gpfd envs` and `gpfd learners`: every registered environment and learner, with what they take.
#include <cstdio>

#include "command.hpp"
#include "listings.hpp"

namespace gpfd::app {
namespace {

int print(const std::string& text) {
  std::fwrite(text.data(), 1, text.size(), stdout);
  return 0;
}

const CommandRegistration envs{
    "envs", [](CLI::App& app) {
      app.add_subcommand("envs",
                         "List the environments, their state variables, actions and parameters");
      return [] { return print(describeEnvironments()); };
    }};

const CommandRegistration learners{
    "learners", [](CLI::App& app) {
      app.add_subcommand("learners", "List the learners, what they need and their parameters");
      return [] { return print(describeLearners()); };
    }};

}  // namespace
}  // namespace gpfd::app
