// service: the text a discovery run prints as it goes (`gpfd evolve`, and gpfd.evolve with
// verbose=True; without a display, only the verdict): a header per run, a line per generation with
// an ETA, on a terminal a status line of the running generation, what each run returned, and a
// set's summary.
#pragma once

#include <atomic>
#include <functional>
#include <string>
#include <thread>

#include "gpfd/service/evolve.hpp"

namespace gpfd::service {

// Where text goes: a line or part of one, written as it is.
using TextSink = std::function<void(const std::string&)>;

// "45s", "4m05s", "2h03m".
std::string formatDuration(double seconds);

class EvolveText final : public EvolveProgress {
 public:
  struct Options {
    TextSink out, err;
    bool terminal = false;     // Redraw a status line of the running generation.
    bool quiet = false;        // Only what stops a run (stderr) is written.
    bool outcomeOnly = false;  // Also what each run returned (its verdict) and a set's summary.
    // How to continue a stopped run, with {} for its directory.
    std::string resumeCommand = "gpfd evolve --resume {}";
  };
  explicit EvolveText(Options options);
  ~EvolveText() override;

  void runStarted(const run::Discovery& discovery, const std::string& dir,
                  const std::string& label) override;
  void generationDone(const run::Discovery& discovery, const run::GenerationRecord& record,
                      const std::string& label) override;
  void runStopped(const run::Discovery& discovery, const std::string& dir,
                  const std::string& resumeDir, bool error) override;
  void runFinished(const run::RunOutcome& outcome, const std::string& dir,
                   const std::string& label) override;
  void setFinished(const std::vector<run::RunOutcome>& outcomes, const std::string& dir) override;
  void alreadyComplete(const std::string& dir, int generations) override;
  void preparedRun(const std::string& text) override;
  void preparing(const std::string& phase) override;

 private:
  void stopStatus();

  Options o_;
  double total_ = 0.0;  // Seconds of the run's generations so far.
  std::atomic<bool> running_{false};
  std::jthread status_;
};

}  // namespace gpfd::service
