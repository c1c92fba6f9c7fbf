// gp: the generational evolution loop of the paper (section 4): elitism, tournament selection,
// the registered variation operators drawn by weight (by default the paper's five with its
// probabilities), and a size penalty; fitness maximised.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "gpfd/gp/evaluator.hpp"
#include "gpfd/gp/operator_registry.hpp"
#include "gpfd/gp/search_space.hpp"
#include "gpfd/util/rng.hpp"

namespace gpfd::gp {

// Defaults are the paper's: the operators' default weights (operator_registry.cpp) and 10% elitism.
struct GpConfig {
  int population = 100;
  int generations = 50;
  // Weights of the variation operators by registered name; an operator left out has its default
  // weight. Each is finite and non-negative, and not all are zero.
  std::map<std::string, double> operatorWeights;
  double elitism = 0.1;  // Fraction of the population copied unchanged (rounded).
  int tournamentSize = 3;
  double sizePenalty = 0.0;  // Subtracted per node from the raw fitness.
  // Common random numbers: every individual of a generation is evaluated with the same seed,
  // deriveSeed(seed, kEvaluationStream, generation), so that fitness differences within a
  // generation are paired. Otherwise each individual has its own seed.
  bool commonRandomNumbers = false;
  // Distinct offspring: a child that repeats a genome of its generation (elites and the children
  // before it, compared by canonicalKey after the reducer), or that the Evolution's filter
  // refuses, is bred again; after kBreedRetries refusals in a row a random genome stands in
  // (also checked), and after kRandomRetries more the last one is kept, so that a small search
  // space still fills its generation. Generation 0 is drawn the same way. Without it a converged
  // population breeds copies of its best, which the fitness cache answers without a trial: the
  // generations go on, the search does not.
  bool distinctOffspring = false;
  // Successive halving (docs/discovery.md): after the generation's evaluation, the best
  // ceil(promote x n) of its n individuals with a finite fitness are evaluated again by the first
  // longer rung's evaluator (Evolution's `rungs`), the best promote share of those by the next,
  // and so on; an individual's fitness is that of the longest rung it reached, and selection ranks
  // a longer rung above a shorter one (ranksAbove). 0: off.
  double promote = 0.0;
  std::uint64_t seed = 1;
};

// Throws InputError naming the first out-of-range field as its config key ("gp.elitism",
// "gp.operators.NAME"); an unknown operator's error lists the known ones.
void validate(const GpConfig& config);

// Probabilities of the registered operators, in registration order: weight / total weight.
std::vector<double> operatorProbabilities(const GpConfig& config);
// The probability that a child comes from an operator with two parents.
double crossoverProbability(const GpConfig& config);

struct Individual {
  expr::Genome genome;
  double rawFitness = 0.0;  // As the evaluator returned it (non-finite -> -inf).
  double fitness = 0.0;     // rawFitness minus the size penalty; what selection uses.
  // The rung its fitness comes from this generation: 0 the short trials, r the r-th longer rung
  // (GpConfig::promote).
  int rung = 0;
};

// Selection's order: a finite fitness above a non-finite one, then a longer rung above a shorter
// one, then the higher fitness. Without promotions (every rung 0) it is `a.fitness > b.fitness`.
bool ranksAbove(const Individual& a, const Individual& b);

struct GenerationStats {
  int generation = 0;
  double best = 0.0;          // Penalised fitness of the best individual.
  double mean = 0.0;          // Over the individuals with a finite fitness.
  double median = 0.0;        // Mean and median of the short trials' fitness (rung 0).
  double meanSize = 0.0;      // Nodes per individual.
  double meanFeatures = 0.0;  // Features per individual.
  int evaluations = 0;        // Genomes sent to the evaluator this generation (elites included).
  int promotions = 0;         // Evaluations at longer rungs (GpConfig::promote).
  int invalid = 0;            // Individuals with a non-finite fitness.
  double seconds = 0.0;       // Wall time of the generation.
  Individual bestIndividual;
};

// Everything a checkpoint needs to continue a run exactly.
struct EvolutionState {
  int generation = -1;
  std::vector<Individual> population;
  Rng::State rng{};
  std::vector<long> operatorCounts;
};

// Rewrites a new genome before it is evaluated (e.g. drops redundant features); must be a pure
// function of the genome and keep it within the search space's limits.
using GenomeReducer = std::function<expr::Genome(const expr::Genome&)>;
// Whether a reduced genome may join the population (e.g. not constant on visited states); must be
// a pure function of the genome. Used only with GpConfig::distinctOffspring.
using GenomeFilter = std::function<bool(const expr::Genome&)>;

// Contract: the run is a pure function of (config, space, fitness, reducer, rungs); evaluation
// seeds are deriveSeed(config.seed, kEvaluationStream, generation, index), or
// deriveSeed(config.seed, kEvaluationStream, generation) for every index with common random
// numbers; at rung r > 0, deriveSeed(config.seed, kRungStream, generation, r, index) (without the
// index likewise). Every individual, elites included, is passed to the evaluator each generation,
// so that an evaluator that re-evaluates (CachingEvaluator) can refine the fitness of the
// survivors.
class Evolution {
 public:
  static constexpr std::uint64_t kVariationStream = 0;
  static constexpr std::uint64_t kEvaluationStream = 1;
  static constexpr std::uint64_t kRungStream = 2;

  static constexpr int kBreedRetries = 8;
  static constexpr int kRandomRetries = 8;

  // `rungs`: the evaluators of the longer rungs, shortest first (used with config.promote > 0).
  Evolution(GpConfig config, SearchSpace space, Evaluator& evaluator, GenomeReducer reduce = {},
            GenomeFilter admissible = {}, std::vector<Evaluator*> rungs = {});

  // Creates and evaluates generation 0.
  GenerationStats initialize();
  // Breeds and evaluates the next generation.
  GenerationStats step();
  // initialize() then step() until config.generations generations exist (0 .. generations - 1);
  // `onGeneration` sees each generation's statistics and may return false to stop early.
  void run(const std::function<bool(const GenerationStats&)>& onGeneration);

  int generation() const { return generation_; }
  const std::vector<Individual>& population() const { return population_; }
  const Individual& best() const;  // Best individual of the current population.
  const GpConfig& config() const { return config_; }
  const SearchSpace& space() const { return space_; }
  // Operator applications so far, in registration order (for frequency checks).
  const std::vector<long>& operatorCounts() const { return operatorCounts_; }

  EvolutionState state() const;
  // Continues from a saved state: the next step() breeds generation state.generation + 1.
  void restore(const EvolutionState& state);

 private:
  const Individual& tournament();
  std::vector<expr::Genome> breed(std::size_t count);
  // GpConfig::distinctOffspring: `count` reduced genomes, bred (or drawn at random: `random`),
  // none repeating a key in `keys` (to which theirs are added), each admissible, as far as the
  // retries allow.
  std::vector<expr::Genome> distinctChildren(std::size_t count, std::set<std::string>& keys,
                                             bool random);
  // Evaluates the whole population and computes the statistics.
  GenerationStats evaluate(double startSeconds);
  // GpConfig::promote: the best of each rung evaluated at the next; how many evaluations.
  int promote();
  // rawFitness from the evaluator's `raw` (non-finite -> -inf), fitness less the size penalty.
  void setFitness(Individual& ind, double raw, int rung) const;
  expr::Genome reduced(expr::Genome genome) const;

  GpConfig config_;
  // The registered operators when the run began, and their probabilities.
  std::vector<OperatorInfo> operators_;
  std::vector<double> probabilities_;
  SearchSpace space_;
  Evaluator& evaluator_;
  GenomeReducer reduce_;
  GenomeFilter admissible_;
  std::vector<Evaluator*> rungs_;
  Rng rng_;
  int generation_ = -1;
  std::vector<Individual> population_;
  std::vector<long> operatorCounts_;
};

}  // namespace gpfd::gp
