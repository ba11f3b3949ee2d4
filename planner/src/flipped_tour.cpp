#include "flipped_tour.hpp"

#include <algorithm>

namespace ccbuild::planner::detail {

FlippedTour::FlippedTour(const WallTour& base) : base_(base) {
  reset();
}

void FlippedTour::reset() {
  runs_.assign(1, Run{0, base_.size() - 1, false});
}

FlippedTour::Place FlippedTour::place_in_runs(int item) const {
  const int p = base_.position_of(item);
  // The last run, by base position, that starts at or before p.
  const auto it = std::upper_bound(by_base_.begin(), by_base_.end(), p,
                                   [&](int position, int r) { return position < runs_[r].first; });
  const int r = *(it - 1);
  const Run& run = runs_[r];
  // Walked backwards, an item is entered by its base exit node.
  return {offset_[r] + (run.backwards ? run.last - p : p - run.first),
          run.backwards ? base_.entry(p) ^ 1 : base_.entry(p)};
}

int FlippedTour::entry_in_runs(int position) const {
  const int r = static_cast<int>(std::upper_bound(offset_.begin(), offset_.end(), position) -
                                 offset_.begin()) -
                1;
  const Run& run = runs_[r];
  const int k = position - offset_[r];
  // Walked backwards, an item is entered by its base exit node.
  return run.backwards ? base_.entry(run.last - k) ^ 1 : base_.entry(run.first + k);
}

void FlippedTour::index_runs() {
  offset_.resize(runs_.size());
  by_base_.resize(runs_.size());
  int offset = 0;
  for (int r = 0; r < runs(); ++r) {
    offset_[r] = offset;
    offset += runs_[r].length();
    by_base_[r] = r;
  }
  std::sort(by_base_.begin(), by_base_.end(),
            [&](int x, int y) { return runs_[x].first < runs_[y].first; });
}

int FlippedTour::split_at(int position) {
  int offset = 0;
  for (int r = 0; r < runs(); ++r) {
    const Run run = runs_[r];
    const int k = position - offset;
    if (k == 0) return r;
    if (k < run.length()) {
      // The first k items of the walk stay in run r, the rest start run r + 1.
      Run head = run, tail = run;
      if (run.backwards) {
        head.first = run.last - k + 1;
        tail.last = run.last - k;
      } else {
        head.last = run.first + k - 1;
        tail.first = run.first + k;
      }
      runs_[r] = head;
      runs_.insert(runs_.begin() + r + 1, tail);
      return r + 1;
    }
    offset += run.length();
  }
  return runs();
}

void FlippedTour::reverse(int first, int last) {
  const int n = size();
  if (first > last) {
    // Wraps past the end: the complement last+1 .. first-1 does not.
    if (last + 1 == first) return;  // the whole tour: the same cycle
    const int from = last + 1;
    last = first - 1;
    first = from;
  }
  if (last - first + 1 >= n) return;
  const int begin = split_at(first);
  const int end = split_at(last + 1);
  std::reverse(runs_.begin() + begin, runs_.begin() + end);
  for (int r = begin; r < end; ++r) runs_[r].backwards = !runs_[r].backwards;
  index_runs();
}

}  // namespace ccbuild::planner::detail
