#pragma once

#include <algorithm>
#include <atomic>
#include <cstdint>

namespace facectl {

// Where the sound is: which second of the audio file is heard at a given
// CLOCK_MONOTONIC time. The audio thread sets it after each write from
// ALSA's delay; the player that times the poses reads it. Lock-free (a
// sequence lock over atomics): one writer, any number of readers.
class AudioClock {
 public:
  // At `now_ns` the listener hears second `media_s` of the file; `running`:
  // the sound moves on with time (false before the device has started, or
  // while it is stalled), but not past `limit_s` (what has been written: a
  // device that stops unnoticed must not carry the face past its sound).
  void set(std::int64_t now_ns, double media_s, bool running, double limit_s) {
    const std::uint32_t s = seq_.load(std::memory_order_relaxed);
    seq_.store(s + 1, std::memory_order_relaxed);
    std::atomic_thread_fence(std::memory_order_release);
    ns_.store(now_ns, std::memory_order_relaxed);
    media_.store(media_s, std::memory_order_relaxed);
    running_.store(running, std::memory_order_relaxed);
    limit_.store(limit_s, std::memory_order_relaxed);
    seq_.store(s + 2, std::memory_order_release);
  }

  // The second heard at `now_ns`, extrapolated from the last setting while
  // running; 0 before the first.
  double at(std::int64_t now_ns) const {
    for (;;) {
      const std::uint32_t s1 = seq_.load(std::memory_order_acquire);
      const std::int64_t ns = ns_.load(std::memory_order_relaxed);
      const double media = media_.load(std::memory_order_relaxed);
      const bool running = running_.load(std::memory_order_relaxed);
      const double limit = limit_.load(std::memory_order_relaxed);
      std::atomic_thread_fence(std::memory_order_acquire);
      if ((s1 & 1U) == 0 && seq_.load(std::memory_order_relaxed) == s1) {
        if (!running) return media;
        return std::max(media, std::min(media + static_cast<double>(now_ns - ns) * 1e-9, limit));
      }
    }
  }

 private:
  std::atomic<std::uint32_t> seq_{0};
  std::atomic<std::int64_t> ns_{0};
  std::atomic<double> media_{0.0};
  std::atomic<bool> running_{false};
  std::atomic<double> limit_{0.0};
};

}  // namespace facectl
