// util: the exception for bad input (command line, config, feature files, parameters). It is
// caught once in main and printed as `error: <what> (<where>)` with a non-zero exit code.
#pragma once

#include <stdexcept>
#include <string>

namespace gpfd {

class InputError : public std::runtime_error {
 public:
  // `where` names the place: a file with line and column, a config key, a flag, a parameter.
  InputError(const std::string& what, std::string where = {})
      : std::runtime_error(what), where_(std::move(where)) {}

  const std::string& where() const { return where_; }

  // "what (where)", or just "what" when no place is known.
  std::string message() const {
    return where_.empty() ? std::string(what()) : std::string(what()) + " (" + where_ + ")";
  }

 private:
  std::string where_;
};

}  // namespace gpfd
