#include "drivers/bus_doctor.hpp"

#include <modbus/modbus.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>
#include <thread>

#include "control/clock.hpp"
#include "drivers/can/cia402_bus.hpp"
#include "drivers/can/custom_can_bus.hpp"
#include "drivers/modbus/modbus_timeouts.hpp"
#include "drivers/protocol/cia402_frames.hpp"
#include "drivers/protocol/custom_can_frames.hpp"
#include "drivers/protocol/modbus_register_map.hpp"

namespace facectl {

namespace {

using Level = DoctorFinding::Level;

std::string fmt(const char* f, double a, double b = 0, double c = 0) {
  return doctor_format(f, a, b, c);
}

void add(DoctorReport& r, Level level, std::string text) {
  r.findings.push_back({level, std::move(text)});
}

struct Rtt {
  std::vector<double> ms;
  std::string describe() const {
    if (ms.empty()) return "no round trip";
    std::vector<double> s = ms;
    std::sort(s.begin(), s.end());
    return fmt("round trip min %.2f ms, median %.2f ms, max %.2f ms", s.front(), s[s.size() / 2],
               s.back());
  }
  double median() const {
    std::vector<double> s = ms;
    std::sort(s.begin(), s.end());
    return s.empty() ? 0.0 : s[s.size() / 2];
  }
};

}  // namespace

std::string doctor_format(const char* format, double a, double b, double c) {
  char buf[256];
  std::snprintf(buf, sizeof buf, format, a, b, c);
  return buf;
}

std::string round_trip_text(std::vector<double>& ms) {
  std::sort(ms.begin(), ms.end());
  return doctor_format("round trip median %.2f ms, max %.2f ms", ms[ms.size() / 2], ms.back());
}

void check_hard_range(DoctorReport& r, const std::string& who, const ActuatorModel& a, double at,
                      const std::string& check) {
  if (at >= a.limits.position_min && at <= a.limits.position_max) return;
  r.findings.push_back({DoctorFinding::Level::kWarning,
                        who +
                            doctor_format(": at %.1f deg, outside the rig's hard range "
                                          "%.1f..%.1f deg",
                                          at * 180.0 / M_PI, a.limits.position_min * 180.0 / M_PI,
                                          a.limits.position_max * 180.0 / M_PI) +
                            " (moved by hand? check " + check + ")"});
}

bool DoctorReport::has_problems() const {
  return std::any_of(findings.begin(), findings.end(),
                     [](const DoctorFinding& f) { return f.level == Level::kProblem; });
}

std::string DoctorReport::to_text() const {
  std::string out = bus + "\n";
  for (const auto& f : findings) {
    out += f.level == Level::kOk ? "  ok   " : f.level == Level::kWarning ? "  WARN " : "  FAIL ";
    out += f.text + "\n";
  }
  return out;
}

std::optional<int> usb_serial_latency_timer_ms(const std::string& device,
                                               const std::string& sysfs) {
  const std::string tty = device.substr(device.rfind('/') + 1);
  std::ifstream in(sysfs + "/class/tty/" + tty + "/device/latency_timer");
  int ms = 0;
  if (!(in >> ms)) return std::nullopt;
  return ms;
}

DoctorFinding usb_latency_finding(const std::string& device) {
  const auto lt = usb_serial_latency_timer_ms(device);
  if (!lt) return {Level::kOk, device + " is not a USB serial adapter with a latency timer"};
  if (*lt > 1) {
    return {Level::kWarning,
            fmt("USB serial latency timer %.0f ms adds up to that to every reply; set it to 1: "
                "echo 1 > /sys/class/tty/",
                *lt) +
                device.substr(device.rfind('/') + 1) + "/device/latency_timer"};
  }
  return {Level::kOk, fmt("USB serial latency timer %.0f ms", *lt)};
}

DoctorReport diagnose_modbus(const std::string& bus, const ModbusEndpoint& ep,
                             const std::vector<ActuatorModel>& actuators,
                             const ModbusTiming& timing, int samples,
                             const modbus_map::Addresses& registers) {
  DoctorReport r;
  r.bus = bus + (ep.tcp ? " (Modbus TCP " + ep.host + ":" + std::to_string(ep.port) + ")"
                        : " (Modbus RTU " + ep.device + " " + std::to_string(ep.baud) + " baud)");
  if (timing.response_timeout_s >= 0.5) {
    add(r, Level::kWarning,
        fmt("response timeout %.0f ms: libmodbus's 500 ms default or longer hides a dead board "
            "for that long per transaction",
            timing.response_timeout_s * 1000));
  } else {
    add(r, Level::kOk,
        fmt("response timeout %.0f ms, byte timeout %.3g ms, %.0f retries",
            timing.response_timeout_s * 1000, timing.byte_timeout_s * 1000, timing.max_retries));
  }
  if (!ep.tcp) {
    r.findings.push_back(usb_latency_finding(ep.device));
  }
  std::map<int, int> channels;  // unit -> channels used
  for (const auto& a : actuators) {
    const auto p = modbus_map::place(a.address);
    channels[p.unit] = std::max(channels[p.unit], p.channel + 1);
  }
  modbus_t* ctx = ep.tcp ? modbus_new_tcp(ep.host.c_str(), ep.port)
                         : modbus_new_rtu(ep.device.c_str(), ep.baud, 'N', 8, 1);
  // Before connecting: libmodbus's TCP connect waits the response timeout.
  if (ctx != nullptr) set_modbus_timeouts(ctx, timing);
  if (ctx == nullptr || modbus_connect(ctx) != 0) {
    add(r, Level::kProblem, std::string("cannot connect: ") + modbus_strerror(errno));
    if (ctx != nullptr) modbus_free(ctx);
    return r;
  }
  double cycle_ms = 0.0;
  for (const auto& [unit, used] : channels) {
    modbus_set_slave(ctx, unit);
    Rtt rtt;
    int failures = 0;
    std::string last_error;
    std::uint16_t in[modbus_map::kInputCount] = {};
    for (int i = 0; i < samples; ++i) {
      const std::int64_t t0 = monotonic_ns();
      if (modbus_read_input_registers(ctx, registers.status, modbus_map::kIrPosition0 + used, in) >
          0) {
        rtt.ms.push_back(static_cast<double>(monotonic_ns() - t0) * 1e-6);
      } else {
        ++failures;
        last_error = modbus_strerror(errno);
        modbus_flush(ctx);
      }
    }
    const std::string who = "board " + std::to_string(unit) + ": ";
    if (rtt.ms.empty()) {
      std::string text = who;
      text += "does not answer (";
      text += last_error;
      text += ")";
      add(r, Level::kProblem, std::move(text));
      continue;
    }
    cycle_ms += 2.0 * rtt.median();  // a write and a read per cycle
    add(r, failures == 0 ? Level::kOk : Level::kWarning,
        who + rtt.describe() + fmt(", %.0f of %.0f reads failed", failures, samples) +
            (failures > 0 ? " (" + last_error + ")" : ""));
    if (in[modbus_map::kIrChannels] < used) {
      add(r, Level::kProblem,
          who + fmt("has %.0f channels, the rig uses %.0f", in[modbus_map::kIrChannels], used));
    }
    if ((in[modbus_map::kIrStatus] & modbus_map::kStatusFault) != 0) {
      add(r, Level::kWarning,
          who + fmt("reports fault code %.0f (cleared on enable)", in[modbus_map::kIrFaultCode]));
    }
  }
  modbus_close(ctx);
  modbus_free(ctx);
  if (timing.cycle_period_s > 0 && cycle_ms > timing.cycle_period_s * 1000) {
    add(r, Level::kWarning,
        fmt("one I/O cycle takes about %.2f ms, longer than the %.2f ms period: targets reach "
            "the boards at that slower rate",
            cycle_ms, timing.cycle_period_s * 1000));
  } else {
    add(r, Level::kOk, fmt("one I/O cycle takes about %.2f ms", cycle_ms));
  }
  return r;
}

DoctorReport diagnose_can(const std::string& bus, CanTransport& transport,
                          const std::string& protocol, const std::vector<ActuatorModel>& actuators,
                          const CanBusOptions& options, double tick_hz, long bitrate,
                          double listen_s) {
  DoctorReport r;
  r.bus = bus + " (CAN, " + protocol + ", " + std::to_string(bitrate) + " bit/s)";
  std::vector<double> no_positions(actuators.size(), 0.0);
  CanBusBudget budget;
  std::set<int> expected;
  if (protocol == "cia402") {
    budget = Cia402Bus(bus, transport, actuators, no_positions, options).budget(tick_hz, bitrate);
    for (const auto& a : actuators) expected.insert(a.address);
  } else {
    const CustomCanBus probe(bus, transport, actuators, no_positions, options);
    budget = probe.budget(tick_hz, bitrate);
    const int per = custom_can::channels_per_frame(options.fd, options.width);
    for (const auto& a : actuators) expected.insert((a.address - 1) / per + 1);
  }
  add(r,
      budget.refused()  ? Level::kProblem
      : budget.warned() ? Level::kWarning
                        : Level::kOk,
      "load: " + budget.describe(bus));

  // CiA 402: one SDO upload of the device type per drive, timed.
  std::map<int, std::int64_t> asked;
  std::map<int, double> rtt_ms;
  std::map<int, std::uint32_t> device_type;
  std::set<int> heard;
  std::map<CanError, int> errors;
  CanFrame f;
  if (protocol == "cia402") {
    for (int node : expected) {
      cia402::encode_sdo_upload(node, 0x1000, 0, f);
      if (transport.send(f)) asked[node] = monotonic_ns();
    }
  }
  const std::int64_t end = monotonic_ns() + static_cast<std::int64_t>(listen_s * 1e9);
  while (monotonic_ns() < end) {
    CanError e = CanError::kNone;
    if (!transport.receive(f, e)) {
      std::this_thread::sleep_for(std::chrono::microseconds(200));
      continue;
    }
    if (e != CanError::kNone) {
      ++errors[e];
      continue;
    }
    if (protocol == "cia402") {
      if (const auto s = cia402::decode_sdo_reply(f);
          s && s->upload && asked.count(s->node) != 0 && rtt_ms.count(s->node) == 0) {
        rtt_ms[s->node] = static_cast<double>(monotonic_ns() - asked[s->node]) * 1e-6;
        device_type[s->node] = s->value;
      }
      if (const auto h = cia402::decode_heartbeat(f)) heard.insert(h->node);
    } else if (f.id > custom_can::kFeedbackBase && f.id <= custom_can::kFeedbackBase + 63) {
      heard.insert(static_cast<int>(f.id - custom_can::kFeedbackBase));
    }
  }
  for (int node : expected) {
    const std::string who = (protocol == "cia402" ? "drive " : "board ") + std::to_string(node);
    if (protocol == "cia402") {
      if (rtt_ms.count(node) != 0) {
        const bool ds402 = (device_type[node] & 0xFFFF) == 402;
        char type[16];
        std::snprintf(type, sizeof type, "0x%08X", static_cast<unsigned>(device_type[node]));
        add(r, ds402 ? Level::kOk : Level::kWarning,
            who + fmt(": SDO round trip %.2f ms", rtt_ms[node]) + ", device type " + type +
                (ds402 ? " (CiA 402)" : " (not a CiA 402 profile)") +
                (heard.count(node) != 0 ? ", heartbeat heard"
                                        : ", no heartbeat yet (set on enable)"));
      } else {
        add(r, Level::kProblem, who + ": no answer to an SDO read of 0x1000");
      }
    } else {
      add(r, heard.count(node) != 0 ? Level::kOk : Level::kProblem,
          who + (heard.count(node) != 0 ? ": heartbeat (feedback frames) heard"
                                        : ": not heard within the listening time"));
    }
  }
  for (const auto& [e, n] : errors) {
    const bool fatal = e == CanError::kBusOff || e == CanError::kErrorPassive ||
                       e == CanError::kNoAck || e == CanError::kProtocol;
    add(r, fatal ? Level::kProblem : Level::kWarning,
        std::string("error frames: ") + to_string(e) + " x" + std::to_string(n));
  }
  return r;
}

}  // namespace facectl
