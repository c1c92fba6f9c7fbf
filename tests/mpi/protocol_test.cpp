// The MPI Task message carries the genome in the one wire format (gpfd/expr/wire.hpp): what the
// master's Writer puts is the record the Python workers read, and the reverse.
#ifdef GPFD_TEST_HAVE_MPI
#include "../../src/mpi/protocol.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>

#include "../expr/test_genomes.hpp"
#include "gpfd/expr/wire.hpp"
#include "gpfd/gp/init.hpp"

namespace gpfd::mpi {
namespace {

TEST(MpiProtocol, TaskCarriesTheWireRecord) {
  Rng rng(35);
  const auto space = expr::testing::everyOperator(4);
  for (int i = 0; i < 100; ++i) {
    const expr::Genome genome = gp::randomGenome(rng, space);
    const auto message =
        protocol::Writer().put(std::uint64_t{7}).put(std::uint64_t{99}).putGenome(genome).take();
    const std::string record = expr::wire::encodeGenome(genome);
    ASSERT_EQ(message.size(), 16 + record.size());
    EXPECT_EQ(std::string(message.begin() + 16, message.end()), record);
    // A record written by the Python side's encoder reads back through the MPI Reader.
    const std::string framed = std::string(16, '\0') + record;
    const std::vector<char> bytes(framed.begin(), framed.end());
    protocol::Reader reader(bytes);
    reader.get<std::uint64_t>();
    reader.get<std::uint64_t>();
    EXPECT_EQ(reader.getGenome(4), genome);
  }
}

TEST(MpiProtocol, ATruncatedTaskIsAWireError) {
  const auto message = protocol::Writer()
                           .put(std::uint64_t{7})
                           .putGenome(expr::Genome::fromFeatures({{expr::Node::variable(1)}}))
                           .take();
  for (std::size_t n = 8; n < message.size(); ++n) {
    const std::vector<char> cut(message.begin(), message.begin() + static_cast<long>(n));
    protocol::Reader reader(cut);
    reader.get<std::uint64_t>();
    EXPECT_THROW(reader.getGenome(2), expr::wire::WireError) << n;
  }
}

}  // namespace
}  // namespace gpfd::mpi
#endif
