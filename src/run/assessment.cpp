#include "gpfd/run/assessment.hpp"

#include <fmt/format.h>

#include <cmath>
#include <sstream>

#include "gpfd/io/gnuplot.hpp"
#include "gpfd/rl/fourier_basis.hpp"
#include "gpfd/util/atomic_file.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::run {

std::shared_ptr<const rl::FourierBasis> fourierBasis(const LearningTask& task, int order) {
  const auto& config = task.config();
  auto ranges = env::Registry::global().make(config.env, config.envParams)->typicalStateRanges();
  if (ranges.empty()) {
    throw InputError("no typical state ranges are known for " + config.env +
                         ", so the Fourier basis is not available for it",
                     "--fourier");
  }
  return std::make_shared<const rl::FourierBasis>(
      rl::FourierBasis::automatic(std::move(ranges), order));
}

FeatureSet fourierFeatureSet(const LearningTask& task, int order) {
  const bool full = fourierBasis(task, order)->coupling() == rl::FourierBasis::Coupling::Full;
  return {fmt::format("fourier-{}{}", order, full ? "" : "-independent"),
          TrialFeatures::fourier(order)};
}

std::vector<double> AssessmentResult::finals(std::size_t set) const {
  std::vector<double> out;
  for (const auto& curve : curves[set]) {
    out.push_back(curve.points.empty() ? -std::numeric_limits<double>::infinity()
                                       : curve.points.back().meanReturn);
  }
  return out;
}

std::vector<double> AssessmentResult::areas(std::size_t set) const {
  std::vector<double> out;
  for (const auto& curve : curves[set]) {
    double sum = 0.0;
    for (const auto& p : curve.points) sum += p.meanReturn;
    out.push_back(curve.points.empty() ? -std::numeric_limits<double>::infinity()
                                       : sum / static_cast<double>(curve.points.size()));
  }
  return out;
}

AssessmentResult runAssessment(const LearningTask& task, const std::vector<FeatureSet>& sets,
                               int runs, std::uint64_t seed, TrialRunner& runner,
                               std::atomic<long>* progress) {
  AssessmentResult result;
  TrialBatch batch;
  for (std::size_t s = 0; s < sets.size(); ++s) {
    result.names.push_back(sets[s].name);
    batch.sets.push_back(sets[s].features);
    auto& seeds = batch.seeds.emplace_back();
    for (int r = 0; r < runs; ++r) seeds.push_back(deriveSeed(seed, s, r));
  }
  result.curves = runner.run(task, batch, [progress](std::size_t n) {
    if (progress) progress->fetch_add(static_cast<long>(n));
  });
  return result;
}

std::vector<SetSummary> summarizeAssessment(const AssessmentResult& result, std::size_t baseline) {
  std::vector<SetSummary> out;
  const auto base = result.finals(baseline);
  const auto baseArea = result.areas(baseline);
  for (std::size_t s = 0; s < result.names.size(); ++s) {
    const auto finals = result.finals(s);
    const auto areas = result.areas(s);
    SetSummary row{result.names[s],  summarize(finals),        compare(finals, base),
                   summarize(areas), compare(areas, baseArea), 0};
    for (const auto& c : result.curves[s]) row.diverged += c.diverged ? 1 : 0;
    out.push_back(row);
  }
  return out;
}

void writeAssessment(const std::string& dir, const AssessmentResult& result,
                     const std::vector<SetSummary>& summary, const std::string& title,
                     const std::string& xlabel) {
  std::string curves = "set,update,episodes,runs,mean,ci_low,ci_high\n";
  std::string finals = "set,run,final,area\n";
  io::LinePlot plot{title, xlabel, "mean return", {}, false};
  for (std::size_t s = 0; s < result.names.size(); ++s) {
    const auto& runs = result.curves[s];
    std::size_t rows = 0;
    for (const auto& c : runs) rows = std::max(rows, c.points.size());
    io::Series series{result.names[s], {}, {}, {}, {}};
    for (std::size_t u = 0; u < rows; ++u) {
      std::vector<double> values;
      double episodes = 0;
      for (const auto& c : runs) {
        if (u < c.points.size()) {
          values.push_back(c.points[u].meanReturn);
          episodes += static_cast<double>(c.points[u].episodes);
        }
      }
      const Summary m = summarize(values);
      episodes /= static_cast<double>(values.size());
      curves += fmt::format("{},{},{},{},{},{},{}\n", result.names[s], u, episodes, m.n, m.mean,
                            m.mean - m.halfWidth, m.mean + m.halfWidth);
      series.x.push_back(static_cast<double>(u));
      series.y.push_back(m.mean);
      series.low.push_back(m.mean - m.halfWidth);
      series.high.push_back(m.mean + m.halfWidth);
    }
    plot.series.push_back(series);
    const auto f = result.finals(s);
    const auto a = result.areas(s);
    for (std::size_t r = 0; r < f.size(); ++r) {
      finals += fmt::format("{},{},{},{}\n", result.names[s], r, f[r], a[r]);
    }
  }
  std::string csv =
      "set,runs,mean_final,std,ci95,diverged,welch_t,welch_p,mann_whitney_u,mann_whitney_p,"
      "cohen_d,a12,mean_area,area_ci95,area_welch_p,area_mann_whitney_p\n";
  std::string md =
      "| feature set | runs | final (mean ± 95% CI) | vs first: Welch p | Mann-Whitney p | "
      "Cohen's d | A12 | area under curve | area: Welch p | area: Mann-Whitney p |\n"
      "|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& row : summary) {
    const auto& c = row.vsBaseline;
    const auto& a = row.areaVsBaseline;
    csv += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", row.name, row.final.n,
                       row.final.mean, row.final.stddev, row.final.halfWidth, row.diverged,
                       c.welchT, c.welchP, c.mannWhitneyU, c.mannWhitneyP, c.cohenD, c.a12,
                       row.area.mean, row.area.halfWidth, a.welchP, a.mannWhitneyP);
    md += fmt::format(
        "| {} | {} | {:.4g} ± {:.3g} | {:.3g} | {:.3g} | {:.3g} | {:.3g} | {:.4g} ± {:.3g} | "
        "{:.3g} | {:.3g} |\n",
        row.name, row.final.n, row.final.mean, row.final.halfWidth, c.welchP, c.mannWhitneyP,
        c.cohenD, c.a12, row.area.mean, row.area.halfWidth, a.welchP, a.mannWhitneyP);
  }
  writeFileAtomically(dir + "/curves.csv", curves);
  writeFileAtomically(dir + "/finals.csv", finals);
  writeFileAtomically(dir + "/summary.csv", csv);
  writeFileAtomically(dir + "/summary.md", md);
  io::plotLines(dir + "/curves", plot);
}

std::vector<SetFinals> readFinals(const std::string& dir) {
  const std::string path = dir + "/finals.csv";
  std::istringstream in(readFile(path));
  std::string line;
  std::getline(in, line);  // Header.
  std::vector<SetFinals> sets;
  while (std::getline(in, line)) {
    // set,run,final,area: the set's name may hold commas, the numbers do not.
    const std::size_t areaAt = line.rfind(',');
    const std::size_t finalAt = line.rfind(',', areaAt - 1);
    const std::size_t runAt = line.rfind(',', finalAt - 1);
    if (runAt == std::string::npos || areaAt == std::string::npos) {
      throw InputError("not a finals table: " + line, path);
    }
    const std::string name = line.substr(0, runAt);
    if (sets.empty() || sets.back().name != name) sets.push_back({name, {}, {}});
    try {
      sets.back().finals.push_back(std::stod(line.substr(finalAt + 1, areaAt - finalAt - 1)));
      sets.back().areas.push_back(std::stod(line.substr(areaAt + 1)));
    } catch (const std::logic_error&) {
      throw InputError("not a finals table: " + line, path);
    }
  }
  return sets;
}

std::vector<std::vector<std::string>> readSummaryTable(const std::string& dir) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(readFile(dir + "/summary.md"));
  std::string line;
  while (std::getline(in, line)) {
    if (line.size() < 4 || line.front() != '|' || line.starts_with("|---")) continue;
    std::vector<std::string> cells;
    std::size_t from = 2;  // After "| ".
    for (std::size_t bar; (bar = line.find(" |", from)) != std::string::npos; from = bar + 3) {
      cells.push_back(line.substr(from, bar - from));
    }
    rows.push_back(std::move(cells));
  }
  return rows;
}

}  // namespace gpfd::run
