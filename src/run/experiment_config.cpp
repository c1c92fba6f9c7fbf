#include "gpfd/run/experiment_config.hpp"

#include "gpfd/env/environment.hpp"
#include "gpfd/io/toml_fields.hpp"
#include "gpfd/rl/learner_params.hpp"
#include "gpfd/util/atomic_file.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::run {
namespace {

const std::vector<std::string> kMeasures{"mean", "final", "last_fraction"};

std::string measureName(TrialMeasure m) { return kMeasures[static_cast<int>(m)]; }

// Visits every field once, for reading and for writing: V is io::TomlReader or Writer below.
template <typename V>
void visit(V& v, ExperimentConfig& c) {
  v.text("", "name", c.name);
  v.seed("", "seed", c.seed);
  v.text("env", "name", c.env);
  v.params("env.params", c.envParams);
  v.text("learner", "name", c.learner, {"pg", "lpi"});
  v.params("learner.params", c.learnerParams);
  v.integer("fitness", "trials", c.trials, 1, 1000);
  v.measure("fitness", "measure", c.measure);
  v.real("fitness", "last_fraction", c.lastFraction, 1e-9, 1.0);
  v.real("fitness", "size_penalty", c.gp.sizePenalty, 0.0, 1e6);
  v.boolean("fitness", "with_original", c.withOriginal);
  v.text("primitives", "set", c.primitives);
  v.reals("primitives", "constants", c.constants);
  v.boolean("primitives", "ephemeral", c.ephemeral);
  v.integer("genome", "min_features", c.limits.minFeatures, 1, 1000);
  v.integer("genome", "max_features", c.limits.maxFeatures, 1, 1000);
  v.integer("genome", "max_depth", c.limits.maxDepth, 1, 64);
  v.integer("genome", "max_size", c.limits.maxSize, 1, 65536);
  v.integer("genome", "init_min_depth", c.initMinDepth, 1, 64);
  v.integer("genome", "init_max_depth", c.initMaxDepth, 1, 64);
  v.integer("genome", "init_max_features", c.initMaxFeatures, 1, 1000);
  v.integer("genome", "mutation_depth", c.mutationDepth, 1, 64);
  v.integer("gp", "population", c.gp.population, 2, 1000000);
  v.integer("gp", "generations", c.gp.generations, 1, 1000000);
  v.real("gp", "crossover", c.gp.crossoverRate, 0.0, 1.0);
  v.real("gp", "list_crossover_share", c.gp.listCrossoverShare, 0.0, 1.0);
  v.real("gp", "node_mutation_weight", c.gp.nodeMutationWeight, 0.0, 1e6);
  v.real("gp", "tree_mutation_weight", c.gp.treeMutationWeight, 0.0, 1e6);
  v.real("gp", "shrinkage_weight", c.gp.shrinkageWeight, 0.0, 1e6);
  v.real("gp", "elitism", c.gp.elitism, 0.0, 0.99);
  v.integer("gp", "tournament_size", c.gp.tournamentSize, 1, 1000);
  v.integer("assess", "runs", c.assessRuns, 1, 100000);
  v.params("assess.params", c.assessParams);
}

struct Reader {
  io::TomlReader& r;
  void text(const char* s, const char* k, std::string& out, std::vector<std::string> choices = {}) {
    r.read(s, k, out, choices);
  }
  void seed(const char* s, const char* k, std::uint64_t& out) { r.read(s, k, out); }
  void integer(const char* s, const char* k, int& out, long lo, long hi) {
    r.read(s, k, out, lo, hi);
  }
  void real(const char* s, const char* k, double& out, double lo, double hi) {
    r.read(s, k, out, lo, hi);
  }
  void reals(const char* s, const char* k, std::vector<double>& out) { r.read(s, k, out); }
  void boolean(const char* s, const char* k, bool& out) { r.read(s, k, out); }
  void params(const char* s, std::map<std::string, std::string>& out) { r.readParams(s, out); }
  void measure(const char* s, const char* k, TrialMeasure& out) {
    std::string name = measureName(out);
    r.read(s, k, name, kMeasures);
    out = static_cast<TrialMeasure>(std::find(kMeasures.begin(), kMeasures.end(), name) -
                                    kMeasures.begin());
  }
};

struct Writer {
  io::TomlWriter w;
  void text(const char* s, const char* k, std::string& v, std::vector<std::string> = {}) {
    w.write(s, k, v);
  }
  void seed(const char* s, const char* k, std::uint64_t& v) {
    w.write(s, k, static_cast<std::int64_t>(v));
  }
  void integer(const char* s, const char* k, int& v, long, long) {
    w.write(s, k, static_cast<std::int64_t>(v));
  }
  void real(const char* s, const char* k, double& v, double, double) { w.write(s, k, v); }
  void reals(const char* s, const char* k, std::vector<double>& v) { w.write(s, k, v); }
  void boolean(const char* s, const char* k, bool& v) { w.write(s, k, v); }
  void params(const char* s, std::map<std::string, std::string>& v) { w.writeParams(s, v); }
  void measure(const char* s, const char* k, TrialMeasure& v) { w.write(s, k, measureName(v)); }
};

void require(bool ok, const std::string& what, const std::string& where) {
  if (!ok) throw InputError(what, where);
}

}  // namespace

ExperimentConfig parseExperimentConfig(const std::string& text, const std::string& source,
                                       const std::vector<std::string>& overrides) {
  toml::table root = io::parseToml(text, source);
  for (const auto& o : overrides) io::applyOverride(root, o);
  ExperimentConfig config;
  io::TomlReader reader(root, source);
  Reader visitor{reader};
  visit(visitor, config);
  reader.finish();
  validate(config);
  return config;
}

ExperimentConfig loadExperimentConfig(const std::string& path,
                                      const std::vector<std::string>& overrides) {
  return parseExperimentConfig(readFile(path), path, overrides);
}

std::string formatExperimentConfig(const ExperimentConfig& config) {
  ExperimentConfig copy = config;
  Writer writer;
  visit(writer, copy);
  return writer.w.text();
}

void validate(const ExperimentConfig& c) {
  env::Registry::global().make(c.env, c.envParams);  // Unknown env or parameter, bad value.
  for (const auto& [key, value] : c.learnerParams) {
    rl::PolicyGradientConfig pg;
    rl::LambdaPolicyIterationConfig lpi;
    const bool known = c.learner == "pg" ? rl::applyPolicyGradientParam(pg, key, value)
                                         : rl::applyLambdaPolicyIterationParam(lpi, key, value);
    require(known, "unknown parameter '" + key + "' of learner " + c.learner,
            "learner.params." + key);
  }
  for (const auto& [key, value] : c.assessParams) {
    rl::PolicyGradientConfig pg;
    rl::LambdaPolicyIterationConfig lpi;
    const bool known = c.learner == "pg" ? rl::applyPolicyGradientParam(pg, key, value)
                                         : rl::applyLambdaPolicyIterationParam(lpi, key, value);
    require(known, "unknown parameter '" + key + "' of learner " + c.learner,
            "assess.params." + key);
  }
  expr::PrimitiveSet::named(c.primitives);
  require(c.limits.minFeatures <= c.limits.maxFeatures,
          "genome.min_features must not exceed genome.max_features", "genome");
  require(c.initMinDepth <= c.initMaxDepth,
          "genome.init_min_depth must not exceed genome.init_max_depth", "genome");
  gp::validate(c.gp);
}

gp::SearchSpace searchSpace(const ExperimentConfig& c, int variableCount) {
  gp::SearchSpace space;
  space.primitives = expr::PrimitiveSet::named(c.primitives);
  space.primitives.constants = c.constants;
  space.primitives.ephemeral = c.ephemeral;
  space.variableCount = variableCount;
  space.limits = c.limits;
  space.initMinDepth = c.initMinDepth;
  space.initMaxDepth = c.initMaxDepth;
  space.initMaxFeatures = c.initMaxFeatures;
  space.mutationDepth = c.mutationDepth;
  return space;
}

gp::GpConfig gpConfig(const ExperimentConfig& c) {
  gp::GpConfig config = c.gp;
  config.seed = c.seed;
  return config;
}

}  // namespace gpfd::run
