// `facectl bus doctor` for a Maestro bus: Get Position and Get Errors only;
// no target reaches a channel. Get Errors, the only way to read the error
// register, also clears it: the doctor reports what it cleared.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>

#include "control/clock.hpp"
#include "drivers/bus_doctor.hpp"
#include "drivers/protocol/maestro_serial.hpp"
#include "drivers/protocol/wire_encoding.hpp"
#include "drivers/serial/serial_port.hpp"

namespace facectl {
namespace {

using Level = DoctorFinding::Level;

// One command and its two-byte reply; false on a short or missing reply.
bool ask(SerialPort& port, std::span<const std::uint8_t> command, double wait_s,
         std::uint16_t& value) {
  port.discard_input();
  const auto wait_ns = static_cast<std::int64_t>(wait_s * 1e9);
  if (!port.write_all(command, wait_ns)) return false;
  std::uint8_t b[2];
  std::size_t got = 0;
  const std::int64_t deadline = monotonic_ns() + wait_ns;
  while (got < 2) {
    const std::int64_t left = deadline - monotonic_ns();
    if (left <= 0) return false;
    const long n = port.read_some({b + got, 2 - got}, left);
    if (n < 0) return false;
    got += static_cast<std::size_t>(n);
  }
  value = maestro::reply_u16(b);
  return true;
}

std::string hex4(std::uint16_t v) {
  char b[8];
  std::snprintf(b, sizeof b, "0x%04x", v);
  return b;
}

}  // namespace

DoctorReport diagnose_maestro(const std::string& bus, const std::string& device, long baud,
                              const std::vector<ActuatorModel>& actuators,
                              const MaestroOptions& options, int samples) {
  DoctorReport r;
  const maestro::Addressing to{options.protocol, options.device_number};
  r.bus = bus + " (Maestro " + device + " " + std::to_string(baud) + " baud, " +
          (options.protocol == maestro::Protocol::kCompact
               ? std::string("compact protocol")
               : "Pololu protocol, device " + std::to_string(options.device_number)) +
          ")";
  const auto port = doctor_open<SerialPort>(r, device, baud);
  if (port == nullptr) return r;
  const double wait_s = std::max(options.response_timeout_s, 0.002) + 4 * serial_byte_s(baud);
  std::uint8_t tx[8];
  const std::size_t n_errors = maestro::encode_get_errors(to, tx);
  std::vector<double> ms;
  std::uint16_t bits = 0, seen = 0;
  for (int i = 0; i < samples; ++i) {
    const std::int64_t t0 = monotonic_ns();
    if (ask(*port, {tx, n_errors}, wait_s, bits)) {
      ms.push_back(static_cast<double>(monotonic_ns() - t0) * 1e-6);
      seen |= bits;
    }
  }
  if (ms.empty()) {
    r.findings.push_back(
        {Level::kProblem,
         "no answer to " + std::to_string(samples) +
             " Get Errors (serial mode USB Dual Port or UART fixed baud at this rate? protocol, "
             "device number, wiring, power?)"});
    return r;
  }
  r.findings.push_back(
      {ms.size() == static_cast<std::size_t>(samples) ? Level::kOk : Level::kWarning,
       std::to_string(ms.size()) + "/" + std::to_string(samples) + " Get Errors answered, " +
           round_trip_text(ms)});
  if (seen != 0) {
    r.findings.push_back(
        {Level::kProblem,
         "error register " + hex4(seen) + ": " + maestro::error_text(seen) +
             " (cleared by reading it; a serial timeout means the host fell silent longer "
             "than the Maestro's Serial Timeout)"});
  } else {
    r.findings.push_back({Level::kOk, "error register 0x0000: no errors"});
  }
  for (const ActuatorModel& a : actuators) {
    const std::string who = "channel " + std::to_string(a.address) + " (" + a.name + ")";
    const std::size_t n = maestro::encode_get_position(to, a.address, tx);
    std::uint16_t q = 0;
    if (n == 0 || !ask(*port, {tx, n}, wait_s, q)) {
      r.findings.push_back({Level::kProblem, who + ": no answer to Get Position"});
      continue;
    }
    if (q == 0) {
      r.findings.push_back({Level::kOk, who + ": no pulses (off)"});
      continue;
    }
    const WireEncoding enc(a.kind, a.encoding);
    const double at = enc.decode(std::llround(q / 4.0));
    const bool outside = at < a.limits.position_min || at > a.limits.position_max;
    r.findings.push_back(
        {outside ? Level::kWarning : Level::kOk,
         who + doctor_format(": sending %.2f us", q / 4.0) +
             (outside ? " (outside the rig's hard range: another program, a script, or its "
                        "home setting?)"
                      : "")});
  }
  // Anything it did not reject as a command: the last check.
  if (ask(*port, {tx, n_errors}, wait_s, bits) && bits != 0) {
    r.findings.push_back(
        {Level::kProblem, "Get Position raised errors: " + maestro::error_text(bits) +
                              " (a channel the Maestro does not have?)"});
  }
  r.findings.push_back(
      {Level::kOk,
       "set in Maestro Control Center (USB only, not readable over serial): Serial Settings: "
       "Timeout a few cycles long (e.g. 0.20 s), so the Maestro stops when facectl does; each "
       "channel's Min/Max covering the rig's hard limits, its Home \"Off\""});
  return r;
}

}  // namespace facectl
