// expr: the features file, the text format in which gpfd reads and writes feature sets.
//
//   # gpfd features 1
//   # env: acrobot
//   # variables: th1, th2, dth1, dth2
//   # format: infix
//   sin(th1) * dth2
//   th2 - 0.5
//
// One feature per non-comment line, in infix (default) or S-expression form as `format` says.
// Lines starting with '#' are comments; `# key: value` comments carry metadata (env, variables,
// format, and any others, kept in `meta`). Variables are referred to by name or as x[i].
#pragma once

#include <map>
#include <string>
#include <vector>

#include "gpfd/expr/genome.hpp"
#include "gpfd/expr/print.hpp"

namespace gpfd::expr {

enum class TextFormat { Infix, Sexpr };

struct FeaturesFile {
  std::string env;          // The environment the features are for ("" if not stated).
  VariableNames variables;  // The problem's state variables, in index order.
  TextFormat format = TextFormat::Infix;
  std::map<std::string, std::string> meta;  // Other `# key: value` lines.
  Genome genome;
};

// Parses a features file's text. `expectedEnv` and `expectedVariables`, when not empty, are the
// problem the features must be for: a file stating another env or other variables is refused.
// Without a `variables` line the expected variables are used; with neither, an error. Errors are
// InputErrors at <sourceName>:<line>:<column>.
FeaturesFile parseFeaturesFile(const std::string& text, const std::string& sourceName,
                               const VariableNames& expectedVariables = {},
                               const std::string& expectedEnv = {});
FeaturesFile readFeaturesFile(const std::string& path, const VariableNames& expectedVariables = {},
                              const std::string& expectedEnv = {});

std::string formatFeaturesFile(const FeaturesFile& file);
// Writes atomically (never leaves a half-written file).
void writeFeaturesFile(const std::string& path, const FeaturesFile& file);

TextFormat parseTextFormat(const std::string& name);  // "infix" | "sexpr"; InputError otherwise.

}  // namespace gpfd::expr
