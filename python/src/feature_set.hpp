// python: gpfd.FeatureSet, a features file compiled to native code and callable on NumPy arrays of
// states.
#pragma once

#include <memory>
#include <string>

#include "gpfd/expr/features_file.hpp"
#include "gpfd/jit/compiled_feature_map.hpp"

namespace gpfd::python {

class FeatureSet {
 public:
  // Compiles the file's genome over its variables. `name` labels the set (assessments).
  FeatureSet(expr::FeaturesFile file, std::string name);

  const expr::FeaturesFile& file() const { return file_; }
  const jit::CompiledFeatureMap& map() const { return *map_; }
  const std::string& name() const { return name_; }
  std::size_t inputDim() const { return file_.variables.size(); }
  std::size_t outputDim() const { return file_.genome.featureCount(); }

 private:
  expr::FeaturesFile file_;
  std::shared_ptr<const jit::CompiledFeatureMap> map_;
  std::string name_;
};

}  // namespace gpfd::python
