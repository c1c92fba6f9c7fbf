// env: reading an environment's text parameters (`k=v`) into typed values, with errors that name
// the environment and the parameter.
#pragma once

#include <initializer_list>
#include <string>

#include "gpfd/env/environment.hpp"

namespace gpfd::env {

// Reads typed values from Params. Every getter returns the default when the name is absent and
// throws InputError (where = "<env>.<name>") on text that is not a valid value. Registry::make has
// already rejected unknown names.
class ParamReader {
 public:
  ParamReader(std::string envName, const Params& params)
      : env_(std::move(envName)), params_(params) {}

  // A finite number in [lo, hi].
  double real(const std::string& name, double fallback, double lo, double hi) const;
  // A finite number strictly above `lo` (lengths, intervals, masses).
  double positive(const std::string& name, double fallback, double lo = 0.0) const;
  // An integer in [lo, hi].
  int integer(const std::string& name, int fallback, int lo, int hi) const;
  // One of `options`.
  std::string choice(const std::string& name, const std::string& fallback,
                     std::initializer_list<const char*> options) const;

 private:
  const std::string* find(const std::string& name) const;
  std::string where(const std::string& name) const { return env_ + "." + name; }

  std::string env_;
  const Params& params_;
};

// Shortest round-trip text of a number ("0.2", "1e-05"), the form defaults and params() use.
std::string numberText(double value);

// Parses a finite number; the whole text must be the number. Throws InputError(where) otherwise.
double parseFiniteNumber(const std::string& text, const std::string& where);

}  // namespace gpfd::env
