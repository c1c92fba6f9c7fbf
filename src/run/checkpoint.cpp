#include "gpfd/run/checkpoint.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

#include "gpfd/expr/parse.hpp"
#include "gpfd/expr/print.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::run {
namespace {

using nlohmann::json;
constexpr const char* kFormat = "gpfd-checkpoint-2";

// Doubles round-trip exactly through JSON numbers; -inf (the worst fitness) is stored as null.
json number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }
double number(const json& j) {
  return j.is_null() ? -std::numeric_limits<double>::infinity() : j.get<double>();
}

json numbers(const std::vector<double>& values) {
  json array = json::array();
  for (const double v : values) array.push_back(number(v));
  return array;
}
std::vector<double> numbersFrom(const json& array) {
  std::vector<double> values;
  for (const auto& v : array) values.push_back(number(v));
  return values;
}

// A genome as its features' S-expressions with variables as x[i]: exact and compact.
json genomeJson(const expr::Genome& g) {
  json features = json::array();
  for (std::size_t k = 0; k < g.featureCount(); ++k)
    features.push_back(expr::toSexpr(g.feature(k), {}));
  return features;
}

expr::Genome genomeFrom(const json& j) {
  // Index-only names: any x[i] up to the hard size cap parses; the evolution re-checks limits.
  static const expr::VariableNames names(65535, "");
  expr::Genome g;
  for (const auto& f : j) g.addFeature(expr::parseSexpr(f.get<std::string>(), names));
  return g;
}

}  // namespace

std::string formatCheckpoint(const Checkpoint& c) {
  json population = json::array();
  for (const auto& ind : c.state.population) {
    json entry = {{"features", genomeJson(ind.genome)},
                  {"raw", number(ind.rawFitness)},
                  {"fitness", number(ind.fitness)}};
    if (ind.rung > 0) entry["rung"] = ind.rung;  // Successive halving only: older files stay.
    population.push_back(std::move(entry));
  }
  json cache = json::array();
  for (const auto& [key, record] : c.cache) {
    cache.push_back({key, number(record.mean), record.trials});
  }
  json validated = json::array();
  for (const auto& set : c.validation.sets) {
    validated.push_back(
        {{"key", set.key},
         {"generation", set.generation},
         {"gp_fitness", std::isnan(set.gpFitness) ? json("nan") : number(set.gpFitness)},
         {"gp_trials", set.gpTrials},
         {"scores", numbers(set.scores)}});
  }
  json history = json::array();
  for (const auto& r : c.history) {
    history.push_back({{"generation", r.generation},
                       {"best", number(r.best)},
                       {"mean", number(r.mean)},
                       {"median", number(r.median)},
                       {"mean_size", r.meanSize},
                       {"mean_features", r.meanFeatures},
                       {"evaluations", r.evaluations},
                       {"reevaluations", r.reevaluations},
                       {"cache_hits", r.cacheHits},
                       {"seconds", r.seconds},
                       {"best_genome", genomeJson(r.bestGenome)}});
    if (r.promotions > 0) history.back()["promotions"] = r.promotions;  // Older files stay.
  }
  const auto& rng = c.state.rng;
  json j = {{"format", kFormat},
            {"version", c.version},
            {"config", c.config},
            {"generation", c.state.generation},
            {"rng",
             {{"words", {rng.words[0], rng.words[1], rng.words[2], rng.words[3]}},
              {"has_spare", rng.hasSpare},
              {"spare", rng.spare}}},
            {"operator_counts", c.state.operatorCounts},
            {"population", population},
            {"cache", cache},
            {"history", history},
            {"validation",
             {{"sets", validated},
              {"no_learning", numbers(c.validation.noLearning)},
              {"confirmation",
               {{"key", c.validation.confirmation.key},
                {"winner", numbers(c.validation.confirmation.winner)},
                {"original", numbers(c.validation.confirmation.original)},
                {"no_learning", numbers(c.validation.confirmation.noLearning)},
                {"no_learning_level", c.validation.confirmation.noLearningLevel}}},
              {"final_generation", c.validation.finalGeneration},
              {"seconds", c.validation.seconds}}}};
  return j.dump(1) + "\n";
}

Checkpoint parseCheckpoint(const std::string& text, const std::string& source) {
  try {
    const json j = json::parse(text);
    if (j.at("format") != kFormat) throw InputError("not a gpfd checkpoint", source);
    Checkpoint c;
    c.version = j.at("version").get<std::string>();
    c.config = j.at("config").get<std::string>();
    c.state.generation = j.at("generation").get<int>();
    const auto& rng = j.at("rng");
    for (int w = 0; w < 4; ++w) c.state.rng.words[w] = rng.at("words").at(w).get<std::uint64_t>();
    c.state.rng.hasSpare = rng.at("has_spare").get<bool>();
    c.state.rng.spare = rng.at("spare").get<double>();
    c.state.operatorCounts = j.at("operator_counts").get<std::vector<long>>();
    for (const auto& ind : j.at("population")) {
      c.state.population.push_back({genomeFrom(ind.at("features")), number(ind.at("raw")),
                                    number(ind.at("fitness")), ind.value("rung", 0)});
    }
    for (const auto& entry : j.at("cache")) {
      c.cache[entry.at(0).get<std::string>()] = {number(entry.at(1)), entry.at(2).get<int>()};
    }
    for (const auto& r : j.at("history")) {
      c.history.push_back({r.at("generation").get<int>(), number(r.at("best")),
                           number(r.at("mean")), number(r.at("median")),
                           r.at("mean_size").get<double>(), r.at("mean_features").get<double>(),
                           r.at("evaluations").get<int>(), r.at("reevaluations").get<int>(),
                           r.at("cache_hits").get<int>(), r.at("seconds").get<double>(),
                           genomeFrom(r.at("best_genome")), r.value("promotions", 0)});
    }
    const auto& validation = j.at("validation");
    for (const auto& v : validation.at("sets")) {
      ValidatedSet set;
      set.key = v.at("key").get<std::string>();
      if (!set.key.empty()) set.genome = gp::genomeFromKey(set.key);
      set.generation = v.at("generation").get<int>();
      const auto& fitness = v.at("gp_fitness");
      set.gpFitness =
          fitness.is_string() ? std::numeric_limits<double>::quiet_NaN() : number(fitness);
      set.gpTrials = v.at("gp_trials").get<int>();
      set.scores = numbersFrom(v.at("scores"));
      c.validation.sets.push_back(std::move(set));
    }
    if (validation.contains("confirmation")) {  // Checkpoints written before confirmation lack it.
      const auto& confirmation = validation.at("confirmation");
      c.validation.confirmation.key = confirmation.at("key").get<std::string>();
      c.validation.confirmation.winner = numbersFrom(confirmation.at("winner"));
      c.validation.confirmation.original = numbersFrom(confirmation.at("original"));
      // Checkpoints written before the no-learning reference lack it.
      if (confirmation.contains("no_learning")) {
        c.validation.confirmation.noLearning = numbersFrom(confirmation.at("no_learning"));
        c.validation.confirmation.noLearningLevel =
            confirmation.at("no_learning_level").get<double>();
      }
    }
    if (validation.contains("no_learning")) {
      c.validation.noLearning = numbersFrom(validation.at("no_learning"));
    }
    c.validation.finalGeneration = validation.at("final_generation").get<int>();
    c.validation.seconds = validation.at("seconds").get<double>();
    return c;
  } catch (const json::exception& e) {
    // The parser quotes what it last read, which can be the whole stored config: cut it.
    std::string what = e.what();
    if (const auto quote = what.find("; last read: "); quote != std::string::npos) {
      what.resize(quote);
    }
    throw InputError("corrupt checkpoint: " + what, source);
  } catch (const InputError& e) {
    throw InputError("corrupt checkpoint: " + e.message(), source);
  }
}

std::string formatGenerationsCsv(const std::vector<GenerationRecord>& history) {
  std::string out =
      "generation,best,mean,median,mean_size,mean_features,evaluations,reevaluations,cache_hits,"
      "seconds\n";
  for (const auto& r : history) {
    out += fmt::format("{},{},{},{},{},{},{},{},{},{:.3f}\n", r.generation, r.best, r.mean,
                       r.median, r.meanSize, r.meanFeatures, r.evaluations, r.reevaluations,
                       r.cacheHits, r.seconds);
  }
  return out;
}

}  // namespace gpfd::run
