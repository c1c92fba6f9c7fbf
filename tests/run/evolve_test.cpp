// `gpfd evolve` end to end on a tiny cart-pole config: reproducibility across threads, exact
// resume after SIGKILL and SIGINT, results directory contents.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>
#include <thread>

#include "cli_helpers.hpp"
#include "gpfd/expr/features_file.hpp"
#include "gpfd/run/experiment_config.hpp"
#include "gpfd/run/statistics.hpp"
#include "gpfd/run/validation.hpp"

namespace gpfd::testing {
namespace {

std::string tinyConfig() { return tinyEvolveConfig("tiny", 3); }

std::string fingerprint(const std::string& dir) {
  return withoutSeconds(readText(dir + "/generations.csv")) + readText(dir + "/best.features");
}

TEST(Evolve, WritesTheResultsDirectory) {
  const auto dir = freshDir("evolve-files");
  const auto r = runGpfd("evolve " + tinyConfig() + " --quiet --out " + dir);
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* file : {"config.toml", "run.json", "generations.csv", "best.features",
                           "checkpoint.json", "validation.csv", "confirmation.csv", "front.csv",
                           "best/generation-0000.features", "best/generation-0005.features"}) {
    EXPECT_TRUE(std::filesystem::exists(dir + "/" + file)) << file;
  }
  const auto csv = readText(dir + "/generations.csv");
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "generation,best,mean,median,mean_size,mean_features,evaluations,reevaluations,"
            "cache_hits,seconds");
  const auto best = readText(dir + "/best.features");
  EXPECT_NE(best.find("# env: cartpole"), std::string::npos);
  EXPECT_NE(best.find("# confirmed: "), std::string::npos);
  EXPECT_NE(best.find("(30 trials)"), std::string::npos);
  EXPECT_NE(best.find("# verdict: "), std::string::npos);
  // Hall of fame (10), the original variables and the no-learning reference (last), each on its
  // own line.
  const auto validation = readText(dir + "/validation.csv");
  EXPECT_EQ(std::count(validation.begin(), validation.end(), '\n'), 13);
  EXPECT_NE(validation.find("\n,no-learning,"), std::string::npos);
  EXPECT_NE(validation.find(",original,"), std::string::npos);
  // The complexity front, and the run directory as a stand-in for its best.features.
  const auto front = runGpfd("features show " + dir + " --front");
  EXPECT_EQ(front.status, 0) << front.output;
  EXPECT_NE(front.output.find("selection (mean +- SE)"), std::string::npos);
  const auto frontCsv = readText(dir + "/front.csv");
  EXPECT_EQ(std::count(front.output.begin(), front.output.end(), '\n'),
            std::count(frontCsv.begin(), frontCsv.end(), '\n'));
  EXPECT_EQ(runGpfd("features show " + dir).status, 0);
  EXPECT_EQ(runGpfd("features show " + dir + "/best.features --front").status, 2);
  const auto missing = runGpfd("features show " + dir + "/no-such-run --front");
  EXPECT_EQ(missing.status, 2);
  EXPECT_NE(missing.output.find("no such run directory"), std::string::npos) << missing.output;
  // The resolved config reads back as a config.
  const auto againDir = freshDir("evolve-files-again");
  const auto again = runGpfd("evolve " + dir + "/config.toml --quiet --out " + againDir);
  EXPECT_EQ(again.status, 0) << again.output;
  EXPECT_EQ(fingerprint(dir), fingerprint(againDir));
}

TEST(Evolve, OneAndTwoThreadsGiveIdenticalResults) {
  const auto one = freshDir("evolve-t1"), two = freshDir("evolve-t2");
  ASSERT_EQ(runGpfd("evolve " + tinyConfig() + " --quiet --threads 1 --out " + one).status, 0);
  ASSERT_EQ(runGpfd("evolve " + tinyConfig() + " --quiet --threads 2 --out " + two).status, 0);
  EXPECT_EQ(fingerprint(one), fingerprint(two));
  const auto other = freshDir("evolve-seed");
  ASSERT_EQ(runGpfd("evolve " + tinyConfig() + " --quiet --seed 4 --out " + other).status, 0);
  EXPECT_NE(fingerprint(one), fingerprint(other));
}

// Starts gpfd evolve in the background and sends `signal` after `delay`.
int runAndSignal(const std::string& args, int signal, std::chrono::milliseconds delay) {
  const pid_t pid = fork();
  if (pid == 0) {
    execl("/bin/sh", "sh", "-c",
          (std::string(GPFD_BINARY) + " " + args + " >/dev/null 2>&1").c_str(),
          static_cast<char*>(nullptr));
    _exit(127);
  }
  std::this_thread::sleep_for(delay);
  kill(pid, signal);
  int status = 0;
  waitpid(pid, &status, 0);
  return status;
}

TEST(Evolve, ResumeAfterSigkillGivesTheUninterruptedResult) {
  const auto reference = freshDir("evolve-reference");
  ASSERT_EQ(runGpfd("evolve " + tinyConfig() + " --quiet --threads 2 --out " + reference).status,
            0);
  // Kill at several points (before, during and after the first checkpoints), then resume.
  for (int delayMs : {5, 60, 150, 300}) {
    const auto dir = freshDir("evolve-killed-" + std::to_string(delayMs));
    const std::string args = "evolve " + tinyConfig() + " --quiet --out " + dir;
    // exec through sh: kill the whole process group so that gpfd itself gets SIGKILL.
    const pid_t pid = fork();
    if (pid == 0) {
      setpgid(0, 0);
      execl(GPFD_BINARY, GPFD_BINARY, "evolve", tinyConfig().c_str(), "--quiet", "--out",
            dir.c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(delayMs));
    kill(pid, SIGKILL);
    waitpid(pid, nullptr, 0);
    if (!std::filesystem::exists(dir + "/config.toml")) {
      // Killed before its config was stored: nothing ran yet, a plain restart is the resume.
      ASSERT_EQ(runGpfd(args).status, 0);
    } else {
      const auto resumed = runGpfd("evolve --quiet --resume " + dir);
      ASSERT_EQ(resumed.status, 0) << resumed.output;
    }
    EXPECT_EQ(fingerprint(dir), fingerprint(reference)) << "killed after " << delayMs << " ms";
  }
}

TEST(Evolve, SigintStopsAfterACheckpoint) {
  const auto reference = freshDir("evolve-reference-int");
  ASSERT_EQ(runGpfd("evolve " + tinyConfig() + " --quiet --out " + reference).status, 0);
  const auto dir = freshDir("evolve-interrupted");
  const int status = runAndSignal("evolve " + tinyConfig() + " --out " + dir, SIGINT,
                                  std::chrono::milliseconds(200));
  (void)status;
  if (std::filesystem::exists(dir + "/checkpoint.json")) {
    const auto resumed = runGpfd("evolve --quiet --resume " + dir);
    ASSERT_EQ(resumed.status, 0) << resumed.output;
    EXPECT_EQ(fingerprint(dir), fingerprint(reference));
  }
}

TEST(Evolve, ExtendingAResumedRunMatchesALongerRun) {
  const auto longer = freshDir("evolve-8");
  ASSERT_EQ(runGpfd("evolve " + tinyConfig() + " --quiet --generations 8 --out " + longer).status,
            0);
  const auto dir = freshDir("evolve-6-then-8");
  ASSERT_EQ(runGpfd("evolve " + tinyConfig() + " --quiet --out " + dir).status, 0);
  ASSERT_EQ(runGpfd("evolve --quiet --resume " + dir + " --generations 8").status, 0);
  EXPECT_EQ(withoutSeconds(readText(dir + "/generations.csv")),
            withoutSeconds(readText(longer + "/generations.csv")));
}

TEST(Evolve, RunsMakeASetThatResumes) {
  const auto dir = freshDir("evolve-runs");
  const auto r =
      runGpfd("evolve " + tinyConfig() + " --generations 3 --runs 3 --quiet --out " + dir);
  ASSERT_EQ(r.status, 0) << r.output;
  const auto runs = readText(dir + "/runs.csv");
  EXPECT_EQ(std::count(runs.begin(), runs.end(), '\n'), 4);
  EXPECT_NE(runs.find(",p_vs_original,scored_by,no_learning_mean,"), std::string::npos) << runs;
  EXPECT_NE(runs.find(",confirmation,"), std::string::npos) << runs;
  // Run 1 is the single run with the set's seed.
  const auto single = freshDir("evolve-runs-single");
  ASSERT_EQ(runGpfd("evolve " + tinyConfig() + " --generations 3 --quiet --out " + single).status,
            0);
  EXPECT_EQ(fingerprint(dir + "/run-01"), fingerprint(single));
  EXPECT_NE(fingerprint(dir + "/run-02"), fingerprint(dir + "/run-01"));
  // A run lost (as if killed before it started) is redone exactly on resume.
  const auto second = fingerprint(dir + "/run-02");
  std::filesystem::remove_all(dir + "/run-02");
  const auto resumed = runGpfd("evolve --resume " + dir + " --quiet");
  ASSERT_EQ(resumed.status, 0) << resumed.output;
  EXPECT_EQ(fingerprint(dir + "/run-02"), second);
  EXPECT_EQ(readText(dir + "/runs.csv"), runs);
  // A set is not started twice in one directory, nor a single run over it, and --runs does not
  // go with --resume.
  EXPECT_EQ(runGpfd("evolve " + tinyConfig() + " --runs 2 --quiet --out " + dir).status, 2);
  const auto over = runGpfd("evolve " + tinyConfig() + " --quiet --out " + dir);
  EXPECT_EQ(over.status, 2);
  EXPECT_NE(over.output.find("already holds a run or a set of runs"), std::string::npos)
      << over.output;
  EXPECT_FALSE(std::filesystem::exists(dir + "/checkpoint.json"));
  EXPECT_EQ(readText(dir + "/runs.csv"), runs);
  EXPECT_EQ(runGpfd("evolve --resume " + dir + " --runs 2").status, 2);
}

TEST(Evolve, PeriodicValidationKeepsEveryValidatedSetAndResumesExactly) {
  const auto dir = freshDir("evolve-every");
  const std::string args = "evolve " + tinyConfig() +
                           " --quiet --set validation.every=2 --set "
                           "validation.candidates=3 --set validation.seeds=5 --out ";
  ASSERT_EQ(runGpfd(args + dir).status, 0);
  // Validated after generations 1 and 3 (every 2) and at the end (5).
  const auto csv = readText(dir + "/validation.csv");
  for (const char* generation : {",1,", ",3,", ",5,"}) {
    EXPECT_NE(csv.find(std::string("hall-of-fame") + generation), std::string::npos) << csv;
  }
  // Stopped after generation 3 (a shorter run), then extended: the same validated sets.
  const auto shorter = freshDir("evolve-every-extended");
  ASSERT_EQ(runGpfd(args + shorter + " --generations 4").status, 0);
  ASSERT_EQ(runGpfd("evolve --quiet --resume " + shorter + " --generations 6").status, 0);
  EXPECT_EQ(fingerprint(shorter), fingerprint(dir));
}

TEST(Evolve, BadDiscoveryKeysNameTheKey) {
  for (const auto& [set, key] : std::vector<std::pair<std::string, std::string>>{
           {"fitness.max_trials=1", "fitness.max_trials"},
           {"fitness.max_trials=-3", "fitness.max_trials"},
           {"validation.seeds=0", "validation.seeds"},
           {"validation.candidates=-1", "validation.candidates"},
           {"validation.every=-2", "validation.every"},
           {"fitness.state_sample=0", "fitness.state_sample"},
           {"validation.params.updatez=3", "updatez"},
           {"validation.confirm_seeds=1", "validation.confirm_seeds"},
           {"validation.confirm_seeds=-1", "validation.confirm_seeds"},
           {"validation.confirm_measure=best", "validation.confirm_measure"},
           {"validation.confirm_params.updates=-1", "validation.confirm_params.updates"},
           {"validation.confirm_params.updatez=3", "updatez"},
           {"validation.confirm_looks=0", "validation.confirm_looks"},
           {"validation.confirm_looks=6", "validation.confirm_looks"},
           {"validation.confirm_seeds=5", "validation.confirm_looks"},
           {"validation.parsimony_se=-1", "validation.parsimony_se"}}) {
    const auto r = runGpfd("evolve " + tinyConfig() + " --quiet --out " + freshDir("bad-key") +
                           " --set " + set);
    EXPECT_EQ(r.status, 2) << set << ": " << r.output;
    EXPECT_NE(r.output.find(key), std::string::npos) << set << ": " << r.output;
  }
}

// A clear difference ends the confirmation at a look before the last seed (run 2 of the tiny
// config: after 20 of 30 seeds); the seeds it trained score as they do in a confirmation that
// trains every seed (confirm_looks = 1), so it is the same test, stopped sooner.
TEST(Evolve, AClearConfirmationEndsEarly) {
  const auto early = freshDir("evolve-looks-3"), full = freshDir("evolve-looks-1");
  const std::string args = "evolve " + tinyConfig() + " --quiet --seed 2 --out ";
  ASSERT_EQ(runGpfd(args + early).status, 0);
  ASSERT_EQ(runGpfd(args + full + " --set validation.confirm_looks=1").status, 0);
  const auto confirmation = [](const std::string& dir) {
    return nlohmann::json::parse(readText(dir + "/checkpoint.json"))["validation"]["confirmation"];
  };
  const auto a = confirmation(early), b = confirmation(full);
  ASSERT_EQ(a["key"], b["key"]);
  ASSERT_EQ(a["winner"].size(), 20u);
  ASSERT_EQ(b["winner"].size(), 30u);
  for (std::size_t m = 0; m < 20; ++m) {
    EXPECT_EQ(a["winner"][m], b["winner"][m]) << m;
    EXPECT_EQ(a["original"][m], b["original"][m]) << m;
  }
  const auto best = readText(early + "/best.features");
  EXPECT_NE(best.find("(20 trials)"), std::string::npos) << best;
  EXPECT_NE(best.find("before the 30 seeds planned"), std::string::npos) << best;
}

// The winner's curse is gone: the validated score that best.features carries (the
// confirmation's, on seeds the choice never saw) agrees with the same trial re-measured on fresh
// seeds, within 2 standard errors of their difference.
TEST(Evolve, TheValidatedScoreHoldsOnFreshSeeds) {
  const auto dir = freshDir("evolve-honest");
  ASSERT_EQ(runGpfd("evolve " + tinyConfig() +
                    " --quiet --set validation.confirm_params.updates=8 --out " + dir)
                .status,
            0);
  const auto config = run::loadExperimentConfig(dir + "/config.toml");
  const auto file = expr::readFeaturesFile(dir + "/best.features");
  EXPECT_EQ(file.meta.at("confirmed_by").rfind("30 fresh seeds", 0), 0u);
  const auto validated = file.meta.at("confirmed");  // "MEAN +- SE (M trials)"
  const double mean = std::stod(validated);
  const double se = std::stod(validated.substr(validated.find("+-") + 2));
  run::ThreadTrialRunner runner(2);
  const run::Validator remeasure(config, runner, run::LearningTask::Budget::Confirmation, 30,
                                 run::Validator::kRemeasureStream);
  const auto scores =
      remeasure.score({run::TrialFeatures::ofGenome(file.genome, config.withOriginal)})[0];
  const auto fresh = run::summarize(scores);
  const double freshSe = fresh.standardError();
  EXPECT_EQ(fresh.n, 30);
  EXPECT_LE(std::fabs(mean - fresh.mean), 2 * std::hypot(se, freshSe))
      << "validated " << validated << ", re-measured " << fresh.mean << " +- " << freshSe;
}

}  // namespace
}  // namespace gpfd::testing
