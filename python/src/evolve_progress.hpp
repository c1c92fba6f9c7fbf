// python: gpfd.evolve's progress: the per-generation callback, Ctrl-C, the command's text and the
// progress display (gpfd.discovery.progress.EvolveBar), as the service layer reports a run
// (service::EvolveProgress); and the text of the KeyboardInterrupt that ends an interrupted run.
#pragma once

#include <atomic>
#include <optional>
#include <stop_token>
#include <string>
#include <thread>
#include <vector>

#include "bindings.hpp"
#include "gpfd/service/evolve_text.hpp"

namespace gpfd::python {

// Where a run stopped by Ctrl-C was (PythonProgress::runStopped), for the text of gpfd.evolve's
// KeyboardInterrupt.
struct Interruption {
  std::string dir, resumeDir, label;
  std::optional<int> lastGeneration;  // The last complete generation (checkpointed), if any.
  run::RunStage::Kind stage = run::RunStage::Generations;
};

// gpfd.evolve's view of a run: the per-generation callback (a true return value stops the run),
// Ctrl-C checked after each generation, the command's text when verbose, only the verdict when
// `verbose` is None without a display (what stops a run is always said, on stderr), and a
// progress display (`observer`, gpfd.discovery.progress.EvolveBar) when one is given: it is told
// when a run starts and ends and, every half second from a thread of its own, the running stage;
// the command's header and outcome lines are printed around it. A run that an interruption stops
// (KeyboardInterrupt, or any error while `interrupted()` is true: Ctrl-C came) says nothing: its
// Interruption is kept for gpfd.evolve's KeyboardInterrupt.
class PythonProgress final : public service::EvolveProgress {
 public:
  // `verbose`: None, True or False, read as a Python object: a disengaged std::optional<bool>'s
  // payload is uninitialised, and gcc -O3 tested it before the flag (valgrind: a conditional jump
  // on an uninitialised value, scripts/check-lockstep-memory --valgrind).
  PythonProgress(nb::object onGeneration, const nb::object& verbose, nb::object observer,
                 const std::string& resumeCommand, nb::object interrupted, std::atomic<bool>& stop);
  ~PythonProgress() override { stopPolling(); }

  void runStarted(const run::Discovery& d, const std::string& dir,
                  const std::string& label) override;
  void generationDone(const run::Discovery& d, const run::GenerationRecord& record,
                      const std::string& label) override;
  void runStopped(const run::Discovery& d, const std::string& dir, const std::string& resumeDir,
                  bool error) override;
  void runFinished(const run::RunOutcome& o, const std::string& dir,
                   const std::string& label) override;
  void setFinished(const std::vector<run::RunOutcome>& o, const std::string& dir) override {
    text_.setFinished(o, dir);
  }
  void alreadyComplete(const std::string& dir, int generations) override {
    text_.alreadyComplete(dir, generations);
  }
  void preparedRun(const std::string& text) override { text_.preparedRun(text); }
  // A stage before the run (the learner's choice, a budget's measurement): said, and shown by the
  // display where it has `phase`.
  void preparing(const std::string& phase) override;

  // Whether the error being handled is an interruption: KeyboardInterrupt, or any error after
  // Ctrl-C (which may surface as another). Call within a catch block, without the GIL.
  bool isInterruption();

  // The run stopped by an interruption, if one was.
  const std::optional<Interruption>& interruption() const { return interruption_; }

  // Ends the polling thread; call without the GIL, which the thread takes.
  void stopPolling();

 private:
  // The running stage to the observer every half second, until stopped. An error in the
  // observer ends the polling (reported as unraisable), never the run.
  void poll(const std::stop_token& token);
  // Needs the GIL.
  void tellStage();
  // The stage where the run ended (so that the display shows it whatever the timing), then the
  // end. A display error is reported as unraisable: the run's own outcome or error goes on.
  void runEnded(bool finished);

  nb::object onGeneration_;
  nb::object observer_;
  nb::object interrupted_;
  service::EvolveText text_;
  std::string label_;  // Of the running run.
  std::optional<Interruption> interruption_;
  std::atomic<bool>& stop_;
  std::vector<std::string> variables_;
  const run::Discovery* discovery_ = nullptr;  // The running one (runStarted to its end).
  std::jthread poller_;
};

// The text of gpfd.evolve's KeyboardInterrupt: where the run was, and how to continue it (or that
// nothing was kept).
std::string interruptionText(const Interruption& i, const std::string& resumeCommand);

}  // namespace gpfd::python
