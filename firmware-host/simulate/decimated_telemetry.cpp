#include "firmware-host/simulate/decimated_telemetry.hpp"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "firmware-host/run/protection_columns.hpp"
#include "firmware-host/simulate/limit_flags_or.hpp"
#include "firmware-host/simulate/write_f6.hpp"

namespace facectl {

DecimatedTelemetry::DecimatedTelemetry(const ControllerModel& model, const std::string& path,
                                       std::uint64_t every)
    : path_(path), every_(every == 0 ? 1 : every) {
  file_ = std::fopen(path.c_str(), "w");
  if (file_ == nullptr) throw std::runtime_error(path + ": cannot write: " + std::strerror(errno));
  std::setvbuf(file_, nullptr, _IOFBF, 1 << 20);
  std::fputs("tick,time_s,state,envelope_flags,coupled_flags,actuator_coupled_flags", file_);
  for (const auto& a : model.actuators) {
    std::fprintf(file_, ",cmd.%s,pos.%s,lim.%s", a.name.c_str(), a.name.c_str(), a.name.c_str());
  }
  write_protection_header(file_, model);
  std::fputc('\n', file_);
}

DecimatedTelemetry::~DecimatedTelemetry() {
  if (file_ != nullptr) std::fclose(file_);
}

void DecimatedTelemetry::add(double t, const TelemetryRecord& r,
                             std::span<const double> positions) {
  envelope_ |= r.envelope_flags;
  coupled_ |= r.coupled_flags;
  actuator_coupled_ |= r.actuator_coupled_flags;
  or_limit_flags(limits_, r.limits);
  if (seen_++ % every_ != 0) return;
  // Formatted by hand, not fprintf: the same bytes, a fraction of the instructions.
  char line[(64 + kProtectionColumnsBytesAtMost) * kMaxActuators];
  char* p = line;
  // An integer takes at most 20 characters; bounding to_chars by that (not by
  // `end`) also shows the compiler that the row stays inside `line`.
  const auto separated = [&](auto flags) {
    *p++ = ',';
    p = std::to_chars(p, p + 20, flags).ptr;
  };
  p = std::to_chars(p, p + 20, seen_ - 1).ptr;
  *p++ = ',';
  p = write_f6(p, p + 320, t);  // %.6f: at most 317 characters
  *p++ = ',';
  const std::string_view state = to_string(r.state);
  p = std::copy(state.begin(), state.end(), p);
  separated(static_cast<unsigned>(envelope_));
  separated(coupled_);
  separated(actuator_coupled_);
  // As printf's %.6g, byte for byte (write_g6), the text reused while a value repeats.
  const auto value = [&](LastValueText& last, double v) {
    *p++ = ',';
    // Round-off below a nanometre or nanoradian is written as 0, not as e-25 noise.
    p = last.write(p, std::fabs(v) < 1e-9 ? 0.0 : v);
  };
  for (std::size_t i = 0; i < r.actuator_count; ++i) {
    value(last_command_[i], r.command[i]);
    value(last_position_[i], positions[i]);
    separated(limits_[i]);
  }
  p = write_protection_columns(p, r);
  *p++ = '\n';
  std::fwrite(line, 1, static_cast<std::size_t>(p - line), file_);
  envelope_ = 0;
  coupled_ = actuator_coupled_ = 0;
  limits_.fill(0);
}

void DecimatedTelemetry::close() {
  if (file_ == nullptr) return;
  const bool failed = std::ferror(file_) != 0;
  const bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  if (failed || !closed) throw std::runtime_error(path_ + ": writing failed");
}

}  // namespace facectl
