#include "gpfd/io/toml_fields.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "gpfd/io/suggest.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::io {
namespace {

std::string join(const std::string& section, const std::string& key) {
  return section.empty() ? key : section + "." + key;
}

std::vector<std::string> split(const std::string& dotted) {
  std::vector<std::string> parts;
  std::size_t begin = 0;
  while (begin <= dotted.size()) {
    const std::size_t end = std::min(dotted.find('.', begin), dotted.size());
    parts.push_back(dotted.substr(begin, end - begin));
    begin = end + 1;
  }
  return parts;
}

bool fromOverride(const toml::node* node) { return node != nullptr && !node->source().begin; }

// file:line:column of the node of `key`; "--set key" for a node that came from a command-line
// override.
std::string place(const std::string& source, const toml::node* node, const std::string& key) {
  if (node == nullptr) return source;
  if (fromOverride(node)) return "--set " + key;
  return fmt::format("{}:{}:{}", source, node->source().begin.line, node->source().begin.column);
}

std::string scalarText(const toml::node& node) {
  if (auto s = node.value<std::string>(); s && node.is_string()) return *s;
  if (node.is_boolean()) return *node.value<bool>() ? "true" : "false";
  if (node.is_integer()) return std::to_string(*node.value<std::int64_t>());
  if (node.is_floating_point()) return fmt::format("{}", *node.value<double>());
  return {};
}

}  // namespace

TomlReader::TomlReader(const toml::table& root, std::string source)
    : root_(root), source_(std::move(source)) {}

const toml::node* TomlReader::find(const std::string& section, const std::string& key) {
  const toml::table* table = &root_;
  std::string path;
  if (!section.empty()) {
    for (const auto& part : split(section)) {
      path = join(path, part);
      known_.insert(path);
      const toml::node* next = table->get(part);
      if (next == nullptr) return nullptr;
      if (!next->is_table()) fail("", path, "must be a table");
      table = next->as_table();
    }
  }
  known_.insert(join(section, key));
  return table->get(key);
}

void TomlReader::fail(const std::string& section, const std::string& key,
                      const std::string& what) const {
  const std::string full = join(section, key);
  const toml::node* node = root_.at_path(full).node();
  throw InputError(full + " " + what, place(source_, node, full));
}

std::string TomlReader::where(const std::string& section, const std::string& key) const {
  const std::string full = join(section, key);
  const toml::node* node = root_.at_path(full).node();
  return place(source_, node, full) + (fromOverride(node) ? "" : " " + full);
}

void TomlReader::read(const std::string& section, const std::string& key, std::string& out,
                      const std::vector<std::string>& choices) {
  const toml::node* node = find(section, key);
  if (node == nullptr) return;
  if (!node->is_string()) fail(section, key, "must be a string");
  const std::string value = *node->value<std::string>();
  if (!choices.empty() && std::find(choices.begin(), choices.end(), value) == choices.end()) {
    std::string list;
    for (const auto& c : choices) list += (list.empty() ? "" : ", ") + c;
    fail(section, key,
         "must be one of " + list + ", not '" + value + "'" + didYouMean(value, choices));
  }
  out = value;
}

void TomlReader::read(const std::string& section, const std::string& key, bool& out) {
  const toml::node* node = find(section, key);
  if (node == nullptr) return;
  if (!node->is_boolean()) fail(section, key, "must be true or false");
  out = *node->value<bool>();
}

void TomlReader::read(const std::string& section, const std::string& key, int& out, long lo,
                      long hi) {
  const toml::node* node = find(section, key);
  if (node == nullptr) return;
  if (!node->is_integer()) fail(section, key, "must be an integer");
  const auto value = *node->value<std::int64_t>();
  if (value < lo || value > hi) {
    fail(section, key, fmt::format("must be in [{}, {}], not {}", lo, hi, value));
  }
  out = static_cast<int>(value);
}

void TomlReader::read(const std::string& section, const std::string& key, std::uint64_t& out) {
  const toml::node* node = find(section, key);
  if (node == nullptr) return;
  if (!node->is_integer()) fail(section, key, "must be an integer");
  out = static_cast<std::uint64_t>(*node->value<std::int64_t>());
}

void TomlReader::read(const std::string& section, const std::string& key, double& out, double lo,
                      double hi) {
  const toml::node* node = find(section, key);
  if (node == nullptr) return;
  if (!node->is_number()) fail(section, key, "must be a number");
  const double value = *node->value<double>();
  if (!std::isfinite(value) || value < lo || value > hi) {
    fail(section, key, fmt::format("must be in [{}, {}], not {}", lo, hi, value));
  }
  out = value;
}

void TomlReader::read(const std::string& section, const std::string& key,
                      std::vector<double>& out) {
  const toml::node* node = find(section, key);
  if (node == nullptr) return;
  const toml::array* array = node->as_array();
  if (array == nullptr) fail(section, key, "must be an array of numbers");
  std::vector<double> values;
  for (const auto& element : *array) {
    if (!element.is_number() || !std::isfinite(*element.value<double>())) {
      fail(section, key, "must be an array of finite numbers");
    }
    values.push_back(*element.value<double>());
  }
  out = values;
}

void TomlReader::read(const std::string& section, const std::string& key,
                      std::vector<std::string>& out) {
  const toml::node* node = find(section, key);
  if (node == nullptr) return;
  const toml::array* array = node->as_array();
  if (array == nullptr) fail(section, key, "must be an array of strings");
  std::vector<std::string> values;
  for (const auto& element : *array) {
    if (!element.is_string()) fail(section, key, "must be an array of strings");
    values.push_back(*element.value<std::string>());
  }
  out = values;
}

void TomlReader::readParams(const std::string& section, std::map<std::string, std::string>& out) {
  const std::size_t dot = section.rfind('.');
  const toml::node* node = dot == std::string::npos
                               ? find("", section)
                               : find(section.substr(0, dot), section.substr(dot + 1));
  if (node == nullptr) return;
  const toml::table* table = node->as_table();
  if (table == nullptr) fail("", section, "must be a table");
  paramsOf(*table, section, out);
}

bool TomlReader::readParamsArray(const std::string& section, const std::string& key,
                                 std::vector<std::map<std::string, std::string>>& out) {
  const toml::node* node = find(section, key);
  if (node == nullptr || !node->is_array()) return false;
  const std::string full = join(section, key);
  std::vector<std::map<std::string, std::string>> tables;
  for (const auto& element : *node->as_array()) {
    const toml::table* table = element.as_table();
    if (table == nullptr) fail(section, key, "must be a table or an array of tables");
    paramsOf(*table, full + "[" + std::to_string(tables.size()) + "]", tables.emplace_back());
  }
  out = tables;
  return true;
}

void TomlReader::paramsOf(const toml::table& table, const std::string& section,
                          std::map<std::string, std::string>& out) {
  for (const auto& [k, v] : table) {
    const std::string key(k.str());
    known_.insert(join(section, key));
    std::string text;
    if (const toml::array* array = v.as_array()) {
      for (const auto& element : *array) {
        const std::string item = scalarText(element);
        if (item.empty()) fail(section, key, "must be a scalar or an array of scalars");
        text += (text.empty() ? "" : ",") + item;
      }
    } else {
      text = scalarText(v);
      if (text.empty() && !v.is_string()) fail(section, key, "must be a scalar or an array");
    }
    out[key] = text;
  }
}

void TomlReader::finish() const {
  // Depth-first over every key; the first unknown one is reported.
  std::vector<std::pair<std::string, const toml::table*>> stack{{"", &root_}};
  while (!stack.empty()) {
    const auto [prefix, table] = stack.back();
    stack.pop_back();
    for (const auto& [k, v] : *table) {
      const std::string full = join(prefix, std::string(k.str()));
      if (!known_.count(full)) {
        std::vector<std::string> siblings;
        for (const auto& known : known_) {
          const std::size_t dot = known.rfind('.');
          const std::string parent = dot == std::string::npos ? "" : known.substr(0, dot);
          if (parent == prefix)
            siblings.push_back(dot == std::string::npos ? known : known.substr(dot + 1));
        }
        // The closest known key, or all of them when none is close.
        const std::string suggestion = didYouMean(std::string(k.str()), siblings);
        throw InputError("unknown key '" + full + "'" +
                             (suggestion.empty() && !siblings.empty()
                                  ? fmt::format(" (known: {})", fmt::join(siblings, ", "))
                                  : suggestion),
                         place(source_, &v, full));
      }
      if (const toml::table* nested = v.as_table()) stack.emplace_back(full, nested);
    }
  }
}

toml::table& TomlWriter::table(const std::string& section) {
  toml::table* t = &root_;
  if (section.empty()) return *t;
  for (const auto& part : split(section)) {
    if (!t->contains(part)) t->insert(part, toml::table{});
    t = t->get(part)->as_table();
  }
  return *t;
}

void TomlWriter::write(const std::string& section, const std::string& key,
                       const std::string& value) {
  table(section).insert_or_assign(key, value);
}
void TomlWriter::write(const std::string& section, const std::string& key, bool value) {
  table(section).insert_or_assign(key, value);
}
void TomlWriter::write(const std::string& section, const std::string& key, std::int64_t value) {
  table(section).insert_or_assign(key, value);
}
void TomlWriter::write(const std::string& section, const std::string& key, double value) {
  table(section).insert_or_assign(key, value);
}
void TomlWriter::write(const std::string& section, const std::string& key,
                       const std::vector<double>& value) {
  toml::array array;
  for (double v : value) array.push_back(v);
  table(section).insert_or_assign(key, array);
}
void TomlWriter::write(const std::string& section, const std::string& key,
                       const std::vector<std::string>& value) {
  toml::array array;
  for (const auto& v : value) array.push_back(v);
  table(section).insert_or_assign(key, array);
}
void TomlWriter::write(const std::string& section, const std::string& key,
                       const std::vector<std::map<std::string, std::string>>& tables) {
  toml::array array;
  for (const auto& params : tables) {
    toml::table t;
    for (const auto& [k, v] : params) t.insert_or_assign(k, v);
    array.push_back(std::move(t));
  }
  table(section).insert_or_assign(key, array);
}
void TomlWriter::writeParams(const std::string& section,
                             const std::map<std::string, std::string>& params) {
  auto& t = table(section);
  for (const auto& [k, v] : params) t.insert_or_assign(k, v);
}

std::string TomlWriter::text() const {
  std::ostringstream out;
  out << toml::toml_formatter{root_} << "\n";
  return out.str();
}

toml::table parseToml(const std::string& text, const std::string& source) {
  try {
    return toml::parse(text, source);
  } catch (const toml::parse_error& e) {
    throw InputError(
        "invalid TOML: " + std::string(e.description()),
        fmt::format("{}:{}:{}", source, e.source().begin.line, e.source().begin.column));
  }
}

void applyOverride(toml::table& root, const std::string& assignment) {
  const std::size_t eq = assignment.find('=');
  const std::string where = "--set " + assignment;
  if (eq == std::string::npos || eq == 0) throw InputError("expected key=value", where);
  const std::string key = assignment.substr(0, eq);
  const std::string value = assignment.substr(eq + 1);
  toml::table parsed;
  try {
    parsed = toml::parse("v = " + value);
  } catch (const toml::parse_error&) {
    parsed.insert("v", value);  // Not a TOML value: take the text as a string.
  }
  const auto parts = split(key);
  toml::table* table = &root;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    if (parts[i].empty()) throw InputError("empty key part", where);
    if (!table->contains(parts[i])) table->insert(parts[i], toml::table{});
    table = table->get(parts[i])->as_table();
    if (table == nullptr) throw InputError("'" + parts[i] + "' is not a table", where);
  }
  table->insert_or_assign(parts.back(), *parsed.get("v"));
}

}  // namespace gpfd::io
