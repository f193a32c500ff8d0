#include "firmware-host/run/telemetry_writer.hpp"

#include <fcntl.h>
#include <poll.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdarg>
#include <cstring>
#include <stdexcept>

#include "firmware-host/run/protection_columns.hpp"

namespace facectl {
namespace {

// Rows are written in blocks of about this size: few system calls, and a
// full disk or a slow reader is noticed within one block.
constexpr std::size_t kBlockBytes = 256 * 1024;

void appendf(std::string& out, const char* format, ...) {
  char text[64];
  va_list args;
  va_start(args, format);
  const int n = std::vsnprintf(text, sizeof text, format, args);
  va_end(args);
  out.append(text, static_cast<std::size_t>(std::clamp(n, 0, static_cast<int>(sizeof text) - 1)));
}

std::uint64_t lines_in(const char* begin, std::size_t n) {
  return static_cast<std::uint64_t>(std::count(begin, begin + n, '\n'));
}

using Clock = std::chrono::steady_clock;

}  // namespace

TelemetryWriter::TelemetryWriter(const ControllerModel& model, SpscRing<TelemetryRecord>& ring,
                                 std::string path)
    : model_(model), ring_(ring), path_(std::move(path)) {
  // Non-blocking from the open on: a blocking open of a FIFO waits without
  // end for a reader that may never come (the head never starts); and a reader
  // that stops reading must not block the drain beyond its budget. (No effect
  // on regular files, whose writes do not wait on a reader.)
  const auto reader_deadline = Clock::now() + std::chrono::seconds(1);
  while ((fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC | O_NONBLOCK,
                       0644)) < 0 &&
         errno == ENXIO && Clock::now() < reader_deadline) {
    ::usleep(10'000);  // a FIFO with no reader yet: give one a moment to open it
  }
  if (fd_ < 0) {
    throw std::runtime_error(path_ + ": cannot write telemetry: " +
                             (errno == ENXIO ? std::string("no process has this FIFO open for "
                                                           "reading (waited 1 s)")
                                             : std::strerror(errno)));
  }
  buffer_.reserve(kBlockBytes + 64 * 1024);
  {
    char* text = nullptr;
    std::size_t size = 0;
    std::FILE* mem = ::open_memstream(&text, &size);
    if (mem == nullptr) throw std::runtime_error(path_ + ": cannot format the telemetry header");
    write_header(mem, model_);
    std::fclose(mem);
    buffer_.assign(text, size);
    std::free(text);
  }
  const auto give_up_at = Clock::now() + std::chrono::seconds(1);
  if (!flush([&] { return Clock::now() > give_up_at; })) {
    ::close(fd_);
    fd_ = -1;
    throw std::runtime_error(path_ + ": cannot write telemetry: " +
                             (error_.empty() ? std::string("the reader is not reading") : error_));
  }
}

TelemetryWriter::~TelemetryWriter() {
  finish(0.0);
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
  write_protection_header(out, model);
  std::fputc('\n', out);
}

void TelemetryWriter::format_row(std::string& out, const TelemetryRecord& r) {
  appendf(out, "%llu,%.6f,%.9f,%.3f,%.3f,", static_cast<unsigned long long>(r.tick), r.time_s,
          r.dt_s, r.wake_latency_s * 1e6, r.compute_s * 1e6);
  out.append(to_string(r.state));
  out.push_back(',');
  if (r.transition != TransitionReason::kNone) out.append(to_string(r.transition));
  appendf(out, ",%d,%u,%u,%.9g,", r.input_stale ? 1 : 0, r.envelope_flags, r.coupled_flags,
          r.coupled_violation);
  appendf(out, "%u,%.9g,%u,%u", r.actuator_coupled_flags, r.actuator_coupled_violation,
          r.rejected_values, r.overruns);
  for (std::size_t i = 0; i < r.signal_count; ++i) appendf(out, ",%.9g", r.face[i]);
  for (std::size_t i = 0; i < r.actuator_count; ++i) appendf(out, ",%.9g", r.command[i]);
  for (std::size_t i = 0; i < r.actuator_count; ++i) appendf(out, ",%.9g", r.feedback[i]);
  for (std::size_t i = 0; i < r.actuator_count; ++i) appendf(out, ",%u", r.limits[i]);
  if (r.protected_mask != 0) {
    char cols[kProtectionColumnsBytesAtMost * kMaxActuators];
    out.append(cols, write_protection_columns(cols, r));
  }
  out.push_back('\n');
}

void TelemetryWriter::write_row(std::FILE* out, const TelemetryRecord& rec) {
  std::string row;
  format_row(row, rec);
  std::fwrite(row.data(), 1, row.size(), out);
}

std::size_t TelemetryWriter::fill() {
  std::size_t n = 0;
  while (buffer_.size() < kBlockBytes) {
    const TelemetryRecord* rec = ring_.front();
    if (rec == nullptr) break;
    format_row(buffer_, *rec);
    ring_.pop();
    ++n;
  }
  return n;
}

bool TelemetryWriter::flush(const Deadline& stop_waiting) {
  while (buffer_off_ < buffer_.size()) {
    const ssize_t n = ::write(fd_, buffer_.data() + buffer_off_, buffer_.size() - buffer_off_);
    if (n > 0) {
      // A row counts as written once the OS took its last byte.
      std::uint64_t rows = lines_in(buffer_.data() + buffer_off_, static_cast<std::size_t>(n));
      if (header_pending_ && rows > 0) {
        header_pending_ = false;
        --rows;
      }
      written_.fetch_add(rows, std::memory_order_relaxed);
      buffer_off_ += static_cast<std::size_t>(n);
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && errno == EAGAIN) {
      if (stop_waiting()) return false;
      pollfd p{fd_, POLLOUT, 0};
      ::poll(&p, 1, 50);
      continue;
    }
    error_ = n == 0 ? "the file accepted no bytes" : std::strerror(errno);
    write_failed_.store(true, std::memory_order_relaxed);
    return false;
  }
  buffer_.clear();
  buffer_off_ = 0;
  return true;
}

void TelemetryWriter::discard_rest() {
  if (buffer_off_ < buffer_.size()) {
    lost_.fetch_add(lines_in(buffer_.data() + buffer_off_, buffer_.size() - buffer_off_),
                    std::memory_order_relaxed);
  }
  buffer_.clear();
  buffer_off_ = 0;
  std::uint64_t n = 0;
  while (ring_.front() != nullptr) {
    ring_.pop();
    ++n;
  }
  lost_.fetch_add(n, std::memory_order_relaxed);
}

void TelemetryWriter::run() {
  const auto stopping = [this] { return stop_.load(std::memory_order_relaxed); };
  while (!stopping()) {
    if (write_failed()) {
      discard_rest();  // nowhere to write: count, so the ring never fills on it
    } else if (fill() > 0 || !buffer_.empty()) {
      if (!flush(stopping)) continue;
    }
    if (ring_.front() == nullptr) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

void TelemetryWriter::finish(double budget_s, const std::function<bool()>& give_up) {
  stop_.store(true, std::memory_order_relaxed);
  if (thread_.joinable()) thread_.join();
  if (fd_ < 0) return;
  const auto deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                           std::chrono::duration<double>(budget_s));
  const Deadline stop_waiting = [&] { return Clock::now() >= deadline || (give_up && give_up()); };
  while (!write_failed()) {
    fill();
    if (buffer_.empty()) break;
    if (!flush(stop_waiting)) {
      cut_short_ = !write_failed();
      break;
    }
  }
  discard_rest();
  if (::close(fd_) != 0 && !write_failed()) {
    error_ = std::strerror(errno);
    write_failed_.store(true, std::memory_order_relaxed);
  }
  fd_ = -1;
}

}  // namespace facectl
