// ParamTable: one declaration reads text parameters (ranges, choices, flags, custom values,
// rules), writes them back, and lists them with defaults and ranges.
#include "gpfd/util/params.hpp"

#include <gtest/gtest.h>

namespace gpfd {
namespace {

enum class Mode { Fast, Exact };

struct Settings {
  double rate = 0.5;
  int count = 3;
  bool on = true;
  Mode mode = Mode::Fast;
  std::string tag = "none";

  static const ParamTable<Settings>& table() {
    static const auto table =
        ParamTable<Settings>("thing")
            .real(
                "rate", [](auto& c) -> auto& { return c.rate; }, 0.0, 1.0, "a rate")
            .integer(
                "count", [](auto& c) -> auto& { return c.count; }, 1, 10, "a count")
            .flag(
                "on", [](auto& c) -> auto& { return c.on; }, "a switch")
            .choice(
                "mode", [](auto& c) -> auto& { return c.mode; },
                std::vector<std::pair<std::string, Mode>>{{"fast", Mode::Fast},
                                                          {"exact", Mode::Exact}},
                "a mode")
            .custom(
                "tag", "a word", "a custom value",
                [](Settings& c, const std::string& text, const std::string& where) {
                  if (text.find(' ') != std::string::npos) throw InputError("one word", where);
                  c.tag = text;
                },
                [](const Settings& c) { return c.tag; })
            .rule(
                "count", [](const Settings& c) { return c.count * c.rate <= 4.0; },
                "count * rate must be at most 4");
    return table;
  }
};

std::string whereOf(const Params& params) {
  try {
    Settings::table().read(params);
  } catch (const InputError& e) {
    return e.where() + ": " + e.what();
  }
  return "accepted";
}

TEST(ParamTable, ReadsEveryKindOverTheDefaults) {
  const Settings s = Settings::table().read(
      {{"rate", "0.25"}, {"count", "7"}, {"on", "no"}, {"mode", "exact"}, {"tag", "x"}});
  EXPECT_EQ(s.rate, 0.25);
  EXPECT_EQ(s.count, 7);
  EXPECT_FALSE(s.on);
  EXPECT_EQ(s.mode, Mode::Exact);
  EXPECT_EQ(s.tag, "x");
  const Settings d = Settings::table().read({});
  EXPECT_EQ(d.rate, 0.5);
  EXPECT_EQ(d.mode, Mode::Fast);
}

TEST(ParamTable, RefusesBadValuesUnknownNamesAndBrokenRules) {
  EXPECT_EQ(whereOf({{"rate", "2"}}), "thing.rate: rate must lie in [0, 1], got 2");
  EXPECT_EQ(whereOf({{"count", "2.5"}}), "thing.count: '2.5' is not an integer");
  EXPECT_EQ(whereOf({{"on", "maybe"}}), "thing.on: 'maybe' is not a boolean (true | false)");
  EXPECT_EQ(whereOf({{"mode", "slow"}}),
            "thing.mode: mode must be one of fast | exact, got 'slow'");
  EXPECT_EQ(whereOf({{"tag", "two words"}}), "thing.tag: one word");
  EXPECT_EQ(whereOf({{"colour", "red"}}),
            "thing.colour: thing has no parameter 'colour' (it takes: rate, count, on, mode, tag)");
  EXPECT_EQ(whereOf({{"count", "10"}, {"rate", "0.5"}}),
            "thing.count: count * rate must be at most 4");
  EXPECT_EQ(whereOf({{"count", "10"}, {"rate", "0.4"}}), "accepted");
}

TEST(ParamTable, WritesTextThatReadsBackAndListsDefaultsAndRanges) {
  Settings s;
  s.rate = 0.1;
  s.mode = Mode::Exact;
  s.on = false;
  const Params text = Settings::table().write(s);
  EXPECT_EQ(
      text,
      (Params{
          {"rate", "0.1"}, {"count", "3"}, {"on", "false"}, {"mode", "exact"}, {"tag", "none"}}));
  EXPECT_EQ(Settings::table().write(Settings::table().read(text)), text);
  const auto specs = Settings::table().specs();
  ASSERT_EQ(specs.size(), 5u);
  EXPECT_EQ(specs[0].name, "rate");
  EXPECT_EQ(specs[0].defaultValue, "0.5");
  EXPECT_EQ(specs[0].range, "[0, 1]");
  EXPECT_EQ(specs[2].range, "true | false");
  EXPECT_EQ(specs[3].range, "fast | exact");
  EXPECT_EQ(specs[4].range, "a word");
  EXPECT_EQ(paramNames(specs), Settings::table().names());
}

}  // namespace
}  // namespace gpfd
