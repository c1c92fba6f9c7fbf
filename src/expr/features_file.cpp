#include "gpfd/expr/features_file.hpp"

#include <sstream>
#include <string_view>

#include "gpfd/expr/parse.hpp"
#include "gpfd/util/atomic_file.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::expr {
namespace {

std::string trim(const std::string& s) {
  const auto begin = s.find_first_not_of(" \t\r");
  if (begin == std::string::npos) return {};
  return s.substr(begin, s.find_last_not_of(" \t\r") - begin + 1);
}

VariableNames splitNames(const std::string& list) {
  VariableNames names;
  std::string current;
  for (char ch : list + ",") {
    if (ch == ',' || ch == ' ' || ch == '\t') {
      if (!current.empty()) names.push_back(current);
      current.clear();
    } else {
      current += ch;
    }
  }
  return names;
}

std::string joinNames(const VariableNames& names) {
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i) out += (i ? ", " : "") + names[i];
  return out;
}

}  // namespace

TextFormat parseTextFormat(const std::string& name) {
  if (name == "infix") return TextFormat::Infix;
  if (name == "sexpr") return TextFormat::Sexpr;
  throw InputError("unknown format '" + name + "' (infix or sexpr)", "format");
}

FeaturesFile parseFeaturesFile(const std::string& text, const std::string& sourceName,
                               const VariableNames& expectedVariables,
                               const std::string& expectedEnv) {
  FeaturesFile file;
  std::vector<std::pair<int, std::string>> featureLines;
  // A UTF-8 byte-order mark (some editors write one) is not part of the text.
  constexpr std::string_view kBom = "\xEF\xBB\xBF";
  std::istringstream in(text.starts_with(kBom) ? text.substr(kBom.size()) : text);
  std::string line;
  int lineNumber = 0;
  bool sawVariables = false;
  const auto where = [&](int l) { return sourceName + ":" + std::to_string(l); };
  while (std::getline(in, line)) {
    ++lineNumber;
    const std::string content = trim(line);
    if (content.empty()) continue;
    if (content[0] != '#') {
      featureLines.emplace_back(lineNumber, line);
      continue;
    }
    const std::string comment = trim(content.substr(1));
    const auto colon = comment.find(':');
    if (colon == std::string::npos) continue;
    const std::string key = trim(comment.substr(0, colon));
    const std::string value = trim(comment.substr(colon + 1));
    if (key.empty() || key.find(' ') != std::string::npos) continue;
    if (key == "env") {
      file.env = value;
    } else if (key == "variables") {
      file.variables = splitNames(value);
      sawVariables = true;
    } else if (key == "format") {
      try {
        file.format = parseTextFormat(value);
      } catch (const InputError& e) {
        throw InputError(e.what(), where(lineNumber));
      }
    } else {
      file.meta[key] = value;
    }
  }
  if (!expectedEnv.empty() && !file.env.empty() && file.env != expectedEnv) {
    throw InputError("features file is for env '" + file.env + "', not '" + expectedEnv + "'",
                     sourceName);
  }
  if (sawVariables && !expectedVariables.empty() && file.variables != expectedVariables) {
    throw InputError("features file variables (" + joinNames(file.variables) +
                         ") differ from the environment's (" + joinNames(expectedVariables) + ")",
                     sourceName);
  }
  if (!sawVariables) {
    if (expectedVariables.empty()) {
      throw InputError("features file has no '# variables:' line and no environment was given",
                       sourceName);
    }
    file.variables = expectedVariables;
  }
  if (file.env.empty()) file.env = expectedEnv;
  if (featureLines.empty()) throw InputError("empty: no features in the file", sourceName);
  for (const auto& [number, featureText] : featureLines) {
    const SourcePlace place{sourceName, number};
    file.genome.addFeature(file.format == TextFormat::Infix
                               ? parseInfix(featureText, file.variables, place)
                               : parseSexpr(featureText, file.variables, place));
  }
  return file;
}

FeaturesFile readFeaturesFile(const std::string& path, const VariableNames& expectedVariables,
                              const std::string& expectedEnv) {
  return parseFeaturesFile(readFile(path), path, expectedVariables, expectedEnv);
}

std::string formatFeaturesFile(const FeaturesFile& file) {
  std::string out = "# gpfd features 1\n";
  if (!file.env.empty()) out += "# env: " + file.env + "\n";
  out += "# variables: " + joinNames(file.variables) + "\n";
  out += std::string("# format: ") + (file.format == TextFormat::Infix ? "infix" : "sexpr") + "\n";
  for (const auto& [key, value] : file.meta) out += "# " + key + ": " + value + "\n";
  for (std::size_t k = 0; k < file.genome.featureCount(); ++k) {
    const auto tree = file.genome.feature(k);
    out += (file.format == TextFormat::Infix ? toInfix(tree, file.variables)
                                             : toSexpr(tree, file.variables)) +
           "\n";
  }
  return out;
}

void writeFeaturesFile(const std::string& path, const FeaturesFile& file) {
  writeFileAtomically(path, formatFeaturesFile(file));
}

}  // namespace gpfd::expr
