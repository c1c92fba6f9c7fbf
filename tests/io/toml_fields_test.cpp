// TomlReader / TomlWriter / applyOverride / parseToml: typed reads with ranges, errors naming
// file:line:column and the key (with a suggestion), free-form parameter tables, and a written
// document that reads back the same.
#include "gpfd/io/toml_fields.hpp"

#include <gtest/gtest.h>

#include "gpfd/util/error.hpp"

namespace gpfd::io {
namespace {

// The InputError of `f`, or fails.
template <typename F>
InputError errorOf(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no InputError";
  return InputError("none");
}

TEST(TomlReader, ReadsTypedFieldsAndLeavesAbsentOnesAlone) {
  const auto root = parseToml(
      "name = \"x\"\n[gp]\npopulation = 40\nrate = 0.5\nflag = true\nlist = [1, 2.5]\n"
      "names = [\"a\", \"b\"]\n",
      "c.toml");
  TomlReader r(root, "c.toml");
  std::string name = "default", absent = "kept";
  int population = 0;
  double rate = 0.0;
  bool flag = false;
  std::vector<double> list;
  std::vector<std::string> names;
  r.read("", "name", name);
  r.read("", "absent", absent);
  r.read("gp", "population", population, 1, 100);
  r.read("gp", "rate", rate, 0.0, 1.0);
  r.read("gp", "flag", flag);
  r.read("gp", "list", list);
  r.read("gp", "names", names);
  EXPECT_NO_THROW(r.finish());
  EXPECT_EQ(name, "x");
  EXPECT_EQ(absent, "kept");
  EXPECT_EQ(population, 40);
  EXPECT_EQ(rate, 0.5);
  EXPECT_TRUE(flag);
  EXPECT_EQ(list, (std::vector<double>{1.0, 2.5}));
  EXPECT_EQ(names, (std::vector<std::string>{"a", "b"}));
}

TEST(TomlReader, ErrorsNameFileLineColumnAndKey) {
  const auto root = parseToml("[gp]\npopulation = 0\nrate = \"fast\"\n", "c.toml");
  TomlReader r(root, "c.toml");
  int population = 0;
  double rate = 0.0;
  const auto range = errorOf([&] { r.read("gp", "population", population, 1, 100); });
  EXPECT_NE(range.where().find("c.toml:2:"), std::string::npos) << range.where();
  EXPECT_NE(range.message().find("gp.population"), std::string::npos) << range.message();
  const auto type = errorOf([&] { r.read("gp", "rate", rate, 0.0, 1.0); });
  EXPECT_NE(type.where().find("c.toml:3:"), std::string::npos) << type.where();
  const auto syntax = errorOf([] { parseToml("a = [1,\n", "bad.toml"); });
  EXPECT_EQ(syntax.where().rfind("bad.toml:", 0), 0u) << syntax.where();
}

TEST(TomlReader, FinishRefusesUnknownKeysWithASuggestion) {
  const auto root = parseToml("[gp]\npopulaton = 40\n", "c.toml");
  TomlReader r(root, "c.toml");
  int population = 0;
  r.read("gp", "population", population, 1, 100);
  const auto e = errorOf([&] { r.finish(); });
  EXPECT_NE(e.message().find("population"), std::string::npos) << e.message();
  EXPECT_NE(e.message().find("popula"), std::string::npos);
}

TEST(TomlReader, ParameterTablesBecomeText) {
  const auto root =
      parseToml("[env]\nparams = { a = 1, b = 0.25, c = \"x\", d = true, e = [1, 2] }\n", "c");
  TomlReader r(root, "c");
  std::map<std::string, std::string> params;
  r.readParams("env.params", params);
  EXPECT_EQ(params, (std::map<std::string, std::string>{
                        {"a", "1"}, {"b", "0.25"}, {"c", "x"}, {"d", "true"}, {"e", "1,2"}}));
}

TEST(TomlWriter, WritesADocumentThatReadsBackTheSame) {
  TomlWriter w;
  w.write("", "name", std::string("run"));
  w.write("gp", "population", std::int64_t{40});
  w.write("gp", "rate", 0.1);
  w.write("gp", "flag", false);
  w.write("gp", "list", std::vector<double>{1.0, 0.5});
  w.write("", "files", std::vector<std::string>{"a.so"});
  w.writeParams("env.params", {{"k", "v"}});
  const auto root = parseToml(w.text(), "written");
  TomlReader r(root, "written");
  std::string name;
  int population = 0;
  double rate = 0.0;
  bool flag = true;
  std::vector<double> list;
  std::vector<std::string> files;
  std::map<std::string, std::string> params;
  r.read("", "name", name);
  r.read("gp", "population", population, 0, 100);
  r.read("gp", "rate", rate, 0.0, 1.0);
  r.read("gp", "flag", flag);
  r.read("gp", "list", list);
  r.read("", "files", files);
  r.readParams("env.params", params);
  EXPECT_NO_THROW(r.finish());
  EXPECT_EQ(name, "run");
  EXPECT_EQ(population, 40);
  EXPECT_EQ(rate, 0.1);
  EXPECT_FALSE(flag);
  EXPECT_EQ(list, (std::vector<double>{1.0, 0.5}));
  EXPECT_EQ(files, (std::vector<std::string>{"a.so"}));
  EXPECT_EQ(params.at("k"), "v");
}

TEST(ApplyOverride, SetsTypedValuesAndCreatesTables) {
  auto root = parseToml("[gp]\npopulation = 40\n", "c");
  applyOverride(root, "gp.population=50");
  applyOverride(root, "env.name=acrobot");  // Not TOML: taken as a string.
  applyOverride(root, "fitness.rate=0.5");
  EXPECT_EQ(root["gp"]["population"].value<std::int64_t>(), 50);
  EXPECT_EQ(root["env"]["name"].value<std::string>(), "acrobot");
  EXPECT_EQ(root["fitness"]["rate"].value<double>(), 0.5);
  EXPECT_EQ(errorOf([&] { applyOverride(root, "novalue"); }).where(), "--set novalue");
  EXPECT_THROW(applyOverride(root, "gp.population.x=1"), InputError);
}

}  // namespace
}  // namespace gpfd::io
