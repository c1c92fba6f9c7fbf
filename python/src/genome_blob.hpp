// python: a genome as bytes, exact to the bit, to send it to the worker processes that evaluate
// fitness on environments stepped in Python.
#pragma once

#include <string>
#include <string_view>

#include "gpfd/expr/genome.hpp"

namespace gpfd::python {

// Per feature: its node count (u32), then per node op (u8), var (u16), value (f64).
std::string packGenome(const expr::Genome& genome);
// The genome back; InputError unless the bytes hold well-formed trees over `variableCount`
// variables.
expr::Genome unpackGenome(std::string_view bytes, int variableCount);

}  // namespace gpfd::python
