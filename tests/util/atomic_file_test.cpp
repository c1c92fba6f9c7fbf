// util/atomic_file.hpp: the names of writeFileAtomically's temporary files.
#include "gpfd/util/atomic_file.hpp"

#include <gtest/gtest.h>

namespace gpfd {
namespace {

TEST(AtomicFile, ItsTemporaryFilesAreRecognisedByName) {
  EXPECT_TRUE(isAtomicWriteTemporary("config.toml.tmp.20973"));
  EXPECT_TRUE(isAtomicWriteTemporary("front.csv.tmp.1"));
  EXPECT_FALSE(isAtomicWriteTemporary("config.toml"));
  EXPECT_FALSE(isAtomicWriteTemporary("notes.tmp."));
  EXPECT_FALSE(isAtomicWriteTemporary("notes.tmp.12x"));
  EXPECT_FALSE(isAtomicWriteTemporary(".tmp.12"));
  EXPECT_FALSE(isAtomicWriteTemporary("data.tmp"));
}

}  // namespace
}  // namespace gpfd
