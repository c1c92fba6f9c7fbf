#include "cli_errors.hpp"

#include <fmt/format.h>

#include <string>
#include <vector>

#include "gpfd/io/suggest.hpp"

namespace gpfd::app {
namespace {

const CLI::App* deepestParsed(const CLI::App& root) {
  const CLI::App* app = &root;
  for (bool descended = true; descended;) {
    descended = false;
    for (const CLI::App* sub : app->get_subcommands([](const CLI::App*) { return true; })) {
      if (sub->parsed() > 0) {
        app = sub;
        descended = true;
        break;
      }
    }
  }
  return app;
}

// "gpfd evolve", "gpfd features show".
std::string commandPath(const CLI::App* app) {
  std::string path;
  for (; app->get_parent() != nullptr; app = app->get_parent()) path = " " + app->get_name() + path;
  return "gpfd" + path;
}

std::vector<std::string> subcommandNames(const CLI::App* app) {
  std::vector<std::string> names;
  for (const CLI::App* sub : app->get_subcommands([](const CLI::App*) { return true; })) {
    names.push_back(sub->get_name());
  }
  return names;
}

std::vector<std::string> flagNames(const CLI::App* app) {
  std::vector<std::string> names;
  for (const CLI::Option* option : app->get_options()) {
    for (const auto& n : option->get_lnames()) names.push_back("--" + n);
    for (const auto& n : option->get_snames()) names.push_back("-" + n);
  }
  return names;
}

// The first command-line word that no command took, and the command it was left to.
bool firstUnused(const CLI::App* app, std::string& word, const CLI::App*& owner) {
  for (; app != nullptr; app = app->get_parent()) {
    const auto left = app->remaining();
    if (!left.empty()) {
      word = left.front();
      owner = app;
      return true;
    }
  }
  return false;
}

InputError unusedWord(const std::string& word, const CLI::App* app) {
  const std::string where = commandPath(app);
  if (word.size() > 1 && word[0] == '-') {
    const std::string flag = word.substr(0, word.find('='));
    return InputError("unknown flag '" + flag + "'" + io::didYouMean(flag, flagNames(app)), where);
  }
  const auto commands = subcommandNames(app);
  if (!commands.empty()) {
    const std::string suggestion = io::didYouMean(word, commands);
    return InputError(
        "unknown command '" + word + "'" +
            (suggestion.empty() ? fmt::format(" (commands: {})", fmt::join(commands, ", "))
                                : suggestion),
        where);
  }
  return InputError("unexpected argument '" + word + "'", where);
}

// "NAME: rest" -> {NAME, rest}; {"", message} without a colon.
std::pair<std::string, std::string> splitName(const std::string& message) {
  const auto colon = message.find(": ");
  if (colon == std::string::npos) return {"", message};
  return {message.substr(0, colon), message.substr(colon + 2)};
}

// The flag (or positional argument) called `name` in `app`, for the place of an error.
std::string placeOf(const CLI::App* app, const std::string& name) {
  const CLI::Option* option = app->get_option_no_throw(name);
  if (option == nullptr || option->get_lnames().empty()) return commandPath(app);
  return commandPath(app) + " --" + option->get_lnames().front();
}

// A positional argument's name as --help shows it, e.g. ENV.
std::string argumentName(const std::string& name) {
  std::string upper = name;
  for (char& c : upper) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return upper;
}

}  // namespace

InputError describeParseError(const CLI::App& root, const CLI::ParseError& error) {
  const CLI::App* app = deepestParsed(root);
  std::string word;
  const CLI::App* owner = nullptr;
  if (firstUnused(app, word, owner)) return unusedWord(word, owner);

  const std::string message = error.what();
  const std::string kind = error.get_name();
  if (kind == "RequiredError") {
    if (message.rfind("A subcommand", 0) == 0) {
      return InputError(
          fmt::format("missing command: one of {}", fmt::join(subcommandNames(app), ", ")),
          commandPath(app));
    }
    const std::string name = message.substr(0, message.find(" is required"));
    const CLI::Option* option = app->get_option_no_throw(name);
    const bool positional = option != nullptr && option->get_lnames().empty();
    return InputError("missing " + (positional ? argumentName(name) : name), commandPath(app));
  }
  if (kind == "ValidationError") {
    const auto [name, what] = splitName(message);
    return InputError(what, placeOf(app, name));
  }
  if (kind == "ArgumentMismatch") {
    const auto [name, what] = splitName(message);
    if (!name.empty() && what.find("missing") != std::string::npos) {
      return InputError("a value is missing", placeOf(app, name));
    }
    return InputError(message, commandPath(app));
  }
  if (kind == "ConversionError") {
    // "Could not convert: NAME = VALUE" or "NAME: Should be true/false or a number".
    const std::string prefix = "Could not convert: ";
    if (message.rfind(prefix, 0) == 0) {
      const std::string rest = message.substr(prefix.size());
      const auto eq = rest.find(" = ");
      if (eq != std::string::npos) {
        return InputError("'" + rest.substr(eq + 3) + "' is not a valid value",
                          placeOf(app, rest.substr(0, eq)));
      }
    }
    const auto [name, what] = splitName(message);
    return InputError(what, placeOf(app, name));
  }
  return InputError(message, commandPath(app));
}

}  // namespace gpfd::app
