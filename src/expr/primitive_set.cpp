#include "gpfd/expr/primitive_set.hpp"

#include <algorithm>

#include "gpfd/util/error.hpp"

namespace gpfd::expr {

std::optional<Op> opFromName(std::string_view name) {
  for (int i = 0; i < kOpCount; ++i) {
    const Op op = static_cast<Op>(i);
    if (isTerminal(op)) continue;
    if (info(op).name == name || info(op).sexpr == name) return op;
  }
  return std::nullopt;
}

PrimitiveSet PrimitiveSet::named(const std::string& spec) {
  PrimitiveSet set;
  set.name = spec;
  if (spec == "control") {
    set.functions = {Op::Add, Op::Sub, Op::Mul, Op::Div, Op::Sin, Op::Cos, Op::Sqrt};
  } else if (spec == "tetris") {
    set.functions = {Op::Add, Op::Sub, Op::Mul, Op::Div, Op::Min, Op::Max, Op::AbsDiff};
  } else if (spec == "arithmetic") {
    set.functions = {Op::Add, Op::Sub, Op::Mul, Op::Div};
  } else if (spec == "all") {
    for (int i = 0; i < kOpCount; ++i) {
      if (!isTerminal(static_cast<Op>(i))) set.functions.push_back(static_cast<Op>(i));
    }
  } else {
    std::size_t begin = 0;
    while (begin <= spec.size()) {
      std::size_t end = spec.find(',', begin);
      if (end == std::string::npos) end = spec.size();
      std::string token = spec.substr(begin, end - begin);
      token.erase(0, token.find_first_not_of(" \t"));
      token.erase(token.find_last_not_of(" \t") + 1);
      auto op = opFromName(token);
      if (!op) {
        throw InputError("unknown primitive set or operator '" + token +
                             "' (sets: control, tetris, arithmetic, all; or a list such as "
                             "'+,-,*,sin')",
                         "primitive set '" + spec + "'");
      }
      if (!set.contains(*op)) set.functions.push_back(*op);
      begin = end + 1;
    }
  }
  return set;
}

bool PrimitiveSet::contains(Op op) const {
  return std::find(functions.begin(), functions.end(), op) != functions.end();
}

std::vector<Op> PrimitiveSet::functionsOfArity(int a) const {
  std::vector<Op> out;
  for (Op op : functions) {
    if (arity(op) == a) out.push_back(op);
  }
  return out;
}

}  // namespace gpfd::expr
