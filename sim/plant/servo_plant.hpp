#pragma once

#include <array>
#include <cstdint>
#include <random>

namespace facectl::sim {

struct ServoPlantParams {
  double time_constant_s = 0.02;  // first-order response to the (delayed) command
  double max_velocity = 10.0;     // the servo's own slew limit, SI/s
  double latency_s = 0.002;       // transport + processing delay of a command
  double noise_stddev = 0.0;      // measurement noise, SI
  std::uint64_t seed = 1;         // deterministic noise
};

// A position servo: a delay line, then a first-order lag toward the command
// with a slew-rate limit, then measurement noise. While disabled it holds its
// position (a braked or back-driven-free servo; the simulated boards model
// relax separately). Steps in fixed time without allocating.
class ServoPlant {
 public:
  explicit ServoPlant(const ServoPlantParams& params, double initial_position = 0.0);

  void command(std::int64_t now_ns, double position);
  // Enabling or disabling drops pending commands and holds the current
  // position, as a drive does (see ActuatorBus::set_enabled).
  void set_enabled(bool enabled);
  // Advances the plant to `now_ns`.
  void advance(std::int64_t now_ns);
  double measured();  // true position plus noise
  double position() const { return position_; }
  bool enabled() const { return enabled_; }

 private:
  // Commands waiting out their latency: 64 slots, so latency × command rate
  // must stay below 64 (checked when the rig is loaded).
  struct Timed {
    std::int64_t at_ns = 0;
    double value = 0.0;
  };
  static constexpr std::size_t kDelaySlots = 64;

  ServoPlantParams params_;
  std::array<Timed, kDelaySlots> delay_{};
  std::size_t delay_head_ = 0;
  std::size_t delay_size_ = 0;
  double active_command_;
  double position_;
  std::int64_t last_ns_ = -1;
  bool enabled_ = false;
  std::mt19937_64 rng_;
  std::normal_distribution<double> noise_{0.0, 1.0};
};

}  // namespace facectl::sim
