// libFuzzer harness for the genome wire format (gpfd/expr/wire.hpp): any bytes either decode, or
// fail with a WireError, never reading past their end (ASan); bytes that decode are the record
// of what they decode to (the format is canonical). Seed: tests/data/wire/genome-v1.bin.
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "gpfd/expr/wire.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  try {
    const auto genome = gpfd::expr::wire::decodeGenome(bytes, 3);
    if (gpfd::expr::wire::encodeGenome(genome) != bytes) std::abort();
  } catch (const gpfd::expr::wire::WireError&) {
  }
  return 0;
}
