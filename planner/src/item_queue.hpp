#pragma once
// The items a local search still has to try from (their "don't-look bits" cleared),
// first in, first out, each at most once.

#include <deque>
#include <vector>

namespace ccbuild::planner::detail {

class ItemQueue {
 public:
  explicit ItemQueue(int items) : queued_(items, 0) {}

  /// Queues `item` unless it is queued already.
  void push(int item) {
    if (!queued_[item]) {
      queued_[item] = 1;
      queue_.push_back(item);
    }
  }
  bool empty() const { return queue_.empty(); }
  /// The oldest item, taken off the queue.
  int pop() {
    const int item = queue_.front();
    queue_.pop_front();
    queued_[item] = 0;
    return item;
  }
  /// Forgets what a run cut short left queued.
  void clear() {
    for (int item : queue_) queued_[item] = 0;
    queue_.clear();
  }

 private:
  std::deque<int> queue_;
  std::vector<char> queued_;
};

}  // namespace ccbuild::planner::detail
