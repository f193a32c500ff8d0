#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <string_view>

namespace facectl {

// The time of the tick that calls into the hardware (ros2_control's read/write(time, period)).
struct TickTime {
  std::int64_t now_ns = 0;  // CLOCK_MONOTONIC, or simulated time offline
  double dt_s = 0.0;        // measured duration since the previous tick
};

struct BusStatus {
  bool fault = false;
  // Static string naming the fault (e.g. "bus-off", "board 3 not answering").
  const char* reason = "";
  std::uint64_t frames_sent = 0;
  std::uint64_t errors = 0;
};

// Hardware seam for one actuator bus. The controller owns a contiguous slice of
// actuators per bus, in the rig's bus order. Every method is called from the
// real-time tick: it must not allocate, lock or block. Backends that need
// blocking I/O (Modbus) hand data to their own I/O thread.
// What a smart servo reports besides its position (docs/SAFETY.md,
// "Drive-level protection"). NaN: the bus does not report that value.
struct ActuatorHealth {
  static constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  double temperature_c = kNone;
  double load = kNone;       // signed fraction of the servo's maximum torque
  double current_a = kNone;  // signed motor current
  double voltage_v = kNone;  // supply voltage at the servo
  // The device's own hardware error bits (its protocol's), 0 = none; a
  // servo that sets one has switched its output off by itself.
  std::uint32_t hardware_error = 0;
};

class ActuatorBus {
 public:
  virtual ~ActuatorBus() = default;

  virtual std::string_view name() const = 0;
  // Latest measured positions (SI), one per actuator of this bus.
  virtual void read(const TickTime& time, std::span<double> positions) = 0;
  // Commanded positions (SI); only called while outputs are enabled.
  virtual void write(const TickTime& time, std::span<const double> positions) = 0;
  // Enables or disables the actuators' outputs (drive enable, torque on/off).
  // On enable a backend must hold each actuator where it is until the first
  // write (e.g. CiA 402: target := actual before "enable operation"), never
  // resume an older target: that is what makes enabling bumpless.
  virtual void set_enabled(bool enabled) = 0;
  // Per-actuator outputs (FAULT with per-actuator reactions, docs/SAFETY.md):
  // one flag per actuator of this bus, 0 = output off (torque off), else on;
  // the bus counts as enabled while any flag is set. All flags equal is the
  // same as set_enabled(flag). An actuator switched on is held where it is
  // until the next write, as on set_enabled(true). Called on state changes
  // only; must not allocate. Where the protocol enables a whole board, not
  // one channel, a board is on only while every actuator on it is, and the
  // backend clears the flags of the actuators it switched off that way: on
  // return, the flags say which outputs are on.
  virtual void set_actuators_enabled(std::span<std::uint8_t> enabled) = 0;
  virtual BusStatus status() const = 0;
  // Latest health per actuator of this bus; buses that report none leave
  // `health` as it is.
  virtual void read_health(std::span<ActuatorHealth> /*health*/) {}
};

// Hardware seam for the safety I/O: an e-stop input and a power-enable output.
class SafetyIo {
 public:
  virtual ~SafetyIo() = default;
  // True while the e-stop is pressed (already debounced).
  virtual bool estop_active() = 0;
  virtual void set_power_enable(bool on) = 0;
  // True if the I/O itself failed (e.g. the GPIO line vanished).
  virtual bool fault() const = 0;
};

}  // namespace facectl
