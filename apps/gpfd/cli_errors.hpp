// CLI11's parse errors in gpfd's style: `<what> (<where>)`, where names the command (and the
// flag), with a did-you-mean for a misspelt command or flag.
#pragma once

#include <CLI/CLI.hpp>

#include "gpfd/util/error.hpp"

namespace gpfd::app {

// The error to report for `error`, raised while `root` parsed the command line. Not for
// CLI::Success (help, version), which CLI11 prints itself.
InputError describeParseError(const CLI::App& root, const CLI::ParseError& error);

}  // namespace gpfd::app
