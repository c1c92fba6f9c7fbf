// gpfd: the command-line tool. It only parses arguments and calls the library; every error is
// reported here once, as `error: <what> (<where>)`. Exit codes: 0 success, 1 internal error,
// 2 bad input, 3 numerical failure (non-finite states or learning), 130 interrupted.
#include <algorithm>
#include <cstdio>
#include <exception>
#include <string>

#include "cli_errors.hpp"
#include "command.hpp"
#include "gpfd/util/error.hpp"
#include "gpfd/version.hpp"
#include "plugin_arguments.hpp"

#ifdef GPFD_HAVE_MPI
#include <optional>

#include "gpfd/mpi/session.hpp"
#endif

namespace gpfd::app {
std::vector<Command>& commands() {
  static std::vector<Command> all;
  return all;
}
}  // namespace gpfd::app

namespace {

// Runs the command of the command line; returns the exit code.
int runCommand(int argc, char** argv) {
  using namespace gpfd;
  std::vector<char*> args;
  try {
    args = app::loadPluginArguments(argc, argv);
  } catch (const InputError& e) {
    std::fprintf(stderr, "error: %s\n", e.message().c_str());
    return 2;
  }
  CLI::App cli{"gpfd: feature discovery for reinforcement learning with genetic programming",
               "gpfd"};
  cli.set_version_flag("--version", std::string("gpfd ") + kVersion + " (" + kRevision + ")");
  std::string pluginHelp;  // Taken out of the arguments above; declared here for --help.
  cli.add_option("--plugin", pluginHelp,
                 "Load environments and learners from a plug-in (a shared library; repeatable, "
                 "anywhere on the line)");
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

  if (argc == 1) {  // Plain `gpfd`: the list of commands, and a usage error (nothing was run).
    std::fputs(cli.help().c_str(), stderr);
    std::fputs("error: no command given (gpfd --help lists them)\n", stderr);
    return 2;
  }
  try {
    cli.parse(static_cast<int>(args.size()), args.data());
  } catch (const CLI::Success& e) {  // --help, --version.
    return cli.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "error: %s\n", app::describeParseError(cli, e).message().c_str());
    return 2;
  }
  try {
#ifdef GPFD_HAVE_MPI
    if (auto* session = mpi::Session::current();
        session && session->size() > 1 && !cli.got_subcommand("evolve")) {
      // Every rank runs the same command line; only evolve divides the work.
      if (!session->isMaster()) return 2;
      throw InputError("only `gpfd evolve` runs on several MPI processes",
                       "mpiexec -n " + std::to_string(session->size()));
    }
#endif
    for (const auto& [sub, run] : runners) {
      if (sub->parsed()) return run();
    }
    return 2;
  } catch (const InputError& e) {
    std::fprintf(stderr, "error: %s\n", e.message().c_str());
    return 2;
  } catch (const NumericalError& e) {
    std::fprintf(stderr, "error: %s\n", e.message().c_str());
    return 3;
  } catch (const Interrupted& e) {
    std::fprintf(stderr, "%s\n", e.message().c_str());
    return 130;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}

}  // namespace

int main(int argc, char** argv) {
  using namespace gpfd;
#ifdef GPFD_HAVE_MPI
  // Started by mpiexec: MPI lives for the whole process (`gpfd evolve` then runs rank 0 as the
  // master, the others as workers). Otherwise gpfd never touches MPI.
  std::optional<mpi::Session> session;
  if (mpi::Session::launchedByProcessManager()) {
    try {
      session.emplace(argc, argv);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "error: %s\n", e.what());
      return 1;
    }
  }
#endif
  const int code = runCommand(argc, argv);
#ifdef GPFD_HAVE_MPI
  // A master that lost workers ends the job here with MPI_Abort (mpi/session.hpp).
  if (session) return session->finish(code);
#endif
  return code;
}
