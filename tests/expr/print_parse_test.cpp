#include <gtest/gtest.h>

#include <bit>
#include <chrono>
#include <cstdint>
#include <utility>
#include <vector>

#include "gpfd/expr/parse.hpp"
#include "gpfd/expr/print.hpp"
#include "gpfd/util/error.hpp"
#include "test_genomes.hpp"

namespace gpfd::expr {
namespace {

const VariableNames kNames{"th1", "th2", "dth1", "dth2"};

TEST(Print, InfixUsesMinimalParentheses) {
  EXPECT_EQ(toInfix(parseInfix("(th1 + th2) * dth1", kNames), kNames), "(th1 + th2) * dth1");
  EXPECT_EQ(toInfix(parseInfix("th1 + th2 * dth1", kNames), kNames), "th1 + th2 * dth1");
  EXPECT_EQ(toInfix(parseInfix("(th1 - th2) - dth1", kNames), kNames), "th1 - th2 - dth1");
  EXPECT_EQ(toInfix(parseInfix("th1 - (th2 - dth1)", kNames), kNames), "th1 - (th2 - dth1)");
  EXPECT_EQ(toInfix(parseInfix("th1 / (th2 * 2)", kNames), kNames), "th1 / (th2 * 2)");
  EXPECT_EQ(toInfix(parseInfix("sin(th1 + 1) * -0.5", kNames), kNames), "sin(th1 + 1) * (-0.5)");
  EXPECT_EQ(toInfix(parseInfix("-th1", kNames), kNames), "neg(th1)");
  EXPECT_EQ(toInfix(parseInfix("absdiff(x[0], x[3])", kNames), kNames), "absdiff(th1, dth2)");
}

// The bit patterns of a tree's constants, in prefix order.
std::vector<std::uint64_t> constantBits(const Tree& tree) {
  std::vector<std::uint64_t> bits;
  for (const Node& n : tree) {
    if (n.op == Op::Const) bits.push_back(std::bit_cast<std::uint64_t>(n.value));
  }
  return bits;
}

// A negative constant right after an operator's symbol reads "x - (-0.139)", never "x - -0.139",
// and parses back to the same tree with bit-identical constants (-0 included).
TEST(Print, NegativeConstantsAfterAnOperatorAreParenthesised) {
  const auto c = [](double v) { return Node::constant(v); };
  const Node th1 = Node::variable(0), th2 = Node::variable(1);
  const auto node = [](Op op) { return Node::function(op); };
  const std::vector<std::pair<Tree, std::string>> cases{
      {{node(Op::Sub), th1, c(-0.139)}, "th1 - (-0.139)"},
      {{node(Op::Add), th1, c(-1e-300)}, "th1 + (-1e-300)"},
      {{node(Op::Mul), th1, c(-2.5)}, "th1 * (-2.5)"},
      {{node(Op::Div), th1, c(-0.0)}, "th1 / (-0)"},
      // The leftmost operand of a right operand follows the operator too.
      {{node(Op::Add), th1, node(Op::Mul), c(-2), th2}, "th1 + (-2) * th2"},
      // Where nothing precedes it, or a parenthesis or comma does, no parentheses are needed.
      {{node(Op::Mul), c(-2), th2}, "-2 * th2"},
      {{node(Op::Sub), th1, node(Op::Sub), c(-3), th2}, "th1 - (-3 - th2)"},
      {{node(Op::Max), c(-1.5), c(-0.25)}, "max(-1.5, -0.25)"},
      {{node(Op::Neg), c(-4)}, "neg(-4)"},
  };
  for (auto [tree, text] : cases) {
    recomputeLengths(tree);
    EXPECT_EQ(toInfix(tree, kNames), text);
    const Tree back = parseInfix(text, kNames);
    EXPECT_EQ(back, tree) << text;
    EXPECT_EQ(constantBits(back), constantBits(tree)) << text;
  }
}

TEST(Print, Sexpr) {
  EXPECT_EQ(toSexpr(parseInfix("sin(th1) * (th2 - 2)", kNames), kNames), "(* (sin th1) (- th2 2))");
  EXPECT_EQ(parseSexpr("(* (sin th1) (- th2 2))", kNames),
            parseInfix("sin(th1) * (th2 - 2)", kNames));
  EXPECT_EQ(parseSexpr("(max -1.5 x[2])", kNames), parseInfix("max(-1.5, dth1)", kNames));
}

TEST(Print, RoundTripOnRandomGenomes) {
  Rng rng(42);
  const auto space = testing::everyOperator(4);
  for (int i = 0; i < 3000; ++i) {
    const Genome g = gp::randomGenome(rng, space);
    for (std::size_t k = 0; k < g.featureCount(); ++k) {
      const Tree original(g.feature(k).begin(), g.feature(k).end());
      const std::string infix = toInfix(original, kNames);
      ASSERT_EQ(parseInfix(infix, kNames), original) << infix;
      const std::string sexpr = toSexpr(original, kNames);
      ASSERT_EQ(parseSexpr(sexpr, kNames), original) << sexpr;
    }
  }
}

// Expects parsing to fail with a message containing `what` at line 1, column `column`.
void expectError(const std::string& text, const std::string& what, int column, bool sexpr = false,
                 int maxDepth = kMaxParseDepth) {
  try {
    if (sexpr) {
      parseSexpr(text, kNames, {"f", 1}, maxDepth);
    } else {
      parseInfix(text, kNames, {"f", 1}, maxDepth);
    }
    FAIL() << "no error for: " << text;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.message();
    EXPECT_EQ(e.where(), "f:1:" + std::to_string(column)) << e.message();
  }
}

TEST(Parse, MalformedInputNamesTheErrorAndPlace) {
  expectError("th1 + frob(th2)", "unknown operator 'frob'", 7);
  expectError("th1 + omega", "unknown variable 'omega'", 7);
  expectError("sin(th1, th2)", "wrong arity", 1);
  expectError("max(th1)", "wrong arity", 1);
  expectError("th1 * x[4]", "variable index 4 out of range", 7);
  expectError("x[99999999999]", "out of range", 1);
  expectError("", "empty", 1);
  expectError("   ", "empty", 1);
  expectError("th1 +", "empty expression", 6);
  expectError("(th1 + th2", "expected ')'", 11);
  expectError("th1 th2", "unexpected text", 5);
  expectError("1e999", "number out of range", 1);
  expectError("2x", "malformed number", 1);
  expectError("sin(sin(sin(th1)))", "too deep", 1, false, 3);
  expectError(std::string(500, '(') + "th1" + std::string(500, ')'), "too deep", 129);
  expectError("(sin th1 th2)", "wrong arity", 2, true);
  expectError("(frob th1)", "unknown operator 'frob'", 2, true);
  expectError("(+ th1 x[7])", "out of range", 8, true);
  expectError("(+ th1", "expected ')'", 7, true);
  expectError("", "empty", 1, true);
}

// The limits docs/expressions.md states: a tree 64 levels deep, infix text nested 128 levels
// (parentheses that add no node count there, not in the tree).
TEST(Parse, TheDocumentedDepthAndNestingLimits) {
  ASSERT_EQ(kMaxParseDepth, 64);
  const auto nested = [](int calls) {
    std::string text = "th1";
    for (int i = 0; i < calls; ++i) text = "sin(" + text + ")";
    return text;
  };
  EXPECT_EQ(parseInfix(nested(63), kNames).size(), 64u);  // Depth 64.
  expectError(nested(64), "too deep: depth exceeds the limit of 64", 1);
  const auto parenthesised = [](int levels) {
    return std::string(static_cast<std::size_t>(levels), '(') + "th1" +
           std::string(static_cast<std::size_t>(levels), ')');
  };
  EXPECT_EQ(parseInfix(parenthesised(127), kNames).size(), 1u);
  expectError(parenthesised(128), "too deep: nesting exceeds the limit of 128", 129);
}

// "x op x op ... op x" with `terms` terms.
std::string flatChain(int terms, char op) {
  std::string text = "x";
  text.reserve(2 * static_cast<std::size_t>(terms));
  for (int i = 1; i < terms; ++i) (text += op) += 'x';
  return text;
}

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The input: 200,000 terms (400 KB) took 145 s before failing, as the parser copied the
// left tree at every operator and checked the limits only on the finished tree. The time bounds
// below are 1000 times what the parser takes, to catch that regression on a loaded machine.
TEST(Parse, LongFlatChainStopsAtTheFirstLimitCrossed) {
  const VariableNames names{"x"};
  for (char op : {'+', '-', '*', '/'}) {
    const std::string text = flatChain(200000, op);
    const auto start = std::chrono::steady_clock::now();
    try {
      parseInfix(text, names, {"f", 1});
      FAIL() << "accepted a 200,000-term chain";
    } catch (const InputError& e) {
      // The 64th operator makes the tree 65 deep: the error is there, at column 128.
      EXPECT_EQ(std::string(e.what()), "too deep: depth exceeds the limit of 64");
      EXPECT_EQ(e.where(), "f:1:128");
    }
    EXPECT_LT(secondsSince(start), 1.0) << op;
  }
  // The size limit, too, stops the parse where it is crossed.
  try {
    parseInfix(flatChain(200000, '+'), names, {"f", 1}, 1 << 20, 1000);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "too large: more than the limit of 1000 nodes");
    EXPECT_EQ(e.where(), "f:1:1000");  // The 500th operator: node 1001.
  }
}

TEST(Parse, FlatChainsParseInLinearTime) {
  // With limits that admit it, the 200,000-term chain parses (quadratic: minutes).
  const VariableNames names{"x"};
  const auto start = std::chrono::steady_clock::now();
  const Tree tree = parseInfix(flatChain(200000, '-'), names, {}, 1 << 20, 1 << 20);
  EXPECT_LT(secondsSince(start), 5.0);
  ASSERT_EQ(tree.size(), 399999u);
  EXPECT_EQ(tree[0].op, Op::Sub);
  EXPECT_EQ(tree[0].length, 399999u);
  EXPECT_EQ(tree[1].length, 399997u);  // Left-associative: ((x - x) - x) - ...
  EXPECT_EQ(tree[199999].op, Op::Var);
  EXPECT_EQ(toInfix(parseInfix("x - x - (x - x)", names), names), "x - x - (x - x)");
}

TEST(Parse, ErrorsCountLinesFromThePlace) {
  try {
    parseInfix("th1 +\n  bogus", kNames, {"file.features", 7});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "file.features:8:3");
  }
}

TEST(Parse, VariableNamedXStillParsesAsAName) {
  const VariableNames cartpole{"x", "dx", "th", "dth"};
  EXPECT_EQ(parseInfix("x * x[2]", cartpole), parseInfix("x * x[2]", cartpole));
  const Tree t = parseInfix("x + dx", cartpole);
  EXPECT_EQ(t[1].var, 0);
  EXPECT_EQ(toInfix(t, cartpole), "x + dx");
}

}  // namespace
}  // namespace gpfd::expr
