#pragma once

#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "control/actuator_model.hpp"
#include "drivers/can/can_bus_options.hpp"
#include "drivers/can/can_transport.hpp"
#include "drivers/dynamixel/dynamixel_options.hpp"
#include "drivers/feetech/feetech_options.hpp"
#include "drivers/maestro/maestro_options.hpp"
#include "drivers/modbus/modbus_bus.hpp"

namespace facectl {

// What `facectl bus doctor` says about one bus. It only reads: no enable, no
// target, no configuration write reaches a device.
struct DoctorFinding {
  enum class Level { kOk, kWarning, kProblem };
  Level level = Level::kOk;
  std::string text;
};
struct DoctorReport {
  std::string bus;
  std::vector<DoctorFinding> findings;
  bool has_problems() const;
  std::string to_text() const;  // one line per finding: "  ok  ...", "  WARN ...", "  FAIL ..."
};

// A USB serial adapter's latency timer in ms (FTDI's default is 16 ms, which
// adds up to 16 ms to every Modbus RTU reply), or nullopt when `device` is not
// such an adapter. `sysfs` is the sysfs root (tests point it elsewhere).
std::optional<int> usb_serial_latency_timer_ms(const std::string& device,
                                               const std::string& sysfs = "/sys");

// printf of up to three numbers into a finding's text.
std::string doctor_format(const char* format, double a, double b = 0, double c = 0);

// The latency timer's finding for a serial device (ok, or a warning above
// 1 ms with the command that fixes it).
DoctorFinding usb_latency_finding(const std::string& device);

// Modbus: connects with `timing`, reads every board's input registers
// `samples` times and reports round-trip times, failures, the board's own
// status and channel count, and known bad defaults (libmodbus's 500 ms
// timeout, a USB latency timer above 1 ms, a cycle that cannot fit the
// configured period).
DoctorReport diagnose_modbus(const std::string& bus, const ModbusEndpoint& endpoint,
                             const std::vector<ActuatorModel>& actuators,
                             const ModbusTiming& timing, int samples = 20,
                             const modbus_map::Addresses& registers = {});

// CAN: the bus load at the tick rate, then `listen_s` of listening for the
// devices: CiA 402 drives are asked for their device type (an SDO upload,
// which changes nothing) and timed; custom boards are heard through their
// periodic feedback frames. Error frames seen are reported.
DoctorReport diagnose_can(const std::string& bus, CanTransport& transport,
                          const std::string& protocol, const std::vector<ActuatorModel>& actuators,
                          const CanBusOptions& options, double tick_hz, long bitrate,
                          double listen_s = 0.5);

// Opens a serial doctor's port or link (`Port(device, baud)`, which throws
// std::runtime_error naming the device): then the latency timer's finding;
// or nullptr and a "cannot open" problem.
template <typename Port>
std::unique_ptr<Port> doctor_open(DoctorReport& r, const std::string& device, long baud) {
  try {
    auto port = std::make_unique<Port>(device, baud);
    r.findings.push_back(usb_latency_finding(device));
    return port;
  } catch (const std::runtime_error& e) {
    r.findings.push_back({DoctorFinding::Level::kProblem, std::string("cannot open: ") + e.what()});
    return nullptr;
  }
}

// "round trip median A ms, max B ms" of the times in `ms` (sorted here; not
// empty).
std::string round_trip_text(std::vector<double>& ms);

// A warning for `who` when `at` (its decoded position) is outside the rig's
// hard range; `check` names what may be wrong besides a hand moving it.
void check_hard_range(DoctorReport& r, const std::string& who, const ActuatorModel& a, double at,
                      const std::string& check);

// DYNAMIXEL: pings every servo of the rig `samples` times (round trip,
// model, firmware), reads what would stop or surprise a run (Hardware Error
// Status, torque already on, the Return Delay Time the bus would rewrite,
// temperature, voltage, a position outside the rig's hard range) and asks
// the whole bus who answers (a broadcast PING), naming IDs not in the rig.
DoctorReport diagnose_dynamixel(const std::string& bus, const std::string& device, long baud,
                                const std::vector<ActuatorModel>& actuators,
                                const DynamixelOptions& options, int samples = 20);

// Feetech SCS/STS: pings every servo of the rig `samples` times (round
// trip, the status packet's error flags), reads its model number, torque
// already on, Response Level, the Return Delay the bus would rewrite,
// voltage, temperature and a position outside the rig's hard range, then
// pings IDs 0..kFeetechScanLastId not in the rig, naming any that answer.
inline constexpr int kFeetechScanLastId = 20;
DoctorReport diagnose_feetech(const std::string& bus, const std::string& device, long baud,
                              const std::vector<ActuatorModel>& actuators,
                              const FeetechOptions& options, int samples = 20);

// Maestro: Get Errors `samples` times (round trip, and the error register,
// which reading clears), then each channel's Get Position (the pulse it is
// sending, against the rig's hard range), and what only Maestro Control
// Center can set (its serial timeout, each channel's range and home).
DoctorReport diagnose_maestro(const std::string& bus, const std::string& device, long baud,
                              const std::vector<ActuatorModel>& actuators,
                              const MaestroOptions& options, int samples = 20);

}  // namespace facectl
