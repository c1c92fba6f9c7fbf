#include "validators.hpp"

#include <fmt/format.h>
#include <tbb/info.h>
#include <unistd.h>

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

int threads(int requested) {
  const int cores = tbb::info::default_concurrency();
  if (requested <= cores) return requested;
  static bool told = false;
  if (!told) {
    std::fprintf(stderr, "note: --threads %d is more than the %d cores available; using %d\n",
                 requested, cores, cores);
    told = true;
  }
  return cores;
}

void requireMemory(double bytes, const std::string& what, const std::string& where) {
  const double machine =
      static_cast<double>(::sysconf(_SC_PHYS_PAGES)) * static_cast<double>(::sysconf(_SC_PAGESIZE));
  if (machine > 0 && bytes > machine) {
    constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;
    throw InputError(fmt::format("{} would need about {:.0f} GiB of memory, more than this "
                                 "machine's {:.0f} GiB",
                                 what, bytes / kGiB, machine / kGiB),
                     where);
  }
}

}  // namespace gpfd::app
