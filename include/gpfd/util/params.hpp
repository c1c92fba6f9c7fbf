// util: parameters given as text `name=value` (command line, configs), declared once per owner (an
// environment, a learner) in a ParamTable: one declaration that reads them into a plain config
// struct, checks their ranges, writes them back as text, and lists them for `gpfd envs`,
// `gpfd learners` and --help.
#pragma once

#include <fmt/format.h>

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "gpfd/util/error.hpp"
#include "gpfd/util/number.hpp"

namespace gpfd {

// Parameter values by name, as text.
using Params = std::map<std::string, std::string>;

// One declared parameter, as listed to users.
struct ParamSpec {
  // What a value is, for fronts that give typed values (Python): a number, a whole number, a flag,
  // or text (a choice of names, anything custom).
  enum class Type { Text, Real, Integer, Flag };

  std::string name;
  std::string defaultValue;  // As text, in the form that params() and configs use.
  std::string range;         // The values it takes: "[0.0001, 1]", "book | nips", "true | false".
  std::string meaning;
  Type type = Type::Text;
};

// "true" | "1" | "on" | "yes" and "false" | "0" | "off" | "no"; InputError(where) otherwise.
bool parseFlag(const std::string& text, const std::string& where);

// The names of declared parameters.
std::vector<std::string> paramNames(const std::vector<ParamSpec>& specs);
// InputError("<owner> has no parameter '<key>' (it takes: ...)", "<owner>.<key>") for the first
// key of `params` that is not one of `names`.
void checkParamNames(const std::string& owner, const std::vector<std::string>& names,
                     const Params& params);

template <typename Config>
class ParamTable {
 public:
  // Sets a field from text, throwing InputError(where) for a value it cannot take.
  using Parse = std::function<void(Config&, const std::string& text, const std::string& where)>;
  using Print = std::function<std::string(const Config&)>;

  // `owner` names the parameters in errors: where = "<owner>.<name>".
  explicit ParamTable(std::string owner) : owner_(std::move(owner)) {}

  // Each declaration takes a `field`: a generic lambda that returns the member it declares, for a
  // config and a const one alike: [](auto& c) -> auto& { return c.dt; }.
  // A finite number in [lo, hi].
  template <typename Field>
  ParamTable& real(std::string name, Field field, double lo, double hi, std::string meaning) {
    return custom(
        name, fmt::format("[{}, {}]", lo, hi), std::move(meaning),
        [field, lo, hi, name](Config& c, const std::string& text, const std::string& where) {
          field(c) = parseNumber(text, lo, hi, name, where);
        },
        [field](const Config& c) { return numberText(field(c)); }, ParamSpec::Type::Real);
  }
  // An integer in [lo, hi].
  template <typename Field>
  ParamTable& integer(std::string name, Field field, std::int64_t lo, std::int64_t hi,
                      std::string meaning) {
    return custom(
        name, fmt::format("[{}, {}]", lo, hi), std::move(meaning),
        [field, lo, hi, name](Config& c, const std::string& text, const std::string& where) {
          using T = std::remove_reference_t<decltype(field(c))>;
          field(c) = static_cast<T>(parseInteger(text, lo, hi, name, where));
        },
        [field](const Config& c) { return std::to_string(field(c)); }, ParamSpec::Type::Integer);
  }
  // true or false.
  template <typename Field>
  ParamTable& flag(std::string name, Field field, std::string meaning) {
    return custom(
        std::move(name), "true | false", std::move(meaning),
        [field](Config& c, const std::string& text, const std::string& where) {
          field(c) = parseFlag(text, where);
        },
        [field](const Config& c) { return std::string(field(c) ? "true" : "false"); },
        ParamSpec::Type::Flag);
  }
  // One of named values, e.g. {{"book", Dynamics::Book}, {"nips", Dynamics::Nips}}.
  template <typename Field, typename Value>
  ParamTable& choice(std::string name, Field field,
                     std::vector<std::pair<std::string, Value>> options, std::string meaning) {
    std::string range;
    for (const auto& [text, value] : options) range += (range.empty() ? "" : " | ") + text;
    return custom(
        name, range, std::move(meaning),
        [field, options, range, name](Config& c, const std::string& text,
                                      const std::string& where) {
          for (const auto& [option, value] : options) {
            if (text == option) {
              field(c) = value;
              return;
            }
          }
          throw InputError(fmt::format("{} must be one of {}, got '{}'", name, range, text), where);
        },
        [field, options](const Config& c) {
          for (const auto& [option, value] : options) {
            if (field(c) == value) return option;
          }
          return std::string("?");
        });
  }
  // Anything else: `parse` sets the field from text, `print` writes it back; `range` says what it
  // takes, `type` what its values are.
  ParamTable& custom(std::string name, std::string range, std::string meaning, Parse parse,
                     Print print, ParamSpec::Type type = ParamSpec::Type::Text) {
    entries_.push_back({std::move(name), std::move(range), std::move(meaning), std::move(parse),
                        std::move(print), type});
    return *this;
  }
  // A rule over several parameters, checked after all are read: InputError(what,
  // "<owner>.<name>") when `holds` is false.
  ParamTable& rule(std::string name, std::function<bool(const Config&)> holds, std::string what) {
    rules_.push_back({std::move(name), std::move(holds), std::move(what)});
    return *this;
  }

  // Config{} with `params` applied and the rules checked. InputError for an unknown name (listing
  // the declared ones), a value out of range, or a broken rule.
  Config read(const Params& params) const {
    checkParamNames(owner_, names(), params);
    Config config;
    for (const auto& [name, value] : params) apply(config, name, value);
    check(config);
    return config;
  }
  // Applies one parameter; false when `name` is not declared.
  bool apply(Config& config, const std::string& name, const std::string& value) const {
    for (const auto& e : entries_) {
      if (e.name == name) {
        e.parse(config, value, where(name));
        return true;
      }
    }
    return false;
  }
  // Checks the rules.
  void check(const Config& config) const {
    for (const auto& r : rules_) {
      if (!r.holds(config)) throw InputError(r.what, where(r.name));
    }
  }
  // Every parameter of `config`, as text that read() takes back.
  Params write(const Config& config) const {
    Params out;
    for (const auto& e : entries_) out[e.name] = e.print(config);
    return out;
  }
  // The declarations in order, with the defaults of Config{}.
  std::vector<ParamSpec> specs() const {
    const Config defaults{};
    std::vector<ParamSpec> out;
    for (const auto& e : entries_) {
      out.push_back({e.name, e.print(defaults), e.range, e.meaning, e.type});
    }
    return out;
  }
  std::vector<std::string> names() const {
    std::vector<std::string> out;
    for (const auto& e : entries_) out.push_back(e.name);
    return out;
  }
  const std::string& owner() const { return owner_; }

 private:
  struct Entry {
    std::string name, range, meaning;
    Parse parse;
    Print print;
    ParamSpec::Type type;
  };
  struct Rule {
    std::string name;
    std::function<bool(const Config&)> holds;
    std::string what;
  };

  std::string where(const std::string& name) const { return owner_ + "." + name; }

  std::string owner_;
  std::vector<Entry> entries_;
  std::vector<Rule> rules_;
};

}  // namespace gpfd
