#include "gpfd/util/params.hpp"

#include <algorithm>

namespace gpfd {

bool parseFlag(const std::string& text, const std::string& where) {
  if (text == "true" || text == "1" || text == "on" || text == "yes") return true;
  if (text == "false" || text == "0" || text == "off" || text == "no") return false;
  throw InputError(fmt::format("'{}' is not a boolean (true | false)", text), where);
}

std::vector<std::string> paramNames(const std::vector<ParamSpec>& specs) {
  std::vector<std::string> names;
  for (const auto& spec : specs) names.push_back(spec.name);
  return names;
}

void checkParamNames(const std::string& owner, const std::vector<std::string>& names,
                     const Params& params) {
  for (const auto& [key, value] : params) {
    if (std::find(names.begin(), names.end(), key) == names.end()) {
      throw InputError(fmt::format("{} has no parameter '{}' (it takes: {})", owner, key,
                                   fmt::join(names, ", ")),
                       owner + "." + key);
    }
  }
}

}  // namespace gpfd
