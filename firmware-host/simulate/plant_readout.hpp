#pragma once

#include <cstddef>

#include "drivers/sim_actuator_bus.hpp"

namespace facectl {

// What the simulated plants and buses report for the summary: the plant
// models' thermal/duty statistics (ServoPlant::stats()) and each bus's timing
// model (SimActuatorBus::timing()). Read through `requires` so that a build
// whose plants have no such models reports `modelled = false` instead of
// inventing numbers.
struct PlantFigures {
  bool modelled = false;
  double time_at_extreme_s = 0.0;
  double longest_at_extreme_s = 0.0;
  double thermal_peak = 0.0;
  double duty_peak = 0.0;
  bool over_budget = false;
  double over_budget_time_s = 0.0;
};

struct BusFigures {
  bool modelled = false;
  double cycle_time_s = 0.0;
  double load = 0.0;  // fraction of the tick period the bus is busy
};

template <typename Plant>
PlantFigures plant_figures(const Plant& plant) {
  if constexpr (requires { plant.stats(); }) {
    const auto& s = plant.stats();
    return {true,          s.time_at_extreme_s, s.longest_at_extreme_s, s.thermal_peak,
            s.duty_peak,   s.over_budget,       s.over_budget_time_s};
  } else {
    return {};
  }
}

template <typename Bus>
BusFigures bus_figures(const Bus& bus) {
  if constexpr (requires { bus.timing(); }) {
    const auto& t = bus.timing();
    return {true, t.cycle_time_s, t.load};
  } else {
    return {};
  }
}

}  // namespace facectl
