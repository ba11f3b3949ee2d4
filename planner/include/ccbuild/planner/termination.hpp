#pragma once
// When a solver must stop: a deadline, a user's cancel flag, or both. Solvers poll
// should_stop(); they are anytime and return the best answer found so far.

#include <atomic>
#include <chrono>
#include <limits>
#include <string>

namespace ccbuild::planner {

/// Why a solver finished.
enum class StopReason {
  kFinished,       ///< a one-pass algorithm ran to its end
  kProvenOptimal,  ///< the answer meets a lower bound, or an exact search completed
  kConverged,      ///< the search used its iteration budget
  kTimeLimit,      ///< the deadline came first: the best answer so far
  kCancelled,      ///< the cancel flag was raised: the best answer so far
};
std::string to_string(StopReason reason);
/// True when the clock or a cancel stopped the solver: its answer is the best so far.
inline bool cut_short(StopReason reason) {
  return reason == StopReason::kTimeLimit || reason == StopReason::kCancelled;
}

class StopCondition {
 public:
  using Clock = std::chrono::steady_clock;

  /// Stops `seconds` after now (infinity: never), or when `*cancel` becomes true.
  explicit StopCondition(double seconds = std::numeric_limits<double>::infinity(),
                         const std::atomic<bool>* cancel = nullptr)
      : start_(Clock::now()), cancel_(cancel), limit_s_(seconds) {}

  bool should_stop() const { return cancelled() || elapsed_s() >= limit_s_; }
  bool cancelled() const { return cancel_ != nullptr && cancel_->load(std::memory_order_relaxed); }
  StopReason reason() const {
    return cancelled() ? StopReason::kCancelled : StopReason::kTimeLimit;
  }
  double elapsed_s() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }
  double remaining_s() const { return limit_s_ - elapsed_s(); }
  /// A condition with the same cancel flag that also stops after `seconds` from now.
  StopCondition within(double seconds) const {
    StopCondition c(std::min(seconds, remaining_s()), cancel_);
    return c;
  }

 private:
  Clock::time_point start_;
  const std::atomic<bool>* cancel_;
  double limit_s_;
};

}  // namespace ccbuild::planner
