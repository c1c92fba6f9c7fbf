// gpfd: the command-line tool. It only parses arguments and calls the library; every error is
// reported here once, as `error: <what> (<where>)`.
#include <algorithm>
#include <cstdio>
#include <exception>
#include <string>

#include "command.hpp"
#include "gpfd/util/error.hpp"
#include "gpfd/version.hpp"

namespace gpfd::app {
std::vector<Command>& commands() {
  static std::vector<Command> all;
  return all;
}
}  // namespace gpfd::app

int main(int argc, char** argv) {
  using namespace gpfd;
  CLI::App cli{"gpfd: feature discovery for reinforcement learning with genetic programming"};
  cli.set_version_flag("--version", std::string("gpfd ") + kVersion + " (" + kRevision + ")");
  cli.require_subcommand(1);

  auto& all = app::commands();
  std::sort(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
  std::vector<std::pair<CLI::App*, std::function<int()>>> runners;
  for (const auto& command : all) {
    const std::size_t before = cli.get_subcommands({}).size();
    auto run = command.setup(cli);
    auto subs = cli.get_subcommands({});
    for (std::size_t i = before; i < subs.size(); ++i) runners.emplace_back(subs[i], run);
  }

  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = cli.exit(e);
    return code == 0 ? 0 : 2;
  }
  try {
    for (const auto& [sub, run] : runners) {
      if (sub->parsed()) return run();
    }
    return 2;
  } catch (const InputError& e) {
    std::fprintf(stderr, "error: %s\n", e.message().c_str());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
