#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <span>
#include <string>

#include "sim/plant/measurement_noise.hpp"
#include "sim/plant/servo_thermal.hpp"

namespace facectl::sim {

enum class PlantModel { kFirstOrder, kPd };

struct ServoPlantParams {
  std::string name = "servo";  // for the thermal fault text
  PlantModel model = PlantModel::kFirstOrder;
  double time_constant_s = 0.02;    // first_order: lag toward the (delayed) command
  double natural_frequency_hz = 8;  // pd: kp = ω², kd = 2ζω with ω = 2π·f
  double damping_ratio = 0.8;       // pd: ζ
  double max_velocity = 10.0;       // the servo's own slew limit, SI/s
  double max_acceleration = 0.0;    // SI/s², 0 = none
  double deadband = 0.0;            // no drive while |command − motor| <= deadband, SI
  double backlash = 0.0;            // total play between motor and output shaft, SI
  double latency_s = 0.002;         // transport + processing delay of a command
  double noise_stddev = 0.0;        // measurement noise, SI
  std::uint64_t seed = 1;           // deterministic noise
  ThermalParams thermal;            // off unless configured (full_effort > 0 or a band)
};

// A position servo: a delay line, then first-order or PD dynamics toward the
// command with speed and acceleration limits and a deadband, then gear play
// (backlash) to the output shaft, then measurement noise of the output. While
// disabled it holds its position (a braked or back-driven-free servo; the
// simulated boards model relax separately). A thermal/duty model watches the
// effort and the time held near the ends of travel and latches a fault, as a
// smart servo's overload protection does. Steps in fixed time without allocating.
class ServoPlant {
 public:
  explicit ServoPlant(const ServoPlantParams& params, double initial_position = 0.0);

  // `position` takes effect at now_ns + latency (the caller adds bus time to now_ns).
  // Inline: a simulated bus commands every servo every tick.
  void command(std::int64_t now_ns, double position) {
    if (delay_size_ == kDelaySlots) {
      // Full: the oldest pending command is overtaken by newer ones anyway.
      delay_head_ = (delay_head_ + 1) % kDelaySlots;
      --delay_size_;
    }
    delay_[(delay_head_ + delay_size_) % kDelaySlots] = {now_ns + latency_ns_, position};
    ++delay_size_;
  }
  // Enabling or disabling drops pending commands and holds the current
  // position, as a drive does (see ActuatorBus::set_enabled).
  void set_enabled(bool enabled);
  // Advances the plant to `now_ns`.
  void advance(std::int64_t now_ns);
  double measured();  // output position plus noise
  double position() const { return output_; }
  double motor_position() const { return motor_; }
  double velocity() const { return velocity_; }  // of the motor
  bool enabled() const { return enabled_; }

  const PlantStats& stats() const { return thermal_.stats(); }
  double temperature_c() const { return thermal_.temperature_c(); }
  double load() const { return thermal_.load(); }
  // An obstacle (skin, a jammed linkage): neither motor nor output passes
  // `stop` upward; +inf = none. The motor then pushes against it.
  void block_above(double stop) { block_above_ = stop; }
  // The latched overload fault ("thermal: <name> ..."), or nullptr. The text
  // lives as long as the plant.
  const char* fault() const { return thermal_.fault(); }
  // A servo reset: clears the latched fault (the thermal state stays).
  void clear_fault() { thermal_.clear_fault(); }

 private:
  // Commands waiting out their latency: 64 slots, so latency × command rate
  // must stay below 64 (checked when the rig is loaded).
  struct Timed {
    std::int64_t at_ns = 0;
    double value = 0.0;
  };
  static constexpr std::size_t kDelaySlots = 64;

  void set_dt(double dt);
  void step_first_order(double dt);
  void step_pd(double dt);
  double limit_velocity(double v_wanted, double dt) const;

  ServoPlantParams params_;
  // Worked out once from params_: the tick would otherwise redo them per servo.
  std::int64_t latency_ns_;  // latency_s in ns
  double half_backlash_;     // the play on either side of the motor
  std::array<Timed, kDelaySlots> delay_{};
  std::size_t delay_head_ = 0;
  std::size_t delay_size_ = 0;
  double active_command_;
  double motor_;
  double output_;
  double velocity_ = 0.0;
  double step_dt_ = -1.0;  // the dt gain_ (first order) or pd_steps_ was worked out for
  double gain_ = 0.0;
  int pd_steps_ = 1;   // PD sub-steps per advance of step_dt_
  double pd_h_ = 0.0;  // their length
  double kp_ = 0.0;    // ω²
  double kd_ = 0.0;    // 2ζω
  std::int64_t last_ns_ = -1;
  bool enabled_ = false;
  double block_above_ = std::numeric_limits<double>::infinity();
  MeasurementNoise noise_;
  ThermalModel thermal_;
};

// Advances each plant to `now_ns` and writes its measured position (as many as
// both spans hold); returns the first latched fault, or nullptr. The simulated
// buses call this every tick: one loop in servo_plant.cpp lets the per-servo
// steps inline into it.
const char* advance_and_measure(std::span<ServoPlant> plants, std::int64_t now_ns,
                                std::span<double> measured);

}  // namespace facectl::sim
