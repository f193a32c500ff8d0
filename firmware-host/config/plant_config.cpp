#include "firmware-host/config/plant_config.hpp"

namespace facectl {
namespace {

// Thermal defaults (docs/CONFIG.md, "Plant"): the outer 5% of travel at each
// end is "at an extreme", where skin and end stops load a servo; 20 s there
// without a break, or the thermal state above its rating, trips it.
constexpr double kExtremeBandFraction = 0.05;
constexpr double kFullEffortFraction = 0.10;
constexpr double kExtremeBudget_s = 20.0;

}  // namespace

sim::ServoPlantParams parse_plant_config(const std::optional<ConfigNode>& plant,
                                         const ActuatorLimits& limits, const std::string& unit,
                                         double to_si) {
  sim::ServoPlantParams p;
  const double range = limits.position_max - limits.position_min;
  // The servo's own limits sit above the controller's, as a drive's do.
  p.max_velocity = 1.5 * limits.max_velocity;
  p.max_acceleration = 1.5 * limits.max_acceleration;
  sim::ThermalParams& t = p.thermal;
  t.position_min = limits.position_min;
  t.position_max = limits.position_max;
  t.extreme_band = kExtremeBandFraction * range;
  t.full_effort = kFullEffortFraction * range;
  t.extreme_budget_s = kExtremeBudget_s;
  if (!plant) return p;

  const std::string s = "_" + unit;
  const ConfigNode& n = *plant;
  n.expect_keys({"model", "time_constant_ms", "natural_frequency_hz", "damping_ratio", "latency_ms",
                 "noise" + s, "max_velocity" + s + "_s", "max_acceleration" + s + "_s2",
                 "deadband" + s, "backlash" + s, "extreme_band" + s, "extreme_budget_s",
                 "extreme_effort", "full_effort" + s, "thermal_time_constant_s", "rated_duty"});
  if (auto m = n.get("model")) {
    const std::string model = m->string();
    if (model == "pd") {
      p.model = sim::PlantModel::kPd;
    } else if (model != "first_order") {
      m->fail("first_order or pd");
    }
  }
  const bool pd = p.model == sim::PlantModel::kPd;
  // Each model's own keys only: a time constant on a PD servo would be ignored.
  for (const char* key : {"natural_frequency_hz", "damping_ratio"}) {
    if (!pd && n.has(key)) n[key].fail(std::string("no ") + key + " without model: pd");
  }
  if (pd && n.has("time_constant_ms")) {
    n["time_constant_ms"].fail(
        "no time_constant_ms with model: pd (natural_frequency_hz and "
        "damping_ratio set its response)");
  }
  if (auto v = n.get("time_constant_ms")) p.time_constant_s = v->non_negative() * 1e-3;
  // 100 Hz keeps the PD integration (0.5 ms steps) well inside its stable range.
  if (auto v = n.get("natural_frequency_hz")) p.natural_frequency_hz = v->number_in(0.1, 100.0);
  if (auto v = n.get("damping_ratio")) p.damping_ratio = v->number_in(0.0, 2.0);
  if (auto v = n.get("latency_ms")) p.latency_s = v->number_in(0.0, 50.0) * 1e-3;
  if (auto v = n.get("noise" + s)) p.noise_stddev = v->non_negative() * to_si;
  if (auto v = n.get("max_velocity" + s + "_s")) p.max_velocity = v->positive() * to_si;
  if (auto v = n.get("max_acceleration" + s + "_s2")) p.max_acceleration = v->positive() * to_si;
  const double tenth = 0.1 * range / to_si;  // play beyond a tenth of travel is a typo
  if (auto v = n.get("deadband" + s)) p.deadband = v->number_in(0.0, tenth) * to_si;
  if (auto v = n.get("backlash" + s)) p.backlash = v->number_in(0.0, tenth) * to_si;
  if (auto v = n.get("extreme_band" + s))
    t.extreme_band = v->number_in(0.0, 0.5 * range / to_si) * to_si;
  if (auto v = n.get("extreme_budget_s")) t.extreme_budget_s = v->non_negative();
  if (auto v = n.get("extreme_effort")) t.extreme_effort = v->number_in(0.0, 1.0);
  if (auto v = n.get("full_effort" + s)) t.full_effort = v->positive() * to_si;
  if (auto v = n.get("thermal_time_constant_s")) t.time_constant_s = v->number_in(0.1, 3600.0);
  if (auto v = n.get("rated_duty")) t.rated_duty = v->number_in(0.01, 1.0);
  return p;
}

}  // namespace facectl
