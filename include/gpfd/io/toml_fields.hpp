// io: typed reading and writing of TOML tables against a fixed set of keys, with errors that name
// the file, line and column, the full key, and a suggestion for an unknown key.
#pragma once

#include <toml++/toml.h>

#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace gpfd::io {

// Reads the fields of one TOML document. Each read marks its key as known; finish() then refuses
// any key that no read asked for.
class TomlReader {
 public:
  // `source` names the document in errors (a file name, or "--set" for overrides).
  TomlReader(const toml::table& root, std::string source);

  // section "" is the root table; "a.b" a nested table. Absent keys leave `out` unchanged.
  void read(const std::string& section, const std::string& key, std::string& out,
            const std::vector<std::string>& choices = {});
  void read(const std::string& section, const std::string& key, bool& out);
  void read(const std::string& section, const std::string& key, int& out, long lo, long hi);
  // A 64-bit unsigned value from a TOML integer (signed 64-bit): a negative one comes back as its
  // two's complement. The experiment config refuses negative seeds and writes 2^63 and above as
  // text (run/experiment_config.cpp).
  void read(const std::string& section, const std::string& key, std::uint64_t& out);
  void read(const std::string& section, const std::string& key, double& out, double lo, double hi);
  void read(const std::string& section, const std::string& key, std::vector<double>& out);
  void read(const std::string& section, const std::string& key, std::vector<std::string>& out);
  // A free-form table of scalars (environment or learner parameters) as text values; arrays
  // become comma-separated lists.
  void readParams(const std::string& section, std::map<std::string, std::string>& out);
  // section.key as an array of such tables; false, reading nothing, where it is absent or not an
  // array.
  bool readParamsArray(const std::string& section, const std::string& key,
                       std::vector<std::map<std::string, std::string>>& out);
  // Where `section.key` is (file:line:column), for errors raised later while validating it.
  std::string where(const std::string& section, const std::string& key) const;

  // Throws InputError for the first key or table that no read asked for.
  void finish() const;

 private:
  const toml::node* find(const std::string& section, const std::string& key);
  void paramsOf(const toml::table& table, const std::string& section,
                std::map<std::string, std::string>& out);
  [[noreturn]] void fail(const std::string& section, const std::string& key,
                         const std::string& what) const;

  const toml::table& root_;
  std::string source_;
  std::set<std::string> known_;  // Full dotted keys read so far, sections included.
};

// Builds a TOML document field by field (for the resolved config).
class TomlWriter {
 public:
  void write(const std::string& section, const std::string& key, const std::string& value);
  void write(const std::string& section, const std::string& key, bool value);
  void write(const std::string& section, const std::string& key, std::int64_t value);
  void write(const std::string& section, const std::string& key, double value);
  void write(const std::string& section, const std::string& key, const std::vector<double>& value);
  void write(const std::string& section, const std::string& key,
             const std::vector<std::string>& value);
  // An array of tables of text values.
  void write(const std::string& section, const std::string& key,
             const std::vector<std::map<std::string, std::string>>& tables);
  void writeParams(const std::string& section, const std::map<std::string, std::string>& params);
  std::string text() const;

 private:
  toml::table& table(const std::string& section);
  toml::table root_;
};

// Parses `key=value` (a dotted key and a TOML value; a value that is not valid TOML is taken as a
// string) into `root`, replacing what was there. Throws InputError naming the override.
void applyOverride(toml::table& root, const std::string& assignment);

// Parses a TOML document; InputError with file:line:column on a syntax error.
toml::table parseToml(const std::string& text, const std::string& source);

}  // namespace gpfd::io
