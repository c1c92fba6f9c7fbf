// util: the exceptions that end a command with a message. main catches them once and prints
// `error: <what> (<where>)`, with the exit code of the kind: InputError 2 (bad input: command
// line, config, feature files, parameters), NumericalError 3 (a simulation or a learner produced
// non-finite numbers), Interrupted 130 (Ctrl-C; the work done so far is saved).
#pragma once

#include <stdexcept>
#include <string>

namespace gpfd {

// What the three kinds share: a message and the place it concerns.
class Failure : public std::runtime_error {
 public:
  // `where` names the place: a file with line and column, a config key, a flag, a parameter.
  Failure(const std::string& what, std::string where = {})
      : std::runtime_error(what), where_(std::move(where)) {}

  const std::string& where() const { return where_; }

  // "what (where)", or just "what" when no place is known.
  std::string message() const {
    return where_.empty() ? std::string(what()) : std::string(what()) + " (" + where_ + ")";
  }

 private:
  std::string where_;
};

class InputError : public Failure {
 public:
  using Failure::Failure;
};

class NumericalError : public Failure {
 public:
  using Failure::Failure;
};

class Interrupted : public Failure {
 public:
  using Failure::Failure;
};

}  // namespace gpfd
