#include "gpfd/util/number.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>

#include "gpfd/util/error.hpp"

namespace gpfd {
namespace {

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

// The text without surrounding whitespace and without one leading '+' (from_chars takes none).
std::string_view core(std::string_view text) {
  while (!text.empty() && isSpace(text.front())) text.remove_prefix(1);
  while (!text.empty() && isSpace(text.back())) text.remove_suffix(1);
  if (text.size() > 1 && text.front() == '+' && text[1] != '-') text.remove_prefix(1);
  return text;
}

template <typename T>
bool parseWhole(std::string_view text, T& value) {
  const std::string_view view = core(text);
  const char* last = view.data() + view.size();
  const auto [end, ec] = std::from_chars(view.data(), last, value);
  return !view.empty() && ec == std::errc() && end == last;
}

}  // namespace

double parseNumber(std::string_view text, const std::string& where) {
  double value = 0.0;
  if (!parseWhole(text, value) || !std::isfinite(value)) {
    throw InputError(fmt::format("'{}' is not a finite number", text), where);
  }
  return value;
}

double parseNumber(std::string_view text, double lo, double hi, const std::string& name,
                   const std::string& where) {
  const double value = parseNumber(text, where);
  if (value < lo || value > hi) {
    throw InputError(fmt::format("{} must lie in [{}, {}], got {}", name, lo, hi, text), where);
  }
  return value;
}

std::int64_t parseInteger(std::string_view text, const std::string& where) {
  std::int64_t value = 0;
  if (!parseWhole(text, value)) {
    throw InputError(fmt::format("'{}' is not an integer", text), where);
  }
  return value;
}

std::int64_t parseInteger(std::string_view text, std::int64_t lo, std::int64_t hi,
                          const std::string& name, const std::string& where) {
  const std::int64_t value = parseInteger(text, where);
  if (value < lo || value > hi) {
    throw InputError(fmt::format("{} must lie in [{}, {}], got {}", name, lo, hi, text), where);
  }
  return value;
}

double parseDuration(std::string_view text, const std::string& where) {
  const auto refuse = [&] {
    throw InputError(fmt::format("a duration is seconds (90) or numbers with h, m or s, largest "
                                 "unit first (90s, 10m, 1h30m), above 0, not '{}'",
                                 text),
                     where);
  };
  const auto first = text.find_first_not_of(" \t"), last = text.find_last_not_of(" \t");
  if (first == std::string_view::npos) refuse();
  const std::string_view body = text.substr(first, last - first + 1);
  double seconds = 0.0;
  if (body.find_first_of("hms") == std::string_view::npos) {
    try {
      seconds = parseNumber(body, where);
    } catch (const InputError&) {
      refuse();
    }
  } else {
    constexpr std::string_view kUnits = "hms";
    constexpr double kSeconds[] = {3600.0, 60.0, 1.0};
    std::size_t at = 0, nextUnit = 0;
    while (at < body.size()) {
      const std::size_t unit = body.find_first_of(kUnits, at);
      if (unit == std::string_view::npos || unit == at) refuse();
      const std::size_t index = kUnits.find(body[unit]);
      if (index < nextUnit) refuse();  // Largest unit first, each once.
      double part = -1.0;
      try {
        part = parseNumber(body.substr(at, unit - at), where);
      } catch (const InputError&) {
        refuse();
      }
      if (part < 0.0) refuse();
      seconds += part * kSeconds[index];
      nextUnit = index + 1;
      at = unit + 1;
    }
  }
  if (!(seconds > 0.0) || !std::isfinite(seconds)) refuse();
  return seconds;
}

std::string numberText(double value) { return fmt::format("{}", value); }

}  // namespace gpfd
