#pragma once

#include <atomic>
#include <cstdio>
#include <string>
#include <thread>

#include "control/controller_model.hpp"
#include "control/realtime/spsc_ring.hpp"
#include "control/telemetry_record.hpp"

namespace facectl {

// The logger thread: drains the telemetry ring into a CSV file whose columns
// docs/TELEMETRY.md documents. Drops (a full ring) are counted by the ring and
// reported by the writer; they never pass silently.
class TelemetryWriter {
 public:
  TelemetryWriter(const ControllerModel& model, SpscRing<TelemetryRecord>& ring, std::string path);
  ~TelemetryWriter();
  TelemetryWriter(const TelemetryWriter&) = delete;
  TelemetryWriter& operator=(const TelemetryWriter&) = delete;

  void start();
  // Drains everything left, closes the file. Call after the loop has stopped.
  void finish();

  std::uint64_t written() const { return written_.load(std::memory_order_relaxed); }
  std::uint64_t dropped() const { return ring_.dropped(); }
  // True if writing the file failed (e.g. a full disk): its rows are lost.
  bool write_failed() const { return write_failed_.load(std::memory_order_relaxed); }
  const std::string& path() const { return path_; }

  static void write_header(std::FILE* out, const ControllerModel& model);
  static void write_row(std::FILE* out, const TelemetryRecord& rec);

 private:
  void run();
  std::size_t drain();

  const ControllerModel& model_;
  SpscRing<TelemetryRecord>& ring_;
  std::string path_;
  std::FILE* file_ = nullptr;
  std::thread thread_;
  std::atomic<bool> stop_{false};
  std::atomic<std::uint64_t> written_{0};
  std::atomic<bool> write_failed_{false};
};

}  // namespace facectl
