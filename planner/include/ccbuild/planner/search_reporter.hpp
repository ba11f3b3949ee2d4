#pragma once
// A long search's progress as lines on a stream, from a thread of its own.

#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <optional>
#include <ostream>
#include <string>
#include <thread>

#include "ccbuild/planner/plan_layer.hpp"

namespace ccbuild::planner {

/// Progress of a long single-nozzle search on a stream: a `--time-limit 600` run is
/// otherwise silent for ten minutes. A line at 1, 2, 4, 8, 16 and 32 s, then every
/// minute, with the best tour so far; nothing after the reporter is destroyed, so a
/// call that ends within a second prints nothing.
class SearchReporter {
 public:
  /// `line(best, due_s)` words the line due `due_s` after the start; `best` is null
  /// before the first tour.
  using Line = std::function<std::string(const SearchProgress*, double)>;

  SearchReporter(Line line, std::ostream& out) : line_(std::move(line)), out_(out) {
    thread_ = std::thread([this] { run(); });
  }
  ~SearchReporter() {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      done_ = true;
    }
    wake_.notify_one();
    thread_.join();
  }
  SearchReporter(const SearchReporter&) = delete;
  SearchReporter& operator=(const SearchReporter&) = delete;

  /// Called on the planning thread with each better tour.
  void record(const SearchProgress& progress) {
    const std::lock_guard<std::mutex> lock(mutex_);
    best_ = progress;
  }

 private:
  void run() {
    using Clock = std::chrono::steady_clock;
    const Clock::time_point start = Clock::now();
    double next_s = 1.0;
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
      const auto due = start + std::chrono::duration<double>(next_s);
      if (wake_.wait_until(lock, due, [this] { return done_; })) return;
      // The line is stamped with its due time: a late wake-up on a loaded machine still
      // reads "1 s", "2 s", ...
      out_ << line_(best_ ? &*best_ : nullptr, next_s) << "\n" << std::flush;
      next_s = next_s < 32.0 ? 2.0 * next_s : next_s < 60.0 ? 60.0 : next_s + 60.0;
    }
  }

  Line line_;
  std::ostream& out_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool done_ = false;
  std::optional<SearchProgress> best_;
  std::thread thread_;
};

}  // namespace ccbuild::planner
