#include "gpfd/gp/evolution.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>

#include "gpfd/gp/fitness_cache.hpp"
#include "gpfd/gp/init.hpp"
#include "gpfd/gp/operators.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::gp {
namespace {

constexpr double kWorst = -std::numeric_limits<double>::infinity();

double nowSeconds() {
  using namespace std::chrono;
  return duration<double>(steady_clock::now().time_since_epoch()).count();
}

void require(bool ok, const char* field, const std::string& rule) {
  if (!ok) throw InputError(std::string(field) + " must be " + rule, std::string("gp.") + field);
}

// weight / total, in the order of `operators` (a total of exactly 1 leaves the weights as they
// are).
std::vector<double> probabilities(const GpConfig& c, const std::vector<OperatorInfo>& operators) {
  auto p = resolvedWeights(c.operatorWeights, operators);
  double total = 0.0;
  for (const double w : p) total += w;
  for (double& w : p) w /= total;
  return p;
}

}  // namespace

bool ranksAbove(const Individual& a, const Individual& b) {
  const bool finiteA = std::isfinite(a.fitness), finiteB = std::isfinite(b.fitness);
  if (finiteA != finiteB) return finiteA;
  if (a.rung != b.rung) return a.rung > b.rung;
  return a.fitness > b.fitness;
}

void validate(const GpConfig& c) {
  require(c.population >= 2, "population", "at least 2");
  require(c.generations >= 1, "generations", "at least 1");
  const auto& registry = OperatorRegistry::global();
  for (const auto& [name, weight] : c.operatorWeights) {
    if (!registry.contains(name)) {
      throw InputError(fmt::format("unknown operator '{}' in gp.operators (known: {})", name,
                                   fmt::join(registry.names(), ", ")),
                       "gp.operators." + name);
    }
    if (!std::isfinite(weight) || weight < 0) {
      throw InputError(fmt::format("gp.operators.{} must be a finite, non-negative weight, not {}",
                                   name, weight),
                       "gp.operators." + name);
    }
  }
  double total = 0.0;
  for (const double w : resolvedWeights(c.operatorWeights, registry.operators())) total += w;
  if (!(total > 0) || !std::isfinite(total)) {
    throw InputError("gp.operators: the weights must not all be zero, and their sum must be finite",
                     "gp.operators");
  }
  require(c.elitism >= 0 && c.elitism < 1, "elitism", "in [0, 1)");
  require(c.tournamentSize >= 1, "tournament_size", "at least 1");
  require(c.sizePenalty >= 0 && std::isfinite(c.sizePenalty), "size_penalty",
          "finite and non-negative");
  if (!(c.promote >= 0 && c.promote < 1)) {
    throw InputError("fitness.promote must be in [0, 1)", "fitness.promote");
  }
}

std::vector<double> operatorProbabilities(const GpConfig& c) {
  return probabilities(c, OperatorRegistry::global().operators());
}

double crossoverProbability(const GpConfig& c) {
  const auto& operators = OperatorRegistry::global().operators();
  const auto p = probabilities(c, operators);
  double sum = 0.0;
  for (std::size_t o = 0; o < operators.size(); ++o) {
    if (operators[o].parents() == 2) sum += p[o];
  }
  return sum;
}

Evolution::Evolution(GpConfig config, SearchSpace space, Evaluator& evaluator, GenomeReducer reduce,
                     GenomeFilter admissible, std::vector<Evaluator*> rungs)
    : config_(config),
      space_(std::move(space)),
      evaluator_(evaluator),
      reduce_(std::move(reduce)),
      admissible_(std::move(admissible)),
      rungs_(std::move(rungs)),
      rng_(deriveSeed(config.seed, kVariationStream)) {
  validate(config_);
  operators_ = OperatorRegistry::global().operators();
  probabilities_ = probabilities(config_, operators_);
  operatorCounts_.assign(operators_.size(), 0);
}

GenerationStats Evolution::initialize() {
  const double start = nowSeconds();
  generation_ = 0;
  population_.clear();
  if (config_.distinctOffspring) {
    std::set<std::string> keys;
    for (auto& g : distinctChildren(static_cast<std::size_t>(config_.population), keys, true)) {
      population_.push_back({std::move(g), 0.0, 0.0});
    }
    return evaluate(start);
  }
  for (int i = 0; i < config_.population; ++i) {
    population_.push_back({reduced(randomGenome(rng_, space_)), 0.0, 0.0});
  }
  return evaluate(start);
}

GenerationStats Evolution::step() {
  const double start = nowSeconds();
  std::vector<std::size_t> order(population_.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return ranksAbove(population_[a], population_[b]);
  });
  const auto elites = static_cast<std::size_t>(
      std::lround(config_.elitism * static_cast<double>(config_.population)));
  std::vector<Individual> next;
  next.reserve(population_.size());
  for (std::size_t e = 0; e < elites; ++e) next.push_back(population_[order[e]]);
  if (config_.distinctOffspring) {
    std::set<std::string> keys;
    for (const auto& elite : next) keys.insert(canonicalKey(elite.genome));
    for (auto& g : distinctChildren(population_.size() - elites, keys, false)) {
      next.push_back({std::move(g), 0.0, 0.0});
    }
  } else {
    for (auto& g : breed(population_.size() - elites))
      next.push_back({reduced(std::move(g)), 0.0, 0.0});
  }
  population_ = std::move(next);
  ++generation_;
  return evaluate(start);
}

void Evolution::run(const std::function<bool(const GenerationStats&)>& onGeneration) {
  if (!onGeneration(initialize())) return;
  while (generation_ + 1 < config_.generations) {
    if (!onGeneration(step())) return;
  }
}

EvolutionState Evolution::state() const {
  return {generation_, population_, rng_.state(), operatorCounts_};
}

void Evolution::restore(const EvolutionState& state) {
  generation_ = state.generation;
  population_ = state.population;
  rng_.setState(state.rng);
  operatorCounts_ = state.operatorCounts;
  operatorCounts_.resize(operators_.size(), 0);
}

const Individual& Evolution::best() const {
  return *std::max_element(
      population_.begin(), population_.end(),
      [](const Individual& a, const Individual& b) { return ranksAbove(b, a); });
}

const Individual& Evolution::tournament() {
  const Individual* winner = nullptr;
  for (int t = 0; t < config_.tournamentSize; ++t) {
    const Individual& candidate = population_[rng_.below(population_.size())];
    if (winner == nullptr || ranksAbove(candidate, *winner)) winner = &candidate;
  }
  return *winner;
}

std::vector<expr::Genome> Evolution::breed(std::size_t count) {
  // Falls to the last operator with a positive probability when rounding leaves u past them all.
  std::size_t fallback = 0;
  for (std::size_t o = 0; o < probabilities_.size(); ++o) {
    if (probabilities_[o] > 0) fallback = o;
  }
  std::vector<expr::Genome> children;
  children.reserve(count + 1);
  while (children.size() < count) {
    double u = rng_.uniform();
    std::size_t chosen = fallback;
    for (std::size_t o = 0; o < probabilities_.size(); ++o) {
      if (u < probabilities_[o]) {
        chosen = o;
        break;
      }
      u -= probabilities_[o];
    }
    ++operatorCounts_[chosen];
    const auto& apply = operators_[chosen].apply;
    if (const auto* crossover = std::get_if<Crossover>(&apply)) {
      const expr::Genome& a = tournament().genome;
      const expr::Genome& b = tournament().genome;
      auto [first, second] = (*crossover)(rng_, a, b, space_);
      children.push_back(std::move(first));
      if (children.size() < count) children.push_back(std::move(second));
    } else {
      const expr::Genome& parent = tournament().genome;
      children.push_back(std::get<Mutation>(apply)(rng_, parent, space_));
    }
  }
  return children;
}

std::vector<expr::Genome> Evolution::distinctChildren(std::size_t count,
                                                      std::set<std::string>& keys, bool random) {
  std::vector<expr::Genome> children;
  children.reserve(count);
  int refused = 0;  // In a row, for the child being made.
  while (children.size() < count) {
    std::vector<expr::Genome> batch;
    if (random || refused >= kBreedRetries) {
      batch.push_back(randomGenome(rng_, space_));
    } else {
      batch = breed(std::min<std::size_t>(2, count - children.size()));
    }
    for (auto& candidate : batch) {
      if (children.size() == count) break;
      auto genome = reduced(std::move(candidate));
      std::string key = canonicalKey(genome);
      const bool fresh = !keys.contains(key) && (!admissible_ || admissible_(genome));
      if (!fresh && refused < kBreedRetries + kRandomRetries) {
        ++refused;
        continue;
      }
      keys.insert(std::move(key));
      children.push_back(std::move(genome));
      refused = 0;
    }
  }
  return children;
}

expr::Genome Evolution::reduced(expr::Genome genome) const {
  return reduce_ ? reduce_(genome) : genome;
}

void Evolution::setFitness(Individual& ind, double raw, int rung) const {
  ind.rung = rung;
  ind.rawFitness = std::isfinite(raw) ? raw : kWorst;
  ind.fitness = std::isfinite(raw)
                    ? raw - config_.sizePenalty * static_cast<double>(ind.genome.size())
                    : kWorst;
}

int Evolution::promote() {
  if (!(config_.promote > 0)) return 0;
  std::vector<std::size_t> field;  // The individuals at the rung below, best first.
  for (std::size_t i = 0; i < population_.size(); ++i) {
    if (std::isfinite(population_[i].fitness)) field.push_back(i);
  }
  int evaluations = 0;
  for (std::size_t r = 1; r <= rungs_.size(); ++r) {
    std::stable_sort(field.begin(), field.end(), [&](std::size_t a, std::size_t b) {
      return ranksAbove(population_[a], population_[b]);
    });
    field.resize(std::min(field.size(), static_cast<std::size_t>(std::ceil(
                                            config_.promote * static_cast<double>(field.size())))));
    if (field.empty()) break;
    std::vector<const expr::Genome*> genomes;
    std::vector<std::uint64_t> seeds;
    for (const std::size_t i : field) {
      genomes.push_back(&population_[i].genome);
      seeds.push_back(config_.commonRandomNumbers
                          ? deriveSeed(config_.seed, kRungStream, generation_, r)
                          : deriveSeed(config_.seed, kRungStream, generation_, r, i));
    }
    const auto raw = rungs_[r - 1]->evaluate(genomes, seeds);
    for (std::size_t k = 0; k < field.size(); ++k) {
      setFitness(population_[field[k]], raw[k], static_cast<int>(r));
    }
    evaluations += static_cast<int>(field.size());
    // A non-finite result at a longer rung ends the individual's climb.
    std::erase_if(field, [&](std::size_t i) { return !std::isfinite(population_[i].fitness); });
  }
  return evaluations;
}

GenerationStats Evolution::evaluate(double startSeconds) {
  std::vector<const expr::Genome*> genomes;
  std::vector<std::uint64_t> seeds;
  for (std::size_t i = 0; i < population_.size(); ++i) {
    genomes.push_back(&population_[i].genome);
    seeds.push_back(config_.commonRandomNumbers
                        ? deriveSeed(config_.seed, kEvaluationStream, generation_)
                        : deriveSeed(config_.seed, kEvaluationStream, generation_, i));
  }
  const auto raw = evaluator_.evaluate(genomes, seeds);
  for (std::size_t i = 0; i < population_.size(); ++i) setFitness(population_[i], raw[i], 0);

  GenerationStats stats;
  stats.generation = generation_;
  stats.evaluations = static_cast<int>(genomes.size());
  std::vector<double> finite;
  double sizeSum = 0.0, featureSum = 0.0;
  for (const auto& ind : population_) {
    if (std::isfinite(ind.fitness)) finite.push_back(ind.fitness);
    sizeSum += static_cast<double>(ind.genome.size());
    featureSum += static_cast<double>(ind.genome.featureCount());
  }
  const auto n = static_cast<double>(population_.size());
  stats.invalid = static_cast<int>(population_.size() - finite.size());
  stats.meanSize = sizeSum / n;
  stats.meanFeatures = featureSum / n;
  if (finite.empty()) {
    stats.mean = stats.median = kWorst;
  } else {
    stats.mean =
        std::accumulate(finite.begin(), finite.end(), 0.0) / static_cast<double>(finite.size());
    std::sort(finite.begin(), finite.end());
    const std::size_t m = finite.size() / 2;
    stats.median = finite.size() % 2 ? finite[m] : 0.5 * (finite[m - 1] + finite[m]);
  }
  stats.promotions = promote();
  stats.bestIndividual = best();
  stats.best = stats.bestIndividual.fitness;
  stats.seconds = nowSeconds() - startSeconds;
  return stats;
}

}  // namespace gpfd::gp
