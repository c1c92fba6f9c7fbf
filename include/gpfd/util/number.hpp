// util: the one parser of numbers written as text (environment and learner parameters, command-line
// values, small result files), so that every place accepts the same inputs and reports the same
// errors. The whole text must be the number; whitespace around it is ignored.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace gpfd {

// A finite decimal number: "0.2", "+1e-5", "-3". Not "inf", "nan", "0x10", "1,5" or "".
// Throws InputError("'<text>' is not a finite number", where).
double parseNumber(std::string_view text, const std::string& where);
// The same, and within [lo, hi]: InputError("<name> must lie in [lo, hi], got <text>", where).
double parseNumber(std::string_view text, double lo, double hi, const std::string& name,
                   const std::string& where);

// A decimal integer: "12", "+3", "-1". Not "1.5", "1e3" or "". InputError(where) otherwise.
std::int64_t parseInteger(std::string_view text, const std::string& where);
// The same, and within [lo, hi]: InputError("<name> must lie in [lo, hi], got <text>", where).
std::int64_t parseInteger(std::string_view text, std::int64_t lo, std::int64_t hi,
                          const std::string& name, const std::string& where);

// A duration in seconds: a number of seconds ("90", "2.5"), or numbers each followed by h, m or s,
// largest unit first ("90s", "10m", "1h", "1h30m", "2.5m"). Positive and finite. Throws
// InputError("a duration is ..., not '<text>'", where) otherwise.
double parseDuration(std::string_view text, const std::string& where);

// The shortest text that parses back to exactly `value` ("0.2", "1e-05"), as defaults and
// resolved parameters are printed.
std::string numberText(double value);

}  // namespace gpfd
