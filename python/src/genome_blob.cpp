#include "genome_blob.hpp"

#include <cstdint>
#include <cstring>

#include "gpfd/util/error.hpp"

namespace gpfd::python {
namespace {

template <typename T>
void append(std::string& out, T value) {
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  out.append(raw, sizeof(T));
}

class Cursor {
 public:
  explicit Cursor(std::string_view bytes) : bytes_(bytes) {}
  template <typename T>
  T take() {
    if (bytes_.size() - at_ < sizeof(T)) throw InputError("the genome's bytes end early", "genome");
    T value;
    std::memcpy(&value, bytes_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return value;
  }
  bool done() const { return at_ == bytes_.size(); }

 private:
  std::string_view bytes_;
  std::size_t at_ = 0;
};

}  // namespace

std::string packGenome(const expr::Genome& genome) {
  std::string out;
  for (std::size_t k = 0; k < genome.featureCount(); ++k) {
    const auto tree = genome.feature(k);
    append(out, static_cast<std::uint32_t>(tree.size()));
    for (const expr::Node& node : tree) {
      append(out, static_cast<std::uint8_t>(node.op));
      append(out, node.var);
      append(out, node.value);
    }
  }
  return out;
}

expr::Genome unpackGenome(std::string_view bytes, int variableCount) {
  expr::Genome genome;
  Cursor cursor(bytes);
  while (!cursor.done()) {
    const auto size = cursor.take<std::uint32_t>();
    if (size == 0 || size > static_cast<std::uint32_t>(expr::kMaxParseSize)) {
      throw InputError("a feature of the genome has a bad size", "genome");
    }
    expr::Tree tree(size);
    for (expr::Node& node : tree) {
      const auto op = cursor.take<std::uint8_t>();
      if (op >= expr::kOpCount) throw InputError("the genome holds an unknown operator", "genome");
      node.op = static_cast<expr::Op>(op);
      node.var = cursor.take<std::uint16_t>();
      node.value = cursor.take<double>();
    }
    std::string problem = expr::recomputeLengths(tree) ? expr::checkTree(tree, variableCount)
                                                       : "not a well-formed prefix tree";
    if (!problem.empty()) throw InputError("bad genome: " + problem, "genome");
    genome.addFeature(tree);
  }
  return genome;
}

}  // namespace gpfd::python
