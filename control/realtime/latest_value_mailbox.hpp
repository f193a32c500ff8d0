#pragma once

#include <atomic>
#include <cstdint>

namespace facectl {

// Lock-free single-producer single-consumer "latest value" mailbox (a triple
// buffer). The producer never waits for the consumer and the consumer always
// gets the newest complete value: the real-time tick reads it without a lock
// and without a system call. Intermediate values may be skipped by design.
template <typename T>
class LatestValueMailbox {
 public:
  LatestValueMailbox() = default;
  LatestValueMailbox(const LatestValueMailbox&) = delete;
  LatestValueMailbox& operator=(const LatestValueMailbox&) = delete;

  // Producer side.
  void publish(const T& value) {
    buffers_[back_] = value;
    // Swap our back buffer with the middle one and mark it fresh.
    const std::uint8_t previous =
        middle_.exchange(static_cast<std::uint8_t>(back_ | kFresh), std::memory_order_acq_rel);
    back_ = previous & kIndexMask;
  }

  // Consumer side: copies the newest value into `out` if one arrived since the
  // last call. Returns false (and leaves `out` alone) when nothing is new.
  bool consume(T& out) {
    if ((middle_.load(std::memory_order_relaxed) & kFresh) == 0) return false;
    const std::uint8_t previous = middle_.exchange(front_, std::memory_order_acq_rel);
    front_ = previous & kIndexMask;
    out = buffers_[front_];
    return true;
  }

  static constexpr bool is_lock_free() { return std::atomic<std::uint8_t>::is_always_lock_free; }

 private:
  static constexpr std::uint8_t kFresh = 0x4;
  static constexpr std::uint8_t kIndexMask = 0x3;

  T buffers_[3]{};
  std::atomic<std::uint8_t> middle_{1};
  std::uint8_t back_ = 0;   // owned by the producer
  std::uint8_t front_ = 2;  // owned by the consumer
};

}  // namespace facectl
