#pragma once

#include <atomic>
#include <cstdio>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "control/controller_model.hpp"
#include "control/realtime/spsc_ring.hpp"
#include "control/telemetry_record.hpp"

namespace facectl {

// The logger thread: drains the telemetry ring into a CSV file whose columns
// docs/TELEMETRY.md documents. Every row is accounted for: written (the OS
// took its bytes), lost (taken from the ring but not written: a failed write
// or a drain cut short) or dropped (the ring was full). Nothing passes silently.
class TelemetryWriter {
 public:
  // How long finish() may spend draining by default (docs/TELEMETRY.md).
  static constexpr double kDrainBudgetSeconds = 5.0;

  // Opens the file and writes the header; throws naming the file if it cannot.
  TelemetryWriter(const ControllerModel& model, SpscRing<TelemetryRecord>& ring, std::string path);
  ~TelemetryWriter();
  TelemetryWriter(const TelemetryWriter&) = delete;
  TelemetryWriter& operator=(const TelemetryWriter&) = delete;

  void start();
  // Stops the logger thread, then drains what the ring still holds for at
  // most `budget_s` seconds, or until `give_up()` says so (a signal); what is
  // left is counted lost. Closes the file. Call after the loop has stopped.
  void finish(double budget_s = kDrainBudgetSeconds, const std::function<bool()>& give_up = {});

  std::uint64_t written() const { return written_.load(std::memory_order_relaxed); }
  std::uint64_t lost() const { return lost_.load(std::memory_order_relaxed); }
  std::uint64_t dropped() const { return ring_.dropped(); }
  // True if writing the file failed (a full disk, an I/O error): error() says why.
  bool write_failed() const { return write_failed_.load(std::memory_order_relaxed); }
  // True if finish() ran out of time or was told to give up.
  bool drain_cut_short() const { return cut_short_; }
  const std::string& error() const { return error_; }
  const std::string& path() const { return path_; }

  static void write_header(std::FILE* out, const ControllerModel& model);
  static void write_row(std::FILE* out, const TelemetryRecord& rec);
  // The row's CSV text, newline included, appended to `out`.
  static void format_row(std::string& out, const TelemetryRecord& rec);

 private:
  using Deadline = std::function<bool()>;  // true: stop waiting for the file
  void run();
  std::size_t fill();  // moves ring records into the buffer
  bool flush(const Deadline& stop_waiting);
  void discard_rest();  // counts the buffer's unwritten rows and the ring's as lost

  const ControllerModel& model_;
  SpscRing<TelemetryRecord>& ring_;
  std::string path_;
  int fd_ = -1;
  std::string buffer_;          // rows formatted, not yet written
  std::size_t buffer_off_ = 0;  // bytes of buffer_ already written
  bool header_pending_ = true;  // the buffer's first line is the header, not a row
  std::thread thread_;
  std::atomic<bool> stop_{false};
  std::atomic<std::uint64_t> written_{0};
  std::atomic<std::uint64_t> lost_{0};
  std::atomic<bool> write_failed_{false};
  bool cut_short_ = false;
  std::string error_;
};

}  // namespace facectl
