#include "validators.hpp"

#include <fmt/format.h>

#include <cstdint>
#include <cstdio>

#include "gpfd/env/environment.hpp"
#include "gpfd/io/suggest.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::app {
namespace {

std::string joined(const std::vector<std::string>& names) {
  return fmt::format("{}", fmt::join(names, ", "));
}

}  // namespace

CLI::Validator bounded(long long lo, long long hi) {
  return CLI::Validator(
      [lo, hi](std::string& text) -> std::string {
        long long value = 0;
        const char* end = text.data() + text.size();
        const auto [stop, error] = std::from_chars(text.data(), end, value);
        if (stop != end || (error != std::errc() && error != std::errc::result_out_of_range)) {
          return fmt::format("'{}' is not an integer", text);
        }
        if (error == std::errc::result_out_of_range || value < lo || value > hi) {
          return fmt::format("{} is outside [{}, {}]", text, lo, hi);
        }
        return {};
      },
      fmt::format("in [{}, {}]", lo, hi));
}

CLI::Validator seedValue() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        std::uint64_t value = 0;
        const char* end = text.data() + text.size();
        const auto [stop, error] = std::from_chars(text.data(), end, value);
        if (stop != end || error != std::errc()) {
          return fmt::format("'{}' is not a seed (an integer in [0, {}])", text, UINT64_MAX);
        }
        return {};
      },
      "");
}

CLI::Validator oneOf(std::vector<std::string> choices) {
  const std::string list = joined(choices);
  return CLI::Validator(
      [choices = std::move(choices), list](std::string& text) -> std::string {
        for (const auto& c : choices) {
          if (c == text) return {};
        }
        return fmt::format("'{}' is not one of {}{}", text, list, io::didYouMean(text, choices));
      },
      "");
}

CLI::Validator environmentName() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        const auto names = env::Registry::global().names();
        for (const auto& n : names) {
          if (n == text) return {};
        }
        return fmt::format("unknown environment '{}'{} (known: {})", text,
                           io::didYouMean(text, names), joined(names));
      },
      "");
}

}  // namespace gpfd::app
