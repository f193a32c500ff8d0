#include "firmware-host/simulate/output_pipeline.hpp"

#include <sys/prctl.h>

#include <chrono>
#include <stdexcept>

#include "firmware-host/simulate/actuator_plots.hpp"
#include "firmware-host/simulate/decimated_telemetry.hpp"
#include "firmware-host/simulate/progress_bar.hpp"
#include "firmware-host/simulate/simulation_stats.hpp"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace facectl {
namespace {

// Waits briefly on the CPU, then gives the CPU away: the sinks' thread sleeps
// (it keeps up easily and need not burn its core), the ticking thread only
// yields (it should lose no time, and on a busy machine the sinks' thread may
// need its core).
class Backoff {
 public:
  explicit Backoff(bool sleep) : sleep_(sleep) {}
  void pause() {
    if (++spins_ < 256) {
#if defined(__x86_64__) || defined(__i386__)
      _mm_pause();
#endif
      return;
    }
    if (sleep_) {
      std::this_thread::sleep_for(std::chrono::microseconds(20));
    } else {
      std::this_thread::yield();
    }
  }

 private:
  bool sleep_;
  int spins_ = 0;
};

}  // namespace

bool OutputPipeline::worth_threading() {
  return std::thread::hardware_concurrency() > 1;
}

OutputPipeline::OutputPipeline(SpscRing<TelemetryRecord>& telemetry, const SimulationSinks& sinks,
                               std::size_t actuators, bool threaded)
    : telemetry_(telemetry), sinks_(sinks), actuators_(actuators), samples_(telemetry.capacity()) {
  if (actuators > kMaxActuators) throw std::invalid_argument("output pipeline: too many actuators");
  if (threaded) worker_ = std::thread([this] { work(); });
}

OutputPipeline::~OutputPipeline() {
  done_.store(true, std::memory_order_release);
  if (worker_.joinable()) worker_.join();
}

void OutputPipeline::wait_for_room() {
  Backoff backoff(false);
  while (telemetry_.size() >= telemetry_.capacity() && !failed()) backoff.pause();
}

void OutputPipeline::push(double t, std::span<const double> positions) {
  Sample* s = samples_.begin_push();
  // The ring has as many slots as the telemetry ring, whose room was waited
  // for before the tick, and every record gets one sample.
  if (s == nullptr) throw std::logic_error("output pipeline: no room for a sample");
  s->t = t;
  std::copy_n(positions.begin(), actuators_, s->positions.begin());
  samples_.commit_push();
  if (!worker_.joinable()) consume_one();
}

void OutputPipeline::consume_one() {
  const Sample& s = *samples_.front();
  // The Controller published the record before the sample was pushed.
  const TelemetryRecord& r = *telemetry_.front();
  const std::span<const double> pos(s.positions.data(), actuators_);
  if (!failed()) {
    try {
      if (sinks_.stats != nullptr) sinks_.stats->add(s.t, r, pos);
      if (sinks_.telemetry != nullptr) sinks_.telemetry->add(s.t, r, pos);
      if (sinks_.plots != nullptr) sinks_.plots->add(s.t, r, pos);
      if (sinks_.progress != nullptr) sinks_.progress->update(s.t);
    } catch (...) {
      error_ = std::current_exception();
      failed_.store(true, std::memory_order_release);
    }
  }
  telemetry_.pop();
  samples_.pop();
}

void OutputPipeline::work() {
  // Short sleeps that end on time (default slack: 50 us), so that the ring,
  // small enough to stay in cache, does not fill while this thread sleeps.
  prctl(PR_SET_TIMERSLACK, 1000UL, 0UL, 0UL, 0UL);
  Backoff backoff(true);
  for (;;) {
    if (samples_.front() != nullptr) {
      consume_one();
      backoff = Backoff(true);
    } else if (done_.load(std::memory_order_acquire)) {
      // Everything pushed before done_ was set is visible now: drain it.
      if (samples_.front() == nullptr) return;
    } else {
      backoff.pause();
    }
  }
}

void OutputPipeline::finish() {
  done_.store(true, std::memory_order_release);
  if (worker_.joinable()) worker_.join();
  if (error_) std::rethrow_exception(error_);
}

}  // namespace facectl
