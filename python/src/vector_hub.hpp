// python: one Gymnasium VectorEnv (made, reset and checked by
// gpfd.adapters.vector_adapter.VectorAdapter) shared by the lockstep players of one or several
// fitness evaluations, so that one call of its step advances the episodes of all of them (a
// lockstep group, lockstep_group.hpp; alone, a group of one). Each player (member) plays its lanes
// in its own range of sub-environments.
//
// Rounds: a member's resetAll or step waits (the members are fibers of one thread,
// gpfd/fibers/scheduler.hpp) until every member still playing has asked for one, then the last to
// ask has the round run on the thread's own stack (never on a fiber's: it calls Python), every
// member suspended meanwhile: the steps of all members that asked for a step, in one vector step;
// or, when every member asks for a reset, one reset of the whole vector environment. So the members
// play their batches of episodes together and start the next batches together, and which calls make
// up a round follows from what the members ask: the same members give the same rounds. A member's
// sub-environments step along with the others while it waits for a reset (unless the vector form
// steps subsets, EnvPool); what they return is not read.
#pragma once

#include <cstdint>
#include <exception>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "env_batch.hpp"
#include "gpfd/env/batch.hpp"
#include "gpfd/util/rng.hpp"
#include "read_view.hpp"

namespace gpfd::python {

// Thrown in the members of a round that failed, except the one that ran it (which throws the
// cause).
class LockstepGroupFailed : public std::runtime_error {
 public:
  LockstepGroupFailed() : std::runtime_error("another member of its lockstep group failed") {}
};

class VectorHub {
 public:
  // `adapter` is a gpfd.adapters.vector_adapter.VectorAdapter. Called with the GIL held.
  VectorHub(nb::object adapter, std::size_t stateDim, std::size_t actionComponents,
            std::size_t members);
  ~VectorHub();
  VectorHub(const VectorHub&) = delete;
  VectorHub& operator=(const VectorHub&) = delete;

  // Member `m`'s calls (BatchEnvironment's), from its fiber without the GIL; each returns when
  // its round has run. Lane l of the member plays in one of its sub-environments.
  void resetAll(std::size_t m, std::span<Rng> rngs, const env::BatchBuffers& io);
  void step(std::size_t m, const env::BatchBuffers& io);
  void moveLane(std::size_t m, std::size_t from, std::size_t to);
  // Member `m` asks for nothing more: rounds no longer wait for it. May run a round that was
  // waiting only for it (and throw what that round threw).
  void leave(std::size_t m);

 private:
  enum class Wants { Nothing, Reset, Step };
  struct Member {
    Wants wants = Wants::Nothing;
    const env::BatchBuffers* io = nullptr;
    std::vector<std::uint64_t> seeds;   // A reset's: one per lane.
    bool playing = true;                // Has not left.
    std::size_t offset = 0, size = 0;   // Its sub-environments: [offset, offset + size).
    std::vector<std::size_t> physical;  // Lane l plays in sub-environment offset + physical[l].
  };
  // What one vector step returned, read in place: rows are sub-environments.
  struct Outputs {
    ReadView obs, reward, terminated, truncated;
    ReadView finalMask, finalObs;  // withFinal: info["_final_obs"], info["final_obs"].
    ReadView elapsed;              // withElapsed: info[elapsedKey_].
    bool withFinal = false, withElapsed = false;
  };

  // Asks for a round, runs it where this call completes it, else waits for it (handing over to
  // the group's other fibers); throws the round's failure (the cause where this member ran it).
  void await(std::size_t m, Wants wants, const env::BatchBuffers& io);
  // Runs the round now due; true when it failed (failure_ set). runRoundOnThreadStack: from a
  // member's fiber, on the thread's own stack.
  bool runRound();
  bool runRoundOnThreadStack();
  bool roundDue() const { return playing_ > 0 && waiting_ == playing_; }
  [[noreturn]] void throwFailure(bool ranIt);

  void resetMembers(const std::vector<std::size_t>& resetting);
  void stepMembers(const std::vector<std::size_t>& stepping);
  void nativeStep(const std::vector<std::size_t>& stepping);
  void book(const Member& member, const Outputs& out);
  void markEnded(const Outputs& out);
  void bindNative(nb::handle engine);
  void bindActions();
  void writeActions(const std::vector<std::size_t>& stepping);
  // f(io, l, p) for each playing lane l of the members, p its sub-environment.
  template <typename F>
  void forEachLane(const std::vector<std::size_t>& members, F&& f) const {
    for (std::size_t m : members) {
      const Member& member = members_[m];
      for (std::size_t l = 0; l < member.io->lanes; ++l) {
        f(*member.io, l, member.offset + member.physical[l]);
      }
    }
  }
  void resetEnded(const std::vector<std::size_t>& stepping);
  ReadView read(nb::handle value, const std::string& what, std::size_t ndim, std::size_t cols = 1);
  std::vector<std::size_t> activeSubEnvironments(const std::vector<std::size_t>& stepping) const;
  [[noreturn]] void resetOnItsOwn(std::size_t subEnv, std::int32_t episodeStep,
                                  const std::string& how) const;
  [[noreturn]] void badObservation(std::size_t subEnv, std::int32_t episodeStep, std::size_t index,
                                   double value) const;

  std::size_t stateDim_, components_;

  // The rounds.
  std::vector<Member> members_;
  std::size_t playing_ = 0;       // Members that have not left.
  std::size_t waiting_ = 0;       // Members whose call waits for its round.
  std::vector<std::size_t> due_;  // The members the running round serves.
  std::exception_ptr failure_;

  // The vector environment, as the adapter has it (read at each reset).
  nb::object adapter_;
  std::int64_t start_ = 0;     // A discrete space's first action.
  bool disabled_ = false;      // Autoreset disabled: ended sub-environments need a reset.
  std::string elapsedKey_;     // The key of info that counts the steps of each episode, if any.
  nb::object step_, actions_;  // The vector environment's step and the action array it receives.
  nb::object stepSubset_;      // The adapter's step_subset, where it steps subsets.
  std::string elapsedWhat_;    // info['<elapsedKey_>'], for errors.
  void* actionData_ = nullptr;
  enum class ActionKind { I64, F64, F32 };
  ActionKind actionKind_ = ActionKind::F64;
  bool subsets_ = false;              // Its step takes env_id: only playing ones are stepped.
  std::size_t lanes_ = 0;             // Sub-environments.
  std::vector<std::size_t> stepped_;  // The sub-environment of each row of the last step.
  std::vector<std::size_t> rowOf_;    // The row of each sub-environment stepped.
  std::vector<char> ended_;           // Per sub-environment: its episode ended (disabled mode).
  std::int64_t steps_ = 0;            // Vector steps since the last reset.
  std::vector<nb::object> keep_;      // Converted arrays, alive while read.
  nb::tuple finals_;                  // The final observations of a same-step autoreset.
  // gpfd's own vector environment: its engine and the buffers of its step.
  struct NativeBuffers {
    EnvBatch* engine = nullptr;
    std::vector<double> actions, obs, rewards, finalObs;
    std::unique_ptr<bool[]> terminated, truncated, finalMask;
  };
  std::unique_ptr<NativeBuffers> native_;
};

}  // namespace gpfd::python
