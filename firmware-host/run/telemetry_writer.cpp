#include "firmware-host/run/telemetry_writer.hpp"

#include <cerrno>
#include <chrono>
#include <cstring>
#include <stdexcept>

namespace facectl {

TelemetryWriter::TelemetryWriter(const ControllerModel& model, SpscRing<TelemetryRecord>& ring,
                                 std::string path)
    : model_(model), ring_(ring), path_(std::move(path)) {
  file_ = std::fopen(path_.c_str(), "w");
  if (file_ == nullptr) {
    throw std::runtime_error(path_ + ": cannot write telemetry: " + std::strerror(errno));
  }
  std::setvbuf(file_, nullptr, _IOFBF, 1 << 20);
  write_header(file_, model_);
}

TelemetryWriter::~TelemetryWriter() {
  finish();
}

void TelemetryWriter::start() {
  thread_ = std::thread([this] { run(); });
}

void TelemetryWriter::write_header(std::FILE* out, const ControllerModel& model) {
  std::fputs(
      "tick,time_s,dt_s,wake_latency_us,compute_us,state,transition,input_stale,envelope_flags,"
      "coupled_flags,coupled_violation,actuator_coupled_flags,actuator_coupled_violation,"
      "rejected,overruns",
      out);
  for (std::size_t i = 0; i < model.layout.size(); ++i) {
    std::fprintf(out, ",face.%s", model.layout.signal(i).name.c_str());
  }
  for (const auto& a : model.actuators) std::fprintf(out, ",cmd.%s", a.name.c_str());
  for (const auto& a : model.actuators) std::fprintf(out, ",fb.%s", a.name.c_str());
  for (const auto& a : model.actuators) std::fprintf(out, ",lim.%s", a.name.c_str());
  std::fputc('\n', out);
}

void TelemetryWriter::write_row(std::FILE* out, const TelemetryRecord& r) {
  std::fprintf(
      out, "%llu,%.6f,%.9f,%.3f,%.3f,%s,%s,%d,%u,%u,%.9g,%u,%.9g,%u,%u",
      static_cast<unsigned long long>(r.tick), r.time_s, r.dt_s, r.wake_latency_s * 1e6,
      r.compute_s * 1e6, std::string(to_string(r.state)).c_str(),
      r.transition == TransitionReason::kNone ? "" : std::string(to_string(r.transition)).c_str(),
      r.input_stale ? 1 : 0, r.envelope_flags, r.coupled_flags, r.coupled_violation,
      r.actuator_coupled_flags, r.actuator_coupled_violation, r.rejected_values, r.overruns);
  for (std::size_t i = 0; i < r.signal_count; ++i) std::fprintf(out, ",%.9g", r.face[i]);
  for (std::size_t i = 0; i < r.actuator_count; ++i) std::fprintf(out, ",%.9g", r.command[i]);
  for (std::size_t i = 0; i < r.actuator_count; ++i) std::fprintf(out, ",%.9g", r.feedback[i]);
  for (std::size_t i = 0; i < r.actuator_count; ++i) std::fprintf(out, ",%u", r.limits[i]);
  std::fputc('\n', out);
}

std::size_t TelemetryWriter::drain() {
  std::size_t n = 0;
  while (const TelemetryRecord* rec = ring_.front()) {
    write_row(file_, *rec);
    ring_.pop();
    ++n;
  }
  written_.fetch_add(n, std::memory_order_relaxed);
  if (std::ferror(file_) != 0) write_failed_.store(true, std::memory_order_relaxed);
  return n;
}

void TelemetryWriter::run() {
  while (!stop_.load(std::memory_order_relaxed)) {
    if (drain() == 0) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

void TelemetryWriter::finish() {
  stop_.store(true, std::memory_order_relaxed);
  if (thread_.joinable()) thread_.join();
  if (file_ == nullptr) return;
  drain();
  if (std::fclose(file_) != 0) write_failed_.store(true, std::memory_order_relaxed);
  file_ = nullptr;
}

}  // namespace facectl
