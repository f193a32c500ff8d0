#include "firmware-host/simulate/decimated_telemetry.hpp"

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "firmware-host/telemetry_writer.hpp"

namespace facectl {

DecimatedTelemetry::DecimatedTelemetry(const ControllerModel& model, const std::string& path,
                                       std::uint64_t every)
    : path_(path), every_(every == 0 ? 1 : every) {
  file_ = std::fopen(path.c_str(), "w");
  if (file_ == nullptr) throw std::runtime_error(path + ": cannot write: " + std::strerror(errno));
  std::setvbuf(file_, nullptr, _IOFBF, 1 << 20);
  TelemetryWriter::write_header_fields(file_, model);
  for (const auto& a : model.actuators) std::fprintf(file_, ",pos.%s", a.name.c_str());
  std::fputc('\n', file_);
}

DecimatedTelemetry::~DecimatedTelemetry() {
  if (file_ != nullptr) std::fclose(file_);
}

void DecimatedTelemetry::add(double t, const TelemetryRecord& r, std::span<const double> positions) {
  const std::uint32_t coupled = row_.coupled_flags | r.coupled_flags;
  const std::uint32_t actuator_coupled = row_.actuator_coupled_flags | r.actuator_coupled_flags;
  const std::uint8_t envelope = row_.envelope_flags | r.envelope_flags;
  std::array<LimitFlags, kMaxActuators> limits = row_.limits;
  for (std::size_t i = 0; i < r.actuator_count; ++i) limits[i] |= r.limits[i];
  if (seen_++ % every_ != 0) {
    row_.coupled_flags = coupled;
    row_.actuator_coupled_flags = actuator_coupled;
    row_.envelope_flags = envelope;
    row_.limits = limits;
    return;
  }
  row_ = r;
  row_.time_s = t;
  row_.coupled_flags = coupled;
  row_.actuator_coupled_flags = actuator_coupled;
  row_.envelope_flags = envelope;
  row_.limits = limits;
  TelemetryWriter::write_fields(file_, row_);
  for (std::size_t i = 0; i < r.actuator_count; ++i) std::fprintf(file_, ",%.9g", positions[i]);
  std::fputc('\n', file_);
  row_ = TelemetryRecord{};
}

void DecimatedTelemetry::close() {
  if (file_ == nullptr) return;
  const bool failed = std::ferror(file_) != 0;
  const bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  if (failed || !closed) throw std::runtime_error(path_ + ": writing failed");
}

}  // namespace facectl
