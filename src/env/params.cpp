#include "gpfd/env/params.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <string_view>

#include "gpfd/util/error.hpp"

namespace gpfd::env {

std::string numberText(double value) { return fmt::format("{}", value); }

double parseFiniteNumber(const std::string& text, const std::string& where) {
  std::string_view view = text;
  while (!view.empty() && (view.front() == ' ' || view.front() == '\t')) view.remove_prefix(1);
  while (!view.empty() && (view.back() == ' ' || view.back() == '\t' || view.back() == '\r')) {
    view.remove_suffix(1);
  }
  if (!view.empty() && view.front() == '+') view.remove_prefix(1);
  double value = 0.0;
  const auto [end, ec] = std::from_chars(view.data(), view.data() + view.size(), value);
  if (view.empty() || ec != std::errc() || end != view.data() + view.size() ||
      !std::isfinite(value)) {
    throw InputError(fmt::format("'{}' is not a finite number", text), where);
  }
  return value;
}

const std::string* ParamReader::find(const std::string& name) const {
  const auto it = params_.find(name);
  return it == params_.end() ? nullptr : &it->second;
}

double ParamReader::real(const std::string& name, double fallback, double lo, double hi) const {
  const std::string* text = find(name);
  if (!text) return fallback;
  const double value = parseFiniteNumber(*text, where(name));
  if (value < lo || value > hi) {
    throw InputError(fmt::format("{} must lie in [{}, {}], got {}", name, lo, hi, value),
                     where(name));
  }
  return value;
}

double ParamReader::positive(const std::string& name, double fallback, double lo) const {
  const std::string* text = find(name);
  if (!text) return fallback;
  const double value = parseFiniteNumber(*text, where(name));
  if (!(value > lo)) {
    throw InputError(fmt::format("{} must be greater than {}, got {}", name, lo, value),
                     where(name));
  }
  return value;
}

int ParamReader::integer(const std::string& name, int fallback, int lo, int hi) const {
  const std::string* text = find(name);
  if (!text) return fallback;
  int value = 0;
  const char* first = text->data();
  const char* last = first + text->size();
  const auto [end, ec] = std::from_chars(first, last, value);
  if (text->empty() || ec != std::errc() || end != last) {
    throw InputError(fmt::format("{} must be an integer, got '{}'", name, *text), where(name));
  }
  if (value < lo || value > hi) {
    throw InputError(fmt::format("{} must lie in [{}, {}], got {}", name, lo, hi, value),
                     where(name));
  }
  return value;
}

std::string ParamReader::choice(const std::string& name, const std::string& fallback,
                                std::initializer_list<const char*> options) const {
  const std::string* text = find(name);
  if (!text) return fallback;
  for (const char* option : options) {
    if (*text == option) return *text;
  }
  throw InputError(
      fmt::format("{} must be one of {}, got '{}'", name, fmt::join(options, " | "), *text),
      where(name));
}

}  // namespace gpfd::env
