// expr: parsing of feature functions in infix and S-expression form. Every error is an InputError
// naming the place as <source>:<line>:<column>.
#pragma once

#include <string>
#include <string_view>

#include "gpfd/expr/genome.hpp"
#include "gpfd/expr/print.hpp"

namespace gpfd::expr {

// Where parsed text comes from, for error messages: a file name (or "<expr>") and the line of
// the text's first character.
struct SourcePlace {
  std::string name = "<expr>";
  int line = 1;
};

// Parses one infix feature. Variables are names from `names` or x[i] by index; an index must be
// below `names.size()` (the problem's variable count). The result must have depth <= maxDepth and
// at most maxSize nodes. Errors: unknown operator or variable, wrong arity, index out of range,
// too deep, too large, empty, malformed.
Tree parseInfix(std::string_view text, const VariableNames& names, const SourcePlace& place = {},
                int maxDepth = kMaxParseDepth, int maxSize = kMaxParseSize);
// The same for an S-expression such as (+ x (sin y)).
Tree parseSexpr(std::string_view text, const VariableNames& names, const SourcePlace& place = {},
                int maxDepth = kMaxParseDepth, int maxSize = kMaxParseSize);

}  // namespace gpfd::expr
