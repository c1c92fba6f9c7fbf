#include "gpfd/expr/features_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>

#include "gpfd/expr/parse.hpp"
#include "gpfd/util/atomic_file.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::expr {
namespace {

const VariableNames kAcrobot{"th1", "th2", "dth1", "dth2"};

std::string errorOf(const std::string& text, const VariableNames& vars = kAcrobot,
                    const std::string& env = "acrobot") {
  try {
    parseFeaturesFile(text, "f.features", vars, env);
  } catch (const InputError& e) {
    return e.message();
  }
  return "no error";
}

TEST(FeaturesFile, WriteThenReadGivesTheSameGenome) {
  FeaturesFile file;
  file.env = "acrobot";
  file.variables = kAcrobot;
  file.meta["fitness"] = "-123.5";
  file.genome.addFeature(parseInfix("sin(th1) * dth2", kAcrobot));
  file.genome.addFeature(parseInfix("th2 - -0.25", kAcrobot));
  for (auto format : {TextFormat::Infix, TextFormat::Sexpr}) {
    file.format = format;
    const std::string path = ::testing::TempDir() + "/roundtrip.features";
    writeFeaturesFile(path, file);
    const auto back = readFeaturesFile(path, kAcrobot, "acrobot");
    EXPECT_EQ(back.genome, file.genome);
    EXPECT_EQ(back.env, "acrobot");
    EXPECT_EQ(back.meta.at("fitness"), "-123.5");
  }
}

TEST(FeaturesFile, ErrorsNameLineAndColumn) {
  EXPECT_EQ(errorOf("# env: acrobot\n\nth1 + 1\nth1 * bad\n"),
            "unknown variable 'bad' (variables: th1 th2 dth1 dth2) (f.features:4:7)");
  EXPECT_EQ(errorOf("cos(th1, th2)\n"),
            "wrong arity: 'cos' takes 1 argument, got 2 (f.features:1:1)");
  EXPECT_EQ(errorOf("# comment only\n"), "empty: no features in the file (f.features)");
  EXPECT_EQ(errorOf("# env: tetris\nth1\n"),
            "features file is for env 'tetris', not 'acrobot' (f.features)");
  EXPECT_NE(errorOf("# variables: a, b\na\n").find("differ from the environment's"),
            std::string::npos);
  EXPECT_NE(errorOf("x\n", {}, "").find("no '# variables:' line"), std::string::npos);
  EXPECT_NE(errorOf("# format: json\nth1\n").find("f.features:1"), std::string::npos);
}

TEST(FeaturesFile, SexprFormatLine) {
  const auto f = parseFeaturesFile("# format: sexpr\n(+ th1 (sin th2))\n", "f", kAcrobot);
  EXPECT_EQ(f.genome.feature(0).size(), 4u);
}

TEST(FeaturesFile, UnwritablePathIsAnInputError) {
  FeaturesFile file;
  file.variables = kAcrobot;
  file.genome.addFeature(parseInfix("th1", kAcrobot));
  EXPECT_THROW(writeFeaturesFile("/nonexistent-dir/x.features", file), InputError);
  EXPECT_THROW(readFeaturesFile("/nonexistent-dir/x.features"), InputError);
}

}  // namespace
}  // namespace gpfd::expr
