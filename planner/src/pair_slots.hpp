#pragma once
// A table of int slots by 64-bit key for the cost model's cache of crossings between two
// layer points (cost_model.cpp): open addressing with linear probing, at most half full.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace ccbuild::planner::detail {

/// Slots by point pair for large layers: open addressing with linear probing. The search
/// asks for millions of pairs; std::unordered_map's node per entry made the lookups a
/// quarter of planning a 6,880-wall layer (bench/README.md, issue 50).
class PairSlots {
 public:
  /// The slot of KEY (0 when the pair has none yet), created on first use.
  int& operator[](std::uint64_t key) {
    if (2 * (used_ + 1) > keys_.size()) grow();
    std::size_t at = position(key);
    if (keys_[at] == kEmpty) {
      keys_[at] = key;
      ++used_;
    }
    return slots_[at];
  }

 private:
  static constexpr std::uint64_t kEmpty = ~std::uint64_t{0};  // no pair of int points
  std::size_t position(std::uint64_t key) const {
    // Fibonacci hashing: the product's top bits depend on every bit of the key.
    const std::size_t mask = keys_.size() - 1;
    std::size_t at = static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ULL) >> shift_);
    while (keys_[at] != kEmpty && keys_[at] != key) at = (at + 1) & mask;
    return at;
  }
  void grow() {
    std::vector<std::uint64_t> keys(std::max<std::size_t>(1024, 2 * keys_.size()), kEmpty);
    shift_ = 64;
    for (std::size_t size = keys.size(); size > 1; size /= 2) --shift_;
    std::vector<int> slots(keys.size(), 0);
    keys.swap(keys_);
    slots.swap(slots_);
    for (std::size_t i = 0; i < keys.size(); ++i)
      if (keys[i] != kEmpty) {
        const std::size_t at = position(keys[i]);
        keys_[at] = keys[i];
        slots_[at] = slots[i];
      }
  }
  std::vector<std::uint64_t> keys_;
  std::vector<int> slots_;
  std::size_t used_ = 0;
  int shift_ = 64;  // 64 - log2(capacity)
};

}  // namespace ccbuild::planner::detail
