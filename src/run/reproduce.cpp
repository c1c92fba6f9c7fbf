#include "gpfd/run/reproduce.hpp"

#include <fmt/format.h>

#include <chrono>
#include <filesystem>
#include <map>

#include "gpfd/expr/features_file.hpp"
#include "gpfd/expr/parse.hpp"
#include "gpfd/io/gnuplot.hpp"
#include "gpfd/io/report.hpp"
#include "gpfd/run/assessment.hpp"
#include "gpfd/run/discovery.hpp"
#include "gpfd/util/atomic_file.hpp"
#include "gpfd/util/error.hpp"
#include "gpfd/util/number.hpp"

namespace gpfd::run {
namespace {
namespace fs = std::filesystem;

class Experiment {
 public:
  Experiment(const ReproduceOptions& o, std::string figure) : o_(o), dir_(o.outDir + "/" + figure) {
    createDirectories(dir_);
  }

  const std::string& dir() const { return dir_; }
  const ReproduceOptions& options() const { return o_; }
  // Compute time of the experiment's steps, whether they ran now or in an earlier invocation:
  // the GP runs' generation times and the assessments' recorded times.
  double evolveSeconds() const { return evolveSeconds_; }
  double assessSeconds() const { return assessSeconds_; }

  ExperimentConfig config(const std::string& base, std::vector<std::string> overrides = {}) const {
    overrides.push_back("seed=" + std::to_string(o_.seed));
    return o_.loadConfig(o_.paperScale ? base : base + "-quick", overrides);
  }

  // Runs, resumes, or reuses the GP run in dir()/name; returns its history. A run asked for
  // again in this invocation is not resumed a second time.
  const std::vector<GenerationRecord>& evolve(const ExperimentConfig& config,
                                              const std::string& name) {
    if (const auto done = histories_.find(name); done != histories_.end()) return done->second;
    const std::string dir = dir_ + "/" + name;
    DiscoveryOptions d;
    d.outDir = dir;
    d.threads = o_.threads;
    d.version = o_.version;
    d.revision = o_.revision;
    auto run = fs::exists(dir + "/config.toml") ? Discovery::resume(d, config, std::nullopt)
                                                : Discovery::start(config, d);
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
    if (!run->finished())
      throw InputError("interrupted; run the same command again to continue", dir);
    for (const auto& r : run->history()) evolveSeconds_ += r.seconds;
    return histories_[name] = run->history();
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
    const auto result =
        runAssessment(task, sets, task.config().assessRuns, task.config().seed, o_.threads);
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
  double assessSeconds_ = 0.0;
  std::map<std::string, std::vector<GenerationRecord>> histories_;  // GP runs done, by name.
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
  return {{"setting", "value"},
          {"config", "`" + c.name + "` (seed " + std::to_string(c.seed) + ")"},
          {"environment", c.env + " (" + joined(c.envParams) + ")"},
          {"learner, short trial", c.learner + " (" + joined(c.learnerParams) + ")"},
          {"trials per fitness", std::to_string(c.trials)},
          {"GP", fmt::format("population {}, {} generations, crossover {}, elitism {}, "
                             "tournament {}, size penalty {} per node",
                             c.gp.population, c.gp.generations, c.gp.crossoverRate, c.gp.elitism,
                             c.gp.tournamentSize, c.gp.sizePenalty)},
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

// A benchmark experiment: GP run, assessment of the discovered features against the original
// variables (and a Fourier basis for the control tasks), and the report section.
io::Report benchmark(Experiment& e, const ExperimentConfig& config, const std::string& heading,
                     const std::string& description, bool withFourier,
                     std::vector<FeatureSet> extraSets = {}) {
  const std::string evolveName = "evolve-" + config.name;
  const auto& history = e.evolve(config, evolveName);
  const LearningTask task(config, LearningTask::Budget::Assessment);
  const auto features = e.discovered(evolveName, task);
  const FeatureSet original{"original",
                            std::make_shared<const features::RawFeatureMap>(task.stateDim())};
  std::vector<FeatureSet> sets{original};
  sets.insert(sets.end(), extraSets.begin(), extraSets.end());
  sets.push_back(
      {"discovered", genomeFeatureMap(features.genome, task.stateDim(), config.withOriginal)});
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
              "GP fitness per generation (" + config.name + ")", {{config.name, history}}, true);

  io::Report r(heading);
  r.heading(heading, 3);
  r.paragraph(description);
  r.image(fs::path(e.dir()).filename().string() + "/" + assessName + "/curves.png",
          "(a) performance of the feature sets: mean over " + std::to_string(config.assessRuns) +
              " runs with a 95% confidence band");
  r.image(fs::path(e.dir()).filename().string() + "/fitness-" + config.name + ".png",
          "(b) best and mean fitness of the GP population per generation");
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
    r.image(fs::path(e.dir()).filename().string() + "/" + fourierName + "/curves.png",
            "the Fourier basis (order 3) against the original variables");
  }
  r.paragraph("Settings (the full resolved config: `" + fs::path(e.dir()).filename().string() +
              "/" + evolveName + "/config.toml`):");
  r.table(settingsTable(config));
  r.paragraph("Discovered features (simplified; `" + fs::path(e.dir()).filename().string() + "/" +
              evolveName + "/best.features`):");
  r.code(featuresText(features));
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
                   true, {{"original+sin/cos", genomeFeatureMap(sincos, task.stateDim(), false)}});
}

io::Report figure3(Experiment& e, const ReproduceOptions& o) {
  if (!fs::exists(e.dir() + "/jit/jit.csv")) o.benchJit(e.dir() + "/jit", !o.paperScale);
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
  for (int population : {25, 50, 100}) {
    auto config = e.config("swimmer3", {"gp.population=" + std::to_string(population)});
    const bool same = population == swimmer3.gp.population;
    if (!same) config.name += "-pop" + std::to_string(population);
    runs.emplace_back("population " + std::to_string(population),
                      e.evolve(same ? swimmer3 : config, "evolve-" + config.name));
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

}  // namespace

void reproduce(const std::vector<std::string>& figures, const ReproduceOptions& o) {
  for (const auto& f : figures) {
    if (std::find(kFigures.begin(), kFigures.end(), f) == kFigures.end()) {
      throw InputError("unknown figure '" + f + "' (fig1, fig3, fig5, fig6, fig7 or all)", f);
    }
  }
  createDirectories(o.outDir);
  for (const auto& figure : figures) {
    if (!o.quiet) {
      fmt::print("{}:\n", figure);
      std::fflush(stdout);
    }
    Experiment e(o, figure);
    io::Report part = runFigure(figure, e, o);
    part.paragraph(fmt::format(
        "Compute time of this experiment: GP runs {:.0f} s, assessments {:.0f} s ({} scale, seed "
        "{}, gpfd {} {}, {} threads).",
        e.evolveSeconds(), e.assessSeconds(), o.paperScale ? "paper" : "quick", o.seed, o.version,
        o.revision, o.threads > 0 ? std::to_string(o.threads) : "all"));
    writeFileAtomically(e.dir() + "/section.json", part.json());
  }

  // The report covers every figure whose section exists in the output directory.
  io::Report report("gpfd: reproduction of Girgin & Preux, feature discovery with GP");
  report.paragraph(fmt::format(
      "Generated by `gpfd reproduce` (gpfd {} {}). Each figure's data, configs, plots (PNG and "
      "SVG) and GP runs are in its directory; `config.toml` in each GP run is the fully resolved "
      "config.",
      o.version, o.revision));
  for (const auto& figure : kFigures) {
    const std::string path = o.outDir + "/" + figure + "/section.json";
    if (fs::exists(path)) report.append(io::Report::fromJson(readFile(path)));
  }
  writeFileAtomically(o.outDir + "/report.md", report.markdown());
  writeFileAtomically(o.outDir + "/report.html", report.html(o.outDir));
  if (!o.quiet) fmt::print("report: {}/report.html and report.md\n", o.outDir);
}

}  // namespace gpfd::run
