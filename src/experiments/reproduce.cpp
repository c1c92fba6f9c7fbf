#include "gpfd/experiments/reproduce.hpp"

#include <fmt/format.h>

#include <chrono>
#include <filesystem>
#include <map>
#include <optional>
#include <sstream>

#include "gpfd/experiments/bench_jit.hpp"
#include "gpfd/expr/features_file.hpp"
#include "gpfd/expr/parse.hpp"
#include "gpfd/io/gnuplot.hpp"
#include "gpfd/io/report.hpp"
#include "gpfd/run/assessment.hpp"
#include "gpfd/run/discovery.hpp"
#include "gpfd/run/method_verdict.hpp"
#include "gpfd/run/run_set.hpp"
#include "gpfd/run/validation.hpp"
#include "gpfd/service/configs.hpp"
#include "gpfd/service/evolve.hpp"
#include "gpfd/service/results_directory.hpp"
#include "gpfd/util/atomic_file.hpp"
#include "gpfd/util/directory_lock.hpp"
#include "gpfd/util/error.hpp"
#include "gpfd/util/number.hpp"

namespace gpfd::experiments {
using namespace gpfd::run;  // The run module's names, used throughout.
namespace {
namespace fs = std::filesystem;

// Fresh trial seeds on which each run's returned features are re-measured.
constexpr int kRemeasureSeeds = 30;

class Experiment {
 public:
  Experiment(const ReproduceOptions& o, std::string figure) : o_(o), dir_(o.outDir + "/" + figure) {
    createDirectories(dir_);
  }

  const std::string& dir() const { return dir_; }
  const ReproduceOptions& options() const { return o_; }
  // Ends the reproduction with Interrupted once a stop was asked for (between steps).
  void checkStop(const std::string& dir) const {
    if (o_.stop != nullptr && o_.stop->load()) {
      throw Interrupted("interrupted; run the same command again to continue", dir);
    }
  }
  // Compute time of the experiment's steps, whether they ran now or in an earlier invocation:
  // the GP runs' generation times and the assessments' recorded times.
  double evolveSeconds() const { return evolveSeconds_; }
  double validationSeconds() const { return validationSeconds_; }
  double assessSeconds() const { return assessSeconds_; }

  ExperimentConfig config(const std::string& base, std::vector<std::string> overrides = {}) const {
    overrides.insert(overrides.begin(), o_.overrides.begin(), o_.overrides.end());
    overrides.push_back("seed=" + std::to_string(o_.seed));
    return service::loadConfig(o_.paperScale ? base : base + "-quick", overrides);
  }

  // Runs, resumes, or reuses the GP run in dir()/name; returns its history. A run asked for
  // again in this invocation is not resumed a second time.
  const std::vector<GenerationRecord>& evolve(const ExperimentConfig& config,
                                              const std::string& name) {
    if (const auto done = histories_.find(name); done != histories_.end()) return done->second;
    const std::string dir = dir_ + "/" + name;
    checkStop(dir);
    const DirectoryLock lock = service::lockDirectory(dir);  // Also against `gpfd evolve --resume`.
    DiscoveryOptions d;
    d.outDir = dir;
    d.threads = o_.threads;
    d.version = o_.version;
    d.revision = o_.revision;
    auto run = service::openRun(config, d, std::nullopt);
    static const std::atomic<bool> never{false};
    run->run(
        [&](const GenerationRecord& r) {
          if (!o_.quiet) {
            fmt::print("  {}: generation {} best {:.6g} mean {:.6g} ({:.1f} s)\n", name,
                       r.generation, r.best, r.mean, r.seconds);
            std::fflush(stdout);
          }
        },
        o_.stop ? *o_.stop : never);
    checkStop(dir);
    for (const auto& r : run->history()) evolveSeconds_ += r.seconds;
    validationSeconds_ += run->validation().seconds;
    outcomes_[name] = outcomeOf(*run, 1);
    return histories_[name] = run->history();
  }

  // What the GP run in dir()/name returned (evolve() it first).
  const RunOutcome& outcome(const std::string& name) const { return outcomes_.at(name); }

  // The trial score of the run's returned features on kRemeasureSeeds fresh seeds (Validator's
  // re-measuring stream), cached in dir()/name/remeasured.csv.
  Summary remeasure(const ExperimentConfig& config, const std::string& name,
                    const expr::Genome& returned) {
    const std::string path = dir_ + "/" + name + "/remeasured.csv";
    std::vector<double> scores;
    if (fs::exists(path)) {
      std::istringstream in(readFile(path));
      for (std::string line; std::getline(in, line);) {
        if (!line.empty() && line != "score") scores.push_back(std::stod(line));
      }
      return summarize(scores);
    }
    // The trial behind the reported score: the confirmation's where the run confirms.
    ThreadTrialRunner runner(o_.threads);
    const Validator validator(config, runner,
                              config.validation.confirms() ? LearningTask::Budget::Confirmation
                                                           : LearningTask::Budget::Validation,
                              kRemeasureSeeds, Validator::kRemeasureStream);
    scores = validator.score({TrialFeatures::ofGenome(returned, config.withOriginal)})[0];
    std::string csv = "score\n";
    for (const double v : scores) csv += fmt::format("{}\n", v);
    writeFileAtomically(path, csv);
    return summarize(scores);
  }

  // The discovered features of the GP run in dir()/name.
  expr::FeaturesFile discovered(const std::string& name, const LearningTask& task) const {
    return expr::readFeaturesFile(dir_ + "/" + name + "/best.features", task.stateNames(),
                                  task.config().env);
  }

  // Assesses the sets into dir()/name unless a finished assessment is there.
  void assess(const LearningTask& task, const std::vector<FeatureSet>& sets,
              const std::string& name, const std::string& title) {
    const std::string dir = dir_ + "/" + name;
    checkStop(dir);
    if (fs::exists(dir + "/summary.csv")) {
      if (fs::exists(dir + "/seconds.txt"))
        assessSeconds_ += parseNumber(readFile(dir + "/seconds.txt"), dir + "/seconds.txt");
      return;
    }
    const auto start = std::chrono::steady_clock::now();
    if (!o_.quiet) {
      fmt::print("  {}: {} feature sets x {} runs\n", name, sets.size(), task.config().assessRuns);
      std::fflush(stdout);
    }
    ThreadTrialRunner runner(o_.threads);
    const auto result =
        runAssessment(task, sets, task.config().assessRuns, task.config().seed, runner);
    createDirectories(dir);
    writeAssessment(dir, result, summarizeAssessment(result, 0), title,
                    rl::LearnerRegistry::global().info(task.config().learner).rowName);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    writeFileAtomically(dir + "/seconds.txt", fmt::format("{:.1f}\n", seconds));
    assessSeconds_ += seconds;
  }

 private:
  const ReproduceOptions& o_;
  std::string dir_;
  double evolveSeconds_ = 0.0;
  double validationSeconds_ = 0.0;
  double assessSeconds_ = 0.0;
  std::map<std::string, std::vector<GenerationRecord>> histories_;  // GP runs done, by name.
  std::map<std::string, RunOutcome> outcomes_;                      // Their outcomes, by name.
};

// GP fitness per generation: best (and mean) of each run.
void fitnessPlot(const std::string& base, const std::string& title,
                 const std::vector<std::pair<std::string, std::vector<GenerationRecord>>>& runs,
                 bool withMean) {
  io::LinePlot plot{title, "generation", "fitness", {}, false};
  for (const auto& [name, history] : runs) {
    io::Series best{runs.size() > 1 ? name + " best" : "best", {}, {}, {}, {}};
    io::Series mean{runs.size() > 1 ? name + " mean" : "population mean", {}, {}, {}, {}};
    for (const auto& r : history) {
      best.x.push_back(r.generation);
      best.y.push_back(r.best);
      if (std::isfinite(r.mean)) {
        mean.x.push_back(r.generation);
        mean.y.push_back(r.mean);
      }
    }
    plot.series.push_back(best);
    if (withMean) plot.series.push_back(mean);
  }
  io::plotLines(base, plot);
}

// "k=v, k=v" of a parameter map ("-" when empty).
std::string joined(const std::map<std::string, std::string>& params) {
  std::string text;
  for (const auto& [key, value] : params) text += (text.empty() ? "" : ", ") + key + "=" + value;
  return text.empty() ? "-" : text;
}

// The settings of a benchmark experiment, for the report.
std::vector<std::vector<std::string>> settingsTable(const ExperimentConfig& c) {
  return {
      {"setting", "value"},
      {"config", "`" + c.name + "` (seed " + std::to_string(c.seed) + ")"},
      {"environment", c.env + " (" + joined(c.envParams) + ")"},
      {"learner, short trial", c.learner + " (" + joined(c.learnerParams) + ")"},
      {"trials per fitness",
       c.maxTrials > 0 ? fmt::format("{}, re-evaluated up to {} per genome", c.trials, c.maxTrials)
                       : std::to_string(c.trials)},
      {"feature sets",
       std::string(c.dropRedundant ? "redundant features dropped" : "redundant features kept") +
           (c.normalise ? ", normalised" : "") +
           (c.gp.commonRandomNumbers ? ", common seeds per generation" : "")},
      {"validation",
       c.validation.candidates > 0
           ? fmt::format(
                 "hall of fame of {} + the original variables, {} seeds ({}){}",
                 c.validation.candidates, c.validation.seeds, joined(c.validation.params),
                 c.validation.confirms()
                     ? fmt::format("; winner confirmed on {} fresh seeds ({}; {}; {} looks)",
                                   c.validation.confirmSeeds, joined(c.validation.confirmParams),
                                   measureName(c.validation.confirmMeasure),
                                   c.validation.confirmLooks)
                     : std::string())
           : "none (the GP's best is returned)"},
      {"GP", fmt::format("population {}, {} generations, crossover {:.3g}, elitism {}, "
                         "tournament {}, size penalty {} per node",
                         c.gp.population, c.gp.generations, gp::crossoverProbability(c.gp),
                         c.gp.elitism, c.gp.tournamentSize, c.gp.sizePenalty)},
      {"primitives", c.primitives + (c.withOriginal ? " (features added to the variables)"
                                                    : " (features replace the variables)")},
      {"long test",
       fmt::format("{} runs per feature set ({})", c.assessRuns, joined(c.assessParams))}};
}

std::string featuresText(const expr::FeaturesFile& f) {
  std::string text;
  for (std::size_t k = 0; k < f.genome.featureCount(); ++k) {
    text += fmt::format("f{} = {}\n", k + 1, expr::toInfix(f.genome.feature(k), f.variables));
  }
  return text;
}

// The method-level results of an earlier reproduction for a benchmark, when there are some.
std::optional<MethodVerdict> baselineVerdict(const ReproduceOptions& o, const std::string& figure,
                                             const std::string& name) {
  if (o.baselineDir.empty()) return std::nullopt;
  const std::string path = o.baselineDir + "/" + figure + "/method-" + name + ".csv";
  if (!fs::exists(path)) return std::nullopt;
  Summary originalFinal, originalArea;
  const auto runs = parseMethodCsv(readFile(path), path, originalFinal, originalArea);
  return methodVerdict(runs, originalFinal, originalArea);
}

// A benchmark experiment: o.gpRuns GP runs, assessment of each run's returned features against
// the original variables (and a Fourier basis for the control tasks), the method-level verdict
// and the report section.
io::Report benchmark(Experiment& e, const ExperimentConfig& config, const std::string& heading,
                     const std::string& description, bool withFourier,
                     std::vector<FeatureSet> extraSets = {}) {
  const int runs = e.options().gpRuns;
  const std::string evolveName = "evolve-" + config.name;
  const std::string figure = fs::path(e.dir()).filename().string();
  const LearningTask task(config, LearningTask::Budget::Assessment);
  const FeatureSet original{"original", TrialFeatures::original()};
  std::vector<FeatureSet> sets{original};
  sets.insert(sets.end(), extraSets.begin(), extraSets.end());
  const std::size_t firstRun = sets.size();

  struct GpRun {
    ExperimentConfig config;
    std::string dir, set;
    expr::FeaturesFile features;
  };
  std::vector<GpRun> gpRuns;
  std::vector<std::pair<std::string, std::vector<GenerationRecord>>> histories;
  for (int r = 1; r <= runs; ++r) {
    GpRun run{config,
              runs == 1 ? evolveName : evolveName + "/" + runDirName(r, runs),
              runs == 1 ? "discovered" : runDirName(r, runs),
              {}};
    run.config.seed = runSeed(config.seed, r);
    histories.emplace_back(runs == 1 ? config.name : run.set, e.evolve(run.config, run.dir));
    run.features = e.discovered(run.dir, task);
    // A run that kept the original variables returned exactly them: nothing to assess.
    if (!e.outcome(run.dir).originalWon) {
      sets.push_back({run.set, TrialFeatures::ofGenome(run.features.genome, config.withOriginal)});
    }
    gpRuns.push_back(std::move(run));
  }
  // The no-learning reference last, so that no other set's seeds move.
  sets.push_back({"no-learning", TrialFeatures::noLearning()});
  const std::string assessName = "assess-" + config.name;
  e.assess(task, sets, assessName, config.env + " (" + config.name + ")");
  // The Fourier basis against the original variables (same seeds, so the same original runs),
  // in its own directory so that it can be left out and added later.
  const std::string fourierName = assessName + "-fourier";
  if (withFourier && !e.options().skipFourier) {
    e.assess(task, {original, fourierFeatureSet(task, 3)}, fourierName,
             config.env + " (" + config.name + "), Fourier basis");
  }
  fitnessPlot(e.dir() + "/fitness-" + config.name,
              "GP fitness per generation (" + config.name + ")", histories, runs == 1);

  // Each run's returned features: validated, re-measured on fresh seeds, assessed.
  const auto finals = readFinals(e.dir() + "/" + assessName);
  const Summary originalFinal = summarize(finals[0].finals);
  const Summary originalArea = summarize(finals[0].areas);
  std::optional<NoLearningRow> noLearning;  // Absent from assessments made before it existed.
  for (const auto& set : finals) {
    if (set.name == "no-learning")
      noLearning = NoLearningRow{summarize(set.finals), summarize(set.areas)};
  }
  std::vector<RunAssessment> assessed;
  std::size_t nextSet = firstRun;
  for (std::size_t r = 0; r < gpRuns.size(); ++r) {
    const auto& run = gpRuns[r];
    const auto& outcome = e.outcome(run.dir);
    // The original variables' own runs for a run that returned them: a difference of 0.
    const auto& set = outcome.originalWon ? finals[0] : finals[nextSet++];
    RunAssessment a;
    a.run = static_cast<int>(r) + 1;
    a.seed = run.config.seed;
    a.returned = !outcome.validated ? "gp-best" : outcome.originalWon ? "original" : "discovered";
    a.features = outcome.features;
    a.size = outcome.size;
    a.gpFitness = outcome.gpBest;
    a.reported = outcome.winner;
    a.remeasured = e.remeasure(run.config, run.dir, run.features.genome);
    a.final = summarize(set.finals);
    a.area = summarize(set.areas);
    a.finalVsOriginal = compare(set.finals, finals[0].finals);
    a.areaVsOriginal = compare(set.areas, finals[0].areas);
    assessed.push_back(a);
  }
  writeFileAtomically(e.dir() + "/method-" + config.name + ".csv",
                      formatMethodCsv(assessed, originalFinal, originalArea, noLearning));
  const auto verdict = methodVerdict(assessed, originalFinal, originalArea, noLearning);
  const auto baseline = baselineVerdict(e.options(), figure, config.name);

  io::Report r(heading);
  r.heading(heading, 3);
  r.paragraph(description);
  r.image(figure + "/" + assessName + "/curves.png",
          "(a) performance of the feature sets: mean over " + std::to_string(config.assessRuns) +
              " runs with a 95% confidence band");
  r.image(figure + "/fitness-" + config.name + ".png",
          runs == 1 ? "(b) best and mean fitness of the GP population per generation"
                    : "(b) best fitness of each GP run per generation");
  auto table = readSummaryTable(e.dir() + "/" + assessName);
  const bool haveFourier = fs::exists(e.dir() + "/" + fourierName + "/summary.md");
  if (haveFourier) {
    const auto fourier = readSummaryTable(e.dir() + "/" + fourierName);
    table.insert(table.end(), fourier.begin() + 2, fourier.end());  // Header and original out.
  } else if (withFourier) {
    r.paragraph("The Fourier basis was left out of this run (`--skip-fourier`).");
  }
  r.table(table);
  if (haveFourier) {
    r.image(figure + "/" + fourierName + "/curves.png",
            "the Fourier basis (order 3) against the original variables");
  }
  r.paragraph(fmt::format(
      "Each GP run's returned features (`best.features`): the GP's own fitness of its best set "
      "(the maximum of noisy estimates, so biased upwards), the validated score `best.features` "
      "reports (where the config confirms the validation winner: its score on fresh "
      "confirmation seeds, which the choice among the candidates never saw; else the validation "
      "score that chose it), the same trial re-measured on {} other fresh seeds, and the long "
      "assessment against the original variables (final {:.4g} ± {:.2g}); a run that returned "
      "the original variables is the original variables (no change).",
      kRemeasureSeeds, originalFinal.mean, originalFinal.halfWidth));
  r.table(runTable(assessed, originalFinal));
  r.paragraph(fmt::format(
      "Method-level verdict over the {} GP run{}: Wilcoxon's signed-rank test of the runs' mean "
      "differences from the original variables (two-sided; with fewer than 6 runs it cannot "
      "reach p < 0.05){}.",
      runs, runs == 1 ? "" : "s",
      baseline ? "; the baseline is " + e.options().baselineDir +
                     " and the last column tests this method's improvements against its own "
                     "(Mann-Whitney)"
               : ""));
  r.table(verdictTable(verdict, baseline ? &*baseline : nullptr));
  if (const auto sentence = noLearningSentence(verdict); !sentence.empty()) r.paragraph(sentence);
  r.paragraph("Settings (the full resolved config: `" + figure + "/" + gpRuns.front().dir +
              "/config.toml`):");
  r.table(settingsTable(config));
  std::string features;
  for (const auto& run : gpRuns) {
    if (runs > 1) features += "# " + run.set + "\n";
    features += featuresText(run.features);
  }
  r.paragraph("Returned features (`" + figure + "/" + evolveName + "/.../best.features`):");
  r.code(features);
  return r;
}

io::Report figure1(Experiment& e) {
  const auto config = e.config("cartpole");
  const LearningTask task(config, LearningTask::Budget::Assessment);
  expr::Genome sincos;
  for (const char* f : {"x", "dx", "th", "dth", "sin(th)", "cos(th)"}) {
    sincos.addFeature(expr::parseInfix(f, task.stateNames()));
  }
  return benchmark(e, config, "Figure 1: cart-pole, policy gradient with Rprop",
                   "The paper's Figure 1: learning with the original state variables, with sin and "
                   "cos of the pole angle added, and with the features GP discovers.",
                   true, {{"original+sin/cos", TrialFeatures::ofGenome(sincos, false)}});
}

io::Report figure3(Experiment& e, const ReproduceOptions& o) {
  if (!fs::exists(e.dir() + "/jit/jit.csv")) {
    BenchJitArgs args;  // Smaller at the quick scale.
    args.out = e.dir() + "/jit";
    args.print = false;
    if (!o.paperScale) {
      args.calls = 200000;
      args.runs = 3;
    }
    runBenchJit(args);
  }
  io::Report r("Figure 3");
  r.heading("Figure 3: speed-up of compiled feature functions", 3);
  r.paragraph(
      "Random complete binary trees of depth 2..8; time per call of the tree-walking "
      "interpreter, the fast interpreter, the JIT (asmjit), ahead-of-time compiled C++ and "
      "the AVX2 batch kernel (`gpfd bench jit`).");
  r.image("fig3/jit/jit.png", "speed-up over the tree-walking interpreter per depth");
  if (fs::exists(e.dir() + "/jit/jit_summary.txt"))
    r.code(readFile(e.dir() + "/jit/jit_summary.txt"));
  return r;
}

io::Report figure6(Experiment& e) {
  io::Report r("Figure 6");
  r.append(benchmark(e, e.config("swimmer3"), "Figure 6: 3-segment swimmer",
                     "Policy gradient with Rprop on the 3-segment swimmer (Coulom 2002).", true));
  r.append(benchmark(e, e.config("swimmer5"), "Figure 6: 5-segment swimmer",
                     "Policy gradient with Rprop on the 5-segment swimmer.", true));
  // Best fitness with populations of 25, 50 and 100 (3 segments); the run with the config's own
  // population is the one above.
  const auto swimmer3 = e.config("swimmer3");
  std::vector<std::pair<std::string, std::vector<GenerationRecord>>> runs;
  const int gpRuns = e.options().gpRuns;
  for (int population : {25, 50, 100}) {
    auto config = e.config("swimmer3", {"gp.population=" + std::to_string(population)});
    const bool same = population == swimmer3.gp.population;
    if (!same) config.name += "-pop" + std::to_string(population);
    // The config's own population is the benchmark's (first) run above.
    const std::string dir = same && gpRuns > 1
                                ? "evolve-" + swimmer3.name + "/" + runDirName(1, gpRuns)
                                : "evolve-" + config.name;
    runs.emplace_back("population " + std::to_string(population),
                      e.evolve(same ? swimmer3 : config, dir));
  }
  fitnessPlot(e.dir() + "/population-sizes", "3-segment swimmer: best fitness per generation", runs,
              false);
  r.heading("Figure 6: population size (3 segments)", 3);
  r.image("fig6/population-sizes.png", "best fitness per generation with populations 25, 50, 100");
  return r;
}

io::Report runFigure(const std::string& figure, Experiment& e, const ReproduceOptions& o) {
  if (figure == "fig1") return figure1(e);
  if (figure == "fig3") return figure3(e, o);
  if (figure == "fig5") {
    return benchmark(
        e, e.config("acrobot"), "Figure 5: Acrobot",
        "Policy gradient with Rprop on Acrobot: the GP run and the discovered features "
        "against the original state variables.",
        true);
  }
  if (figure == "fig6") return figure6(e);
  return benchmark(e, e.config("tetris"), "Figure 7: Tetris 12x8",
                   "Approximate lambda-policy iteration on Tetris (12 rows, 8 columns).", false);
}

// One row per benchmark with method-level results in the output directory (and the baseline's).
std::vector<std::vector<std::string>> methodSummaryTable(const ReproduceOptions& o) {
  std::vector<std::string> header{
      "benchmark",      "runs",       "original (final)",    "median change",
      "better / worse", "Wilcoxon p", "area: median change", "area: Wilcoxon p"};
  if (!o.baselineDir.empty()) {
    header.insert(header.end(), {"baseline: median change", "baseline: better / worse",
                                 "baseline: Wilcoxon p", "vs baseline: Mann-Whitney p"});
  }
  std::vector<std::vector<std::string>> rows{header};
  for (const auto& figure : kFigures) {
    const std::string dir = o.outDir + "/" + figure;
    if (!fs::is_directory(dir)) continue;
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(dir)) {
      const auto name = entry.path().filename().string();
      if (name.starts_with("method-") && name.ends_with(".csv")) files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    for (const auto& file : files) {
      Summary originalFinal, originalArea;
      const auto runs =
          parseMethodCsv(readFile(file.string()), file.string(), originalFinal, originalArea);
      const auto v = methodVerdict(runs, originalFinal, originalArea);
      const std::string name = file.stem().string().substr(7);
      std::vector<std::string> row{
          name,
          std::to_string(v.runs),
          fmt::format("{:.4g}", originalFinal.mean),
          fmt::format("{:+.4g} ({:+.1f}%)", v.final.median,
                      100.0 * v.final.median / std::fabs(originalFinal.mean)),
          fmt::format("{} / {}", v.betterFinal, v.worseFinal),
          fmt::format("{:.3g}", v.final.p),
          fmt::format("{:+.4g}", v.area.median),
          fmt::format("{:.3g}", v.area.p)};
      if (!o.baselineDir.empty()) {
        const auto base = baselineVerdict(o, figure, name);
        if (base) {
          row.insert(
              row.end(),
              {fmt::format("{:+.4g}", base->final.median),
               fmt::format("{} / {}", base->betterFinal, base->worseFinal),
               fmt::format("{:.3g}", base->final.p),
               fmt::format("{:.3g}",
                           compare(v.finalDifferences, base->finalDifferences).mannWhitneyP)});
        } else {
          row.insert(row.end(), {"-", "-", "-", "-"});
        }
      }
      rows.push_back(row);
    }
  }
  return rows;
}

}  // namespace

void reproduce(const std::vector<std::string>& figures, const ReproduceOptions& o) {
  for (const auto& f : figures) {
    if (std::find(kFigures.begin(), kFigures.end(), f) == kFigures.end()) {
      throw InputError("unknown figure '" + f + "' (fig1, fig3, fig5, fig6, fig7 or all)", f);
    }
  }
  const DirectoryLock lock = service::lockDirectory(o.outDir, "output directory");
  for (const auto& figure : figures) {
    if (!o.quiet) {
      fmt::print("{}:\n", figure);
      std::fflush(stdout);
    }
    Experiment e(o, figure);
    io::Report part = runFigure(figure, e, o);
    part.paragraph(
        fmt::format("Compute time of this experiment: GP runs {:.0f} s, their validation {:.0f} s, "
                    "assessments {:.0f} s ({} scale, seed {}, gpfd {} {}, {} threads).",
                    e.evolveSeconds(), e.validationSeconds(), e.assessSeconds(),
                    o.paperScale ? "paper" : "quick", o.seed, o.version, o.revision,
                    o.threads > 0 ? std::to_string(o.threads) : "all"));
    writeFileAtomically(e.dir() + "/section.json", part.json());
    e.checkStop(e.dir());
  }

  // The report covers every figure whose section exists in the output directory.
  io::Report report("gpfd: reproduction of Girgin & Preux, feature discovery with GP");
  report.paragraph(fmt::format(
      "Generated by `gpfd reproduce` (gpfd {} {}). Each figure's data, configs, plots (PNG and "
      "SVG) and GP runs are in its directory; `config.toml` in each GP run is the fully resolved "
      "config.",
      o.version, o.revision));
  const auto summary = methodSummaryTable(o);
  if (summary.size() > 1) {
    report.heading("Method-level summary", 2);
    report.paragraph(fmt::format(
        "Per benchmark, over its GP runs ({} per benchmark in this reproduction): the median "
        "change of the returned features' final performance against the original variables (long "
        "assessment), how many runs are significantly better or worse (Welch p < 0.05), and "
        "Wilcoxon's signed-rank test over the runs' mean differences{}.",
        o.gpRuns,
        o.baselineDir.empty() ? ""
                              : "; then the same for the baseline " + o.baselineDir +
                                    " and a Mann-Whitney test of the two sets of changes"));
    report.table(summary);
  }
  for (const auto& figure : kFigures) {
    const std::string path = o.outDir + "/" + figure + "/section.json";
    if (fs::exists(path)) report.append(io::Report::fromJson(readFile(path)));
  }
  writeFileAtomically(o.outDir + "/report.md", report.markdown());
  writeFileAtomically(o.outDir + "/report.html", report.html(o.outDir));
  if (!o.quiet) fmt::print("report: {}/report.html and report.md\n", o.outDir);
}

}  // namespace gpfd::experiments
