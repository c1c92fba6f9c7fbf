// expr: the one wire format of a genome, shared by every process that sends genomes to another
// (the MPI master and workers, src/mpi/protocol.hpp; the Python worker processes,
// python/src/python_evaluator.cpp and trial_runner.cpp). Exact to the bit: decode(encode(g))
// == g, every node field included, whatever the machine (all numbers little-endian).
//
// Version 1, one record per genome:
//   'g' 'w'        magic
//   u8             version (kWireVersion)
//   u32            feature count (0 allowed)
//   per feature:   u32 node count (1 .. kMaxParseSize), then its nodes in prefix order:
//     u8           op code (low 6 bits) | 0x40 when a u16 var follows | 0x80 when a f64 follows
//     [u16 var]    Node::var, present when not 0
//     [u64 value]  the bits of Node::value, present when not all zero (-0.0 is sent)
// Node::length is not sent: it follows from the arities (recomputeLengths).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "gpfd/expr/genome.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::expr::wire {

inline constexpr std::uint8_t kWireVersion = 1;

// Bytes that are not one well-formed record of this version: truncated, corrupt, another
// version (the message names both), or a genome invalid over the receiver's variables.
class WireError : public InputError {
 public:
  explicit WireError(const std::string& what) : InputError(what, "genome wire format") {}
};

// Appends the record of `genome` to `out`.
void appendGenome(std::string& out, const Genome& genome);
std::string encodeGenome(const Genome& genome);

// The features of the record at bytes[at...], structurally well-formed prefix trees (lengths
// set), constants and variable indices unchecked; `at` moves past the record. WireError when
// the bytes are not one record of this version.
std::vector<Tree> readTrees(std::string_view bytes, std::size_t& at);
// readTrees, each tree also checked (checkTree) over `variableCount` variables.
Genome readGenome(std::string_view bytes, std::size_t& at, int variableCount);
// The genome of `bytes`, which must hold exactly one record.
Genome decodeGenome(std::string_view bytes, int variableCount);

}  // namespace gpfd::expr::wire
