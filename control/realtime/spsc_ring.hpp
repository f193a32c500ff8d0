#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>

namespace facectl {

// Lock-free single-producer single-consumer ring of fixed capacity, allocated
// once at construction. The real-time side pushes without waiting: when the
// ring is full the element is refused and counted, never blocked on.
template <typename T>
class SpscRing {
 public:
  explicit SpscRing(std::size_t capacity)
      : capacity_(capacity), slots_(std::make_unique<T[]>(capacity)) {}
  SpscRing(const SpscRing&) = delete;
  SpscRing& operator=(const SpscRing&) = delete;

  // Producer: a slot to fill in place, or nullptr when full (counted as a drop).
  T* begin_push() {
    const std::uint64_t head = head_.load(std::memory_order_relaxed);
    if (head - tail_.load(std::memory_order_acquire) >= capacity_) {
      dropped_.fetch_add(1, std::memory_order_relaxed);
      return nullptr;
    }
    return &slots_[head % capacity_];
  }
  void commit_push() {
    head_.store(head_.load(std::memory_order_relaxed) + 1, std::memory_order_release);
  }

  bool try_push(const T& value) {
    T* slot = begin_push();
    if (slot == nullptr) return false;
    *slot = value;
    commit_push();
    return true;
  }

  // Consumer: the oldest element, or nullptr when empty; release it with pop().
  const T* front() const {
    const std::uint64_t tail = tail_.load(std::memory_order_relaxed);
    if (tail == head_.load(std::memory_order_acquire)) return nullptr;
    return &slots_[tail % capacity_];
  }
  void pop() { tail_.store(tail_.load(std::memory_order_relaxed) + 1, std::memory_order_release); }

  std::size_t capacity() const { return capacity_; }
  std::uint64_t dropped() const { return dropped_.load(std::memory_order_relaxed); }
  std::uint64_t pushed() const { return head_.load(std::memory_order_relaxed); }

 private:
  const std::size_t capacity_;
  std::unique_ptr<T[]> slots_;
  alignas(64) std::atomic<std::uint64_t> head_{0};
  alignas(64) std::atomic<std::uint64_t> tail_{0};
  alignas(64) std::atomic<std::uint64_t> dropped_{0};
};

}  // namespace facectl
