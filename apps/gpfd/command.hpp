// The gpfd tool's subcommands. Each apps/gpfd/cmd_*.cpp registers its subcommands with a static
// CommandRegistration, so adding a command touches no other file.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

#include "validators.hpp"

namespace gpfd::app {

// Adds a subcommand (and its options) to `app` and returns the function that runs it once the
// command line is parsed; that function returns the process exit code.
using CommandSetup = std::function<std::function<int()>(CLI::App& app)>;

struct Command {
  std::string name;
  CommandSetup setup;
};

std::vector<Command>& commands();

struct CommandRegistration {
  CommandRegistration(std::string name, CommandSetup setup) {
    commands().push_back({std::move(name), std::move(setup)});
  }
};

}  // namespace gpfd::app
