#include "sim/devices/can_device_network.hpp"

#include <chrono>
#include <ctime>

namespace facectl::sim {

void CanDevice::emit(const CanFrame& f, std::int64_t now_ns) {
  ++emitted_;
  const int drop = faults_.drop_every.load();
  if (drop > 0 && emitted_ % static_cast<std::uint64_t>(drop) == 0) return;
  CanFrame out = f;
  if (faults_.corrupt_next.load() > 0 && out.len > 0) {
    faults_.corrupt_next.fetch_sub(1);
    --out.len;  // one byte short: every decoder must refuse it
  }
  outbox_.push_back({now_ns + static_cast<std::int64_t>(faults_.delay_ms.load()) * 1'000'000, out});
}

CanDeviceNetwork::CanDeviceNetwork(CanTransport& transport, std::vector<CanDevice*> devices)
    : transport_(transport), devices_(std::move(devices)) {}

CanDeviceNetwork::~CanDeviceNetwork() {
  stop();
}

void CanDeviceNetwork::poll(std::int64_t now_ns) {
  CanFrame f;
  CanError err = CanError::kNone;
  while (transport_.receive(f, err)) {
    if (err != CanError::kNone) continue;
    for (CanDevice* d : devices_) {
      if (!d->faults().silent.load()) d->on_frame(f, now_ns);
    }
  }
  for (CanDevice* d : devices_) {
    if (d->faults().silent.load()) {
      d->outbox_.clear();
      continue;
    }
    d->step(now_ns);
    while (!d->outbox_.empty() && d->outbox_.front().at_ns <= now_ns) {
      if (transport_.send(d->outbox_.front().frame)) sent_.fetch_add(1);
      d->outbox_.pop_front();
    }
  }
}

void CanDeviceNetwork::start(int period_us) {
  thread_ = std::thread([this, period_us] {
    while (!stop_.load()) {
      timespec ts{};
      clock_gettime(CLOCK_MONOTONIC, &ts);
      poll(static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec);
      std::this_thread::sleep_for(std::chrono::microseconds(period_us));
    }
  });
}

void CanDeviceNetwork::stop() {
  stop_.store(true);
  if (thread_.joinable()) thread_.join();
}

}  // namespace facectl::sim
