#pragma once
// A triple buffer: one writer publishes values, one reader takes the newest complete one.
// Neither waits for the other, and the reader never sees a value being written. Three slots:
// the writer's, the reader's, and the one in the middle that the two exchange atomically.
#include <array>
#include <atomic>
#include <cstdint>

namespace scour {

template <class T>
class TripleBuffer {
 public:
  /// The writer's slot: fill it, then publish().
  T& back() { return slots_[back_]; }
  /// Makes the back slot the newest complete value.
  void publish() {
    const uint8_t old = middle_.exchange(uint8_t(back_ | kFresh), std::memory_order_acq_rel);
    back_ = old & kIndex;
  }
  /// The newest published value, if there is one the reader has not taken yet; then front()
  /// holds it. Returns false (front() unchanged) when nothing new was published.
  bool take() {
    if (!(middle_.load(std::memory_order_acquire) & kFresh)) return false;
    const uint8_t old = middle_.exchange(front_, std::memory_order_acq_rel);
    front_ = old & kIndex;
    return true;
  }
  /// The reader's slot: the value last taken.
  const T& front() const { return slots_[front_]; }

 private:
  static constexpr uint8_t kFresh = 4, kIndex = 3;
  std::array<T, 3> slots_{};
  uint8_t back_ = 0, front_ = 1;
  std::atomic<uint8_t> middle_{2};
};

}  // namespace scour
