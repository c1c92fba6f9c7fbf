#include "gpfd/run/experiment_config.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <filesystem>
#include <functional>
#include <limits>
#include <string_view>

#include "gpfd/env/environment.hpp"
#include "gpfd/gp/operator_registry.hpp"
#include "gpfd/io/suggest.hpp"
#include "gpfd/io/toml_fields.hpp"
#include "gpfd/rl/learner.hpp"
#include "gpfd/run/learner_choice.hpp"
#include "gpfd/run/plugin.hpp"
#include "gpfd/run/sequential_test.hpp"
#include "gpfd/run/stored_config.hpp"
#include "gpfd/util/atomic_file.hpp"
#include "gpfd/util/error.hpp"
#include "gpfd/util/number.hpp"

namespace gpfd::run {
namespace {

const std::vector<std::string> kMeasures{"mean", "final", "last_fraction"};

}  // namespace

std::string measureName(TrialMeasure m) { return kMeasures[static_cast<int>(m)]; }

namespace {

void require(bool ok, const std::string& what, const std::string& where) {
  if (!ok) throw InputError(what, where);
}

// Visits every field once, for reading and for writing: V is io::TomlReader or Writer below.
template <typename V>
void visit(V& v, ExperimentConfig& c) {
  v.text("", "name", c.name);
  v.seed("", "seed", c.seed);
  v.texts("", "plugins", c.plugins);
  v.duration("", "time_budget", c.timeBudget);
  v.duration("", "task_timeout", c.taskTimeout);
  v.text("env", "name", c.env);
  v.params("env.params", c.envParams);
  v.text("learner", "name", c.learner);
  v.params("learner.params", c.learnerParams);
  v.choices("learner", c.learnerChoices, c.learnerAlternatives, c.choiceSeeds, c.choiceSignificance,
            c.choiceRandomSets);
  v.alternatives("learner", "choose_fallback", c.learnerFallbacks);
  v.integer("fitness", "trials", c.trials, 1, 1000);
  v.integer("fitness", "max_trials", c.maxTrials, 0, 100000);
  v.real("fitness", "reevaluation_share", c.reevaluationShare, 0.0, 1.0);
  v.boolean("fitness", "common_seeds", c.gp.commonRandomNumbers);
  v.measure("fitness", "measure", c.measure);
  v.real("fitness", "last_fraction", c.lastFraction, 1e-9, 1.0);
  v.real("fitness", "size_penalty", c.gp.sizePenalty, 0.0, 1e6);
  v.boolean("fitness", "with_original", c.withOriginal);
  v.boolean("fitness", "normalise", c.normalise);
  v.integer("fitness", "state_sample", c.stateSample, 16, 100000);
  v.real("fitness", "promote", c.gp.promote, 0.0, 0.99);
  v.params("fitness.rung_params", c.rungParams);
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
  v.boolean("genome", "drop_redundant", c.dropRedundant);
  v.real("genome", "redundant_r2", c.redundantR2, 0.5, 1.0);
  v.boolean("genome", "reject_constant", c.rejectConstant);
  v.integer("gp", "population", c.gp.population, 2, 1000000);
  v.integer("gp", "generations", c.gp.generations, 1, 1000000);
  v.weights("gp.operators", c.gp.operatorWeights);
  for (const char* key : {"crossover", "list_crossover_share", "node_mutation_weight",
                          "tree_mutation_weight", "shrinkage_weight"}) {
    v.replacedByOperators("gp", key);
  }
  v.real("gp", "elitism", c.gp.elitism, 0.0, 0.99);
  v.integer("gp", "tournament_size", c.gp.tournamentSize, 1, 1000);
  v.boolean("gp", "distinct_offspring", c.gp.distinctOffspring);
  v.integer("validation", "candidates", c.validation.candidates, 0, 1000);
  v.integer("validation", "seeds", c.validation.seeds, 2, 100000);
  v.integer("validation", "every", c.validation.every, 0, 1000000);
  v.params("validation.params", c.validation.params);
  v.optionalMeasure("validation", "measure", c.validation.measure);
  v.integer("validation", "confirm_seeds", c.validation.confirmSeeds, 0, 100000);
  v.integer("validation", "confirm_looks", c.validation.confirmLooks, 1, kMaxLooks);
  v.params("validation.confirm_params", c.validation.confirmParams);
  v.measure("validation", "confirm_measure", c.validation.confirmMeasure);
  v.real("validation", "parsimony_se", c.validation.parsimonySe, 0.0, 100.0);
  v.integer("assess", "runs", c.assessRuns, 1, 100000);
  v.params("assess.params", c.assessParams);
}

// "section.key", or "key" in the root table.
std::string dotted(const std::string& section, const std::string& key) {
  return section.empty() ? key : section + "." + key;
}

// The paper's operator table as a config writes it, from the registry's defaults.
std::string defaultOperatorTable() {
  std::vector<std::string> entries;
  for (const auto& o : gp::OperatorRegistry::global().operators()) {
    entries.push_back(fmt::format("{} = {}", o.name, o.defaultWeight));
  }
  return fmt::format("gp.operators = {{ {} }}", fmt::join(entries, ", "));
}

struct Reader {
  io::TomlReader& r;
  const toml::table& root;

  const toml::node* node(const char* s, const char* k) const {
    return root.at_path(dotted(s, k)).node();
  }
  void text(const char* s, const char* k, std::string& out, std::vector<std::string> choices = {}) {
    r.read(s, k, out, choices);
  }
  // Any uint64: an integer up to 2^63 - 1, or decimal text (how 2^63 and above are written, since
  // TOML integers are signed 64-bit). A negative integer is refused.
  void seed(const char* s, const char* k, std::uint64_t& out) {
    const toml::node* n = node(s, k);
    const std::string rule = fmt::format("{} must be an integer in [0, {}]", dotted(s, k),
                                         std::numeric_limits<std::uint64_t>::max());
    if (n != nullptr && n->is_string()) {
      std::string text;
      r.read(s, k, text);
      std::uint64_t value = 0;
      const char* end = text.data() + text.size();
      const auto [stop, error] = std::from_chars(text.data(), end, value);
      require(!text.empty() && stop == end && error == std::errc(), rule + ", not '" + text + "'",
              r.where(s, k));
      out = value;
      return;
    }
    if (n != nullptr && n->is_integer() && *n->value<std::int64_t>() < 0) {
      const std::int64_t value = *n->value<std::int64_t>();
      throw InputError(fmt::format("{}, not {} (a seed of 2^63 or more is written as text, as in "
                                   "seed = \"{}\", which older versions stored as {})",
                                   rule, value, static_cast<std::uint64_t>(value), value),
                       r.where(s, k));
    }
    r.read(s, k, out);
  }
  // A table of operator weights by name (the names and values are checked by validateAt).
  void weights(const char* s, std::map<std::string, double>& out) {
    std::map<std::string, std::string> asText;
    r.readParams(s, asText);  // Marks the table and its keys as read; refuses a non-table.
    const toml::table* table = root.at_path(s).as_table();
    if (table == nullptr) return;
    for (const auto& [name, value] : *table) {
      const std::string key(name.str());
      require(value.is_number(), dotted(s, key) + " must be a number (the operator's weight)",
              r.where(s, key));
      out[key] = *value.value<double>();
    }
  }
  // A key of older versions: refused, pointing to gp.operators.
  void replacedByOperators(const char* s, const char* k) {
    if (node(s, k) == nullptr) return;
    throw InputError(dotted(s, k) +
                         " is no longer a key: the variation operators' weights are the table " +
                         defaultOperatorTable() + " (the paper's rates; docs/discovery.md)",
                     r.where(s, k));
  }
  void integer(const char* s, const char* k, int& out, long lo, long hi) {
    r.read(s, k, out, lo, hi);
  }
  void real(const char* s, const char* k, double& out, double lo, double hi) {
    r.read(s, k, out, lo, hi);
  }
  void reals(const char* s, const char* k, std::vector<double>& out) { r.read(s, k, out); }
  void texts(const char* s, const char* k, std::vector<std::string>& out) { r.read(s, k, out); }
  // Seconds (a number above 0), or text parseDuration reads ("10m").
  void duration(const char* s, const char* k, double& out) {
    const toml::node* n = node(s, k);
    if (n != nullptr && n->is_string()) {
      std::string text;
      r.read(s, k, text);
      out = parseDuration(text, r.where(s, k));
      return;
    }
    r.read(s, k, out, 0.0, 1e9);
    require(n == nullptr || out > 0.0,
            dotted(s, k) + " must be above 0 (seconds, or text such as \"10m\")", r.where(s, k));
  }
  void boolean(const char* s, const char* k, bool& out) { r.read(s, k, out); }
  void params(const char* s, std::map<std::string, std::string>& out) { r.readParams(s, out); }
  // `s`.choose: a table of a value or an array of values per key (learner parameters' values
  // hold no commas), or an array of tables (alternatives); `s`.choose_seeds.
  void choices(const char* s, std::map<std::string, std::vector<std::string>>& out,
               std::vector<std::map<std::string, std::string>>& alternatives, int& seeds,
               double& significance, int& randomSets) {
    r.read(s, "choose_seeds", seeds, 2, 100000);
    r.read(s, "choose_significance", significance, 0.0, 0.5);
    r.read(s, "choose_random_sets", randomSets, 0, 1000);
    if (r.readParamsArray(s, "choose", alternatives)) {
      require(!alternatives.empty(), dotted(s, "choose") + " must list at least one alternative",
              r.where(s, "choose"));
      return;
    }
    const std::string section = dotted(s, "choose");
    std::map<std::string, std::string> joined;
    r.readParams(section, joined);
    for (const auto& [key, text] : joined) {
      require(!text.empty(), section + "." + key + " must list at least one value",
              r.where(section, key));
      std::vector<std::string> values;
      for (std::size_t from = 0;;) {
        const std::size_t comma = text.find(',', from);
        values.push_back(text.substr(from, comma - from));
        if (comma == std::string::npos) break;
        from = comma + 1;
      }
      out[key] = values;
    }
  }
  // An array of tables, each a learner's settings (learner.choose_fallback); [] for none.
  void alternatives(const char* s, const char* k,
                    std::vector<std::map<std::string, std::string>>& out) {
    const toml::node* n = node(s, k);
    if (n == nullptr) return;
    require(n->is_array(), dotted(s, k) + " must be an array of tables", r.where(s, k));
    r.readParamsArray(s, k, out);
  }
  void measure(const char* s, const char* k, TrialMeasure& out) {
    std::string name = measureName(out);
    r.read(s, k, name, kMeasures);
    out = static_cast<TrialMeasure>(std::find(kMeasures.begin(), kMeasures.end(), name) -
                                    kMeasures.begin());
  }
  // Left as it is where the key is absent.
  void optionalMeasure(const char* s, const char* k, std::optional<TrialMeasure>& out) {
    if (node(s, k) == nullptr) return;
    TrialMeasure read = out.value_or(TrialMeasure::Mean);
    measure(s, k, read);
    out = read;
  }
};

struct Writer {
  io::TomlWriter w;
  void text(const char* s, const char* k, std::string& v, std::vector<std::string> = {}) {
    w.write(s, k, v);
  }
  void seed(const char* s, const char* k, std::uint64_t& v) {
    if (v > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())) {
      w.write(s, k, std::to_string(v));  // Beyond a TOML integer: as text (Reader::seed).
    } else {
      w.write(s, k, static_cast<std::int64_t>(v));
    }
  }
  // Every registered operator's weight, defaults included.
  void weights(const char* s, std::map<std::string, double>& v) {
    const auto& operators = gp::OperatorRegistry::global().operators();
    const auto resolved = gp::resolvedWeights(v, operators);
    for (std::size_t o = 0; o < operators.size(); ++o) w.write(s, operators[o].name, resolved[o]);
  }
  void replacedByOperators(const char*, const char*) {}
  void integer(const char* s, const char* k, int& v, long, long) {
    w.write(s, k, static_cast<std::int64_t>(v));
  }
  void real(const char* s, const char* k, double& v, double, double) { w.write(s, k, v); }
  void reals(const char* s, const char* k, std::vector<double>& v) { w.write(s, k, v); }
  void texts(const char* s, const char* k, std::vector<std::string>& v) {
    if (!v.empty()) w.write(s, k, v);  // Configs without plug-ins keep their text.
  }
  void duration(const char* s, const char* k, double& v) {
    if (v > 0.0) w.write(s, k, v);  // Configs without a budget keep their text.
  }
  void boolean(const char* s, const char* k, bool& v) { w.write(s, k, v); }
  void params(const char* s, std::map<std::string, std::string>& v) { w.writeParams(s, v); }
  void choices(const char* s, std::map<std::string, std::vector<std::string>>& v,
               std::vector<std::map<std::string, std::string>>& alternatives, int& seeds,
               double& significance, int& randomSets) {
    // Configs without a choice (every resolved one) keep their text.
    if (v.empty() && alternatives.empty()) return;
    for (const auto& [key, values] : v) w.write(dotted(s, "choose"), key, values);
    if (!alternatives.empty()) w.write(s, "choose", alternatives);
    w.write(s, "choose_seeds", static_cast<std::int64_t>(seeds));
    if (significance > 0.0) w.write(s, "choose_significance", significance);
    if (randomSets > 0) w.write(s, "choose_random_sets", static_cast<std::int64_t>(randomSets));
  }
  void alternatives(const char* s, const char* k,
                    std::vector<std::map<std::string, std::string>>& v) {
    if (!v.empty())
      w.write(s, k, v);  // Configs without fallbacks (every resolved one) keep their text.
  }
  void measure(const char* s, const char* k, TrialMeasure& v) { w.write(s, k, measureName(v)); }
  void optionalMeasure(const char* s, const char* k, std::optional<TrialMeasure>& v) {
    if (v) measure(s, k, *v);  // Configs without one keep their text.
  }
};

}  // namespace

namespace {

// Where a config key is: file:line:column plus the key when read from TOML, else the key.
using Place = std::function<std::string(const std::string& section, const std::string& key)>;

std::string plainPlace(const std::string& section, const std::string& key) {
  return section.empty() ? key : section + "." + key;
}

// Refuses a key of `params` that is not one of `names` (the parameters of `owner`), with a
// suggestion, at the key's place in `section`.
// Whether one of `overrides` (key=value) sets `key`.
bool overridden(const std::vector<std::string>& overrides, const std::string& key) {
  return std::any_of(overrides.begin(), overrides.end(), [&](const std::string& o) {
    return std::string_view(o).substr(0, o.find('=')) == key;
  });
}

void requireKnown(const Params& params, const std::vector<std::string>& names,
                  const std::string& owner, const std::string& section, const Place& place) {
  for (const auto& [key, value] : params) {
    require(std::find(names.begin(), names.end(), key) != names.end(),
            "unknown parameter '" + key + "' of " + owner + io::didYouMean(key, names),
            place(section, key));
  }
}

// Runs `make`. An InputError about parameter "<owner>.<key>" (as parameter tables name them) is
// moved to the place of that key in the first of `sections` that sets it, any other to
// `fallback`.
template <typename Make>
auto makeAt(const Make& make, const std::string& owner,
            const std::vector<std::pair<std::string, const Params*>>& sections,
            const std::string& fallback, const Place& place) {
  try {
    return make();
  } catch (const InputError& e) {
    const std::string prefix = owner + ".";
    if (e.where().starts_with(prefix)) {
      const std::string key = e.where().substr(prefix.size());
      for (const auto& [section, params] : sections) {
        if (params->count(key)) throw InputError(e.what(), place(section, key));
      }
    }
    throw InputError(e.what(), fallback);
  }
}

// An alternative of learner.choose (at `section`) that names another learner: a known learner
// that can learn on `environment`, parameters it takes but its budget (which the choice matches
// to the config's learner's episodes), and every training's settings (withCandidate) it makes.
void validateCandidateLearner(const ExperimentConfig& c, const Params& alternative,
                              const std::string& section, env::Environment& environment,
                              const Place& place) {
  const auto& learners = rl::LearnerRegistry::global();
  const auto names = learners.names();
  const std::string& name = alternative.at(kCandidateLearnerKey);
  require(std::find(names.begin(), names.end(), name) != names.end(),
          "unknown learner '" + name + "'" + io::didYouMean(name, names),
          place(section, kCandidateLearnerKey));
  try {
    learners.checkSuitable(name, environment);
  } catch (const InputError& e) {
    throw InputError(e.what(), place(section, kCandidateLearnerKey));
  }
  Params own = alternative;
  own.erase(kCandidateLearnerKey);
  const auto& info = learners.info(name);
  requireKnown(own, paramNames(info.params), "learner " + name, section, place);
  require(!own.contains(info.budgetParam),
          fmt::format("a candidate naming another learner gives no budget: its {} is set so that "
                      "each training plays as many episodes as learner {} plays there "
                      "(docs/learners.md, \"Choosing between learners\")",
                      info.budgetParam, c.learner),
          place(section, info.budgetParam));
  const std::vector<std::pair<std::string, const Params*>> sections{{section, &own}};
  const ExperimentConfig trained = makeAt([&] { return withCandidate(c, alternative); }, name,
                                          sections, place(section, kCandidateLearnerKey), place);
  for (const Params* overrides :
       {&trained.validation.params, &trained.validation.confirmParams, &trained.assessParams,
        &trained.rungParams, static_cast<const Params*>(nullptr)}) {
    Params merged = trained.learnerParams;
    if (overrides != nullptr) {
      for (const auto& [key, value] : *overrides) merged[key] = value;
    }
    makeAt([&] { return learners.make(name, merged); }, name, sections,
           place(section, kCandidateLearnerKey), place);
  }
}

// gp::validate, its errors ("gp.KEY", "gp.operators.NAME") moved to the key's place, after the
// operators' names are checked with a did-you-mean.
void validateGp(const gp::GpConfig& gp, const Place& place) {
  const auto names = gp::OperatorRegistry::global().names();
  for (const auto& [name, weight] : gp.operatorWeights) {
    const std::string suggestion = io::didYouMean(name, names);
    require(
        std::find(names.begin(), names.end(), name) != names.end(),
        "unknown operator '" + name + "' in gp.operators" +
            (suggestion.empty() ? fmt::format(" (known: {})", fmt::join(names, ", ")) : suggestion),
        place("gp.operators", name));
  }
  try {
    gp::validate(gp);
  } catch (const InputError& e) {
    const std::size_t dot = e.where().rfind('.');
    if (!e.where().starts_with("gp.") || dot == std::string::npos) throw;
    throw InputError(e.what(), place(e.where().substr(0, dot), e.where().substr(dot + 1)));
  }
}

// What reading a config does with the plug-ins it names: a config the user gives loads them; one
// read back from a results directory (run/stored_config.hpp) requires them loaded already.
enum class PluginLoading { Load, RequireLoaded };

// InputError unless the plug-in `plugin` (a path) is loaded already.
void requireLoaded(const std::string& plugin, const Place& place) {
  std::error_code ec;
  const std::string file = std::filesystem::canonical(plugin, ec).string();
  const auto loaded = loadedPlugins();
  require(!ec && std::find(loaded.begin(), loaded.end(), file) != loaded.end(),
          "the config names the plug-in " + plugin +
              ", which is not loaded: a config read back from a results directory (a resume, a "
              "checkpoint) loads no code; give the plug-in again to load it (gpfd --plugin " +
              plugin + " ...)",
          place("", "plugins"));
}

void validateAt(const ExperimentConfig& c, const Place& place,
                PluginLoading plugins = PluginLoading::Load) {
  require(isRunName(c.name),
          "name must be letters, digits, '.', '_' and '-', not starting with '.' (it names the "
          "results directory), not '" +
              c.name + "'",
          place("", "name"));
  for (const auto& plugin : c.plugins) {
    if (plugins == PluginLoading::RequireLoaded) {
      requireLoaded(plugin, place);
      continue;
    }
    try {
      loadPlugin(plugin);
    } catch (const InputError& e) {
      throw InputError(e.what() + (" (" + e.where() + ")"), place("", "plugins"));
    }
  }
  const auto& registry = env::Registry::global();
  const auto envs = registry.names();
  require(std::find(envs.begin(), envs.end(), c.env) != envs.end(),
          "unknown environment '" + c.env + "'" + io::didYouMean(c.env, envs),
          place("env", "name"));
  requireKnown(c.envParams, paramNames(registry.info(c.env).params), "environment " + c.env,
               "env.params", place);
  const auto environment = makeAt([&] { return registry.make(c.env, c.envParams); }, c.env,
                                  {{"env.params", &c.envParams}}, place("env", "name"), place);

  const auto& learners = rl::LearnerRegistry::global();
  const auto learnerNames = learners.names();
  require(std::find(learnerNames.begin(), learnerNames.end(), c.learner) != learnerNames.end(),
          "unknown learner '" + c.learner + "'" + io::didYouMean(c.learner, learnerNames),
          place("learner", "name"));
  try {
    learners.checkSuitable(c.learner, *environment);
  } catch (const InputError& e) {
    throw InputError(e.what(), place("learner", "name"));
  }
  const auto learnerParamNames = paramNames(learners.info(c.learner).params);
  requireKnown(c.learnerParams, learnerParamNames, "learner " + c.learner, "learner.params", place);
  requireKnown(c.assessParams, learnerParamNames, "learner " + c.learner, "assess.params", place);
  requireKnown(c.validation.params, learnerParamNames, "learner " + c.learner, "validation.params",
               place);
  requireKnown(c.validation.confirmParams, learnerParamNames, "learner " + c.learner,
               "validation.confirm_params", place);
  requireKnown(c.rungParams, learnerParamNames, "learner " + c.learner, "fitness.rung_params",
               place);
  makeAt([&] { return learners.make(c.learner, c.learnerParams); }, c.learner,
         {{"learner.params", &c.learnerParams}}, place("learner", "name"), place);
  // Each candidate of learner.choose over learner.params.
  for (const auto& [key, values] : c.learnerChoices) {
    require(key != kCandidateLearnerKey,
            "another learner is named in an alternative, learner.choose = [{ learner = \"ars\" "
            "}, ...], not among values per parameter",
            place("learner.choose", key));
    require(std::find(learnerParamNames.begin(), learnerParamNames.end(), key) !=
                learnerParamNames.end(),
            "unknown parameter '" + key + "' of learner " + c.learner +
                io::didYouMean(key, learnerParamNames),
            place("learner.choose", key));
    for (const auto& value : values) {
      Params merged = c.learnerParams;
      merged[key] = value;
      const Params chosen{{key, value}};
      makeAt([&] { return learners.make(c.learner, merged); }, c.learner,
             {{"learner.choose", &chosen}}, place("learner.choose", key), place);
    }
  }
  // Each alternative of learner.choose over learner.params.
  require(c.learnerChoices.empty() || c.learnerAlternatives.empty(),
          "learner.choose is either a table of values per parameter or an array of alternatives",
          place("learner", "choose"));
  const auto checkAlternatives = [&](const std::vector<Params>& listed, const std::string& key) {
    for (std::size_t i = 0; i < listed.size(); ++i) {
      const std::string section = "learner." + key + "[" + std::to_string(i) + "]";
      if (candidateLearner(c, listed[i]) != c.learner) {
        validateCandidateLearner(c, listed[i], section, *environment, place);
        continue;
      }
      Params alternative = listed[i];
      alternative.erase(kCandidateLearnerKey);  // The config's own learner, named.
      requireKnown(alternative, learnerParamNames, "learner " + c.learner, section, place);
      Params merged = c.learnerParams;
      for (const auto& [name, value] : alternative) merged[name] = value;
      makeAt([&] { return learners.make(c.learner, merged); }, c.learner,
             {{section, &alternative}, {"learner.params", &c.learnerParams}}, place("learner", key),
             place);
    }
  };
  checkAlternatives(c.learnerAlternatives, "choose");
  require(c.learnerFallbacks.empty() || choosesLearner(c),
          "learner.choose_fallback is tried where every candidate of learner.choose learns "
          "nothing: give learner.choose too",
          place("learner", "choose_fallback"));
  checkAlternatives(c.learnerFallbacks, "choose_fallback");
  // The significance test compares the original variables' scores per seed, which the random
  // sets' best quarter may replace.
  require(c.choiceSignificance == 0.0 || c.choiceRandomSets == 0,
          "learner.choose_significance and learner.choose_random_sets cannot both be given",
          place("learner", "choose_random_sets"));
  const std::size_t combinations = learnerCandidates(c).size() + c.learnerFallbacks.size();
  require(combinations <= kMaxLearnerChoices,
          fmt::format("learner.choose and learner.choose_fallback list {} combinations; at most {} "
                      "(each costs learner.choose_seeds trainings)",
                      combinations, kMaxLearnerChoices),
          place("learner", "choose"));
  // The assessment, validation and confirmation budgets, as LearningTask sees them.
  const std::vector<std::pair<const Params*, const char*>> budgets{
      {&c.assessParams, "assess.params"},
      {&c.validation.params, "validation.params"},
      {&c.validation.confirmParams, "validation.confirm_params"},
      {&c.rungParams, "fitness.rung_params"}};
  for (const auto& [overrides, section] : budgets) {
    Params merged = c.learnerParams;
    for (const auto& [key, value] : *overrides) merged[key] = value;
    makeAt([&] { return learners.make(c.learner, merged); }, c.learner,
           {{section, overrides}, {"learner.params", &c.learnerParams}}, place("learner", "name"),
           place);
  }
  require(c.validation.confirmSeeds != 1,
          "validation.confirm_seeds must be 0 (no confirmation) or at least 2 (a standard error "
          "needs two trials)",
          place("validation", "confirm_seeds"));
  require(
      c.validation.confirmSeeds == 0 || c.validation.confirmSeeds >= 2 * c.validation.confirmLooks,
      "validation.confirm_looks must leave at least 2 confirmation seeds per look "
      "(confirm_seeds >= 2 * confirm_looks)",
      place("validation", "confirm_looks"));
  require(c.gp.promote == 0 || c.validation.confirms(),
          "fitness.promote needs a confirmation (validation.candidates and "
          "validation.confirm_seeds above 0): its longest rung is the confirmation's training",
          place("fitness", "promote"));
  require(c.rungParams.empty() || c.gp.promote > 0,
          "fitness.rung_params is the middle rung of successive halving: set fitness.promote too",
          place("fitness", "rung_params"));
  require(c.maxTrials == 0 || c.maxTrials >= c.trials,
          "fitness.max_trials must be 0 (no re-evaluation) or at least fitness.trials (" +
              std::to_string(c.trials) + ")",
          place("fitness", "max_trials"));
  try {
    expr::PrimitiveSet::named(c.primitives);
  } catch (const InputError& e) {
    throw InputError(e.what(), place("primitives", "set"));
  }
  require(c.limits.minFeatures <= c.limits.maxFeatures,
          "genome.min_features must not exceed genome.max_features",
          place("genome", "min_features"));
  require(c.initMinDepth <= c.initMaxDepth,
          "genome.init_min_depth must not exceed genome.init_max_depth",
          place("genome", "init_min_depth"));
  require(!c.rejectConstant || c.gp.distinctOffspring,
          "genome.reject_constant needs gp.distinct_offspring = true (it refuses children as that "
          "does)",
          place("genome", "reject_constant"));
  validateGp(c.gp, place);
}

}  // namespace

void keepChoicesWith(ExperimentConfig& config, const Params& given) {
  std::erase_if(config.learnerChoices,
                [&](const auto& choice) { return given.contains(choice.first); });
  // An alternative that sets another value than one given.
  const auto contradicts = [&](const Params& alternative) {
    return std::any_of(alternative.begin(), alternative.end(), [&](const auto& setting) {
      const auto value = given.find(setting.first);
      return value != given.end() && value->second != setting.second;
    });
  };
  const std::size_t alternatives = config.learnerAlternatives.size();
  std::erase_if(config.learnerAlternatives, contradicts);
  // A single one left is applied, unless it names another learner: that stays a choice (of one),
  // which withCandidate applies with the budgets matched once the config is checked.
  if (config.learnerAlternatives.size() == 1 && alternatives > 1 &&
      !config.learnerAlternatives.front().contains(kCandidateLearnerKey)) {
    for (const auto& [key, value] : config.learnerAlternatives.front()) {
      if (!given.contains(key)) config.learnerParams[key] = value;
    }
    config.learnerAlternatives.clear();
  }
  // The fallbacks are a choice's: none without one, and none that sets another value given.
  std::erase_if(config.learnerFallbacks, contradicts);
  if (!choosesLearner(config)) config.learnerFallbacks.clear();
}

namespace {

ExperimentConfig parseConfig(const std::string& text, const std::string& source,
                             const std::vector<std::string>& overrides, PluginLoading plugins) {
  toml::table root = io::parseToml(text, source);
  for (const auto& o : overrides) io::applyOverride(root, o);
  ExperimentConfig config;
  io::TomlReader reader(root, source);
  Reader visitor{reader, root};
  visit(visitor, config);
  reader.finish();
  // A learner parameter an override sets (learner.params.KEY) wins over its choice.
  Params given;
  for (const auto& [key, value] : config.learnerParams) {
    if (overridden(overrides, "learner.params." + key)) given[key] = value;
  }
  keepChoicesWith(config, given);
  // Plug-in paths relative to the config file's directory, stored absolute (for resumes).
  const std::filesystem::path base =
      std::filesystem::is_regular_file(source) ? std::filesystem::path(source).parent_path() : "";
  for (auto& plugin : config.plugins) {
    plugin = std::filesystem::absolute(base / plugin).lexically_normal().string();
  }
  validateAt(
      config,
      [&reader](const std::string& section, const std::string& key) {
        return reader.where(section, key);
      },
      plugins);
  return config;
}

}  // namespace

ExperimentConfig parseExperimentConfig(const std::string& text, const std::string& source,
                                       const std::vector<std::string>& overrides) {
  return parseConfig(text, source, overrides, PluginLoading::Load);
}

ExperimentConfig loadExperimentConfig(const std::string& path,
                                      const std::vector<std::string>& overrides) {
  return parseExperimentConfig(readFile(path), path, overrides);
}

ExperimentConfig parseStoredExperimentConfig(const std::string& text, const std::string& source) {
  return parseConfig(text, source, {}, PluginLoading::RequireLoaded);
}

ExperimentConfig loadStoredExperimentConfig(const std::string& path) {
  return parseStoredExperimentConfig(readFile(path), path);
}

std::string formatExperimentConfig(const ExperimentConfig& config) {
  ExperimentConfig copy = config;
  Writer writer;
  visit(writer, copy);
  return writer.w.text();
}

bool isRunName(const std::string& name) {
  return !name.empty() && name[0] != '.' && std::all_of(name.begin(), name.end(), [](char ch) {
    return (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') ||
           ch == '.' || ch == '_' || ch == '-';
  });
}

void validate(const ExperimentConfig& c) { validateAt(c, plainPlace); }

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
