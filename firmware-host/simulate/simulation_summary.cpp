#include "firmware-host/simulate/simulation_summary.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>

#include "control/units.hpp"

namespace facectl {
namespace {

double r6(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return std::strtod(buf, nullptr);
}

SummaryJson tally(const Tally& t, double period) {
  return {{"count", t.count}, {"time_s", r6(static_cast<double>(t.ticks) * period)}};
}

// Limiters whose action means the show asked for something the rig must not
// do (rate limits only shape motion and are not problems).
bool is_problem_limit(int bit) {
  const auto f = static_cast<LimitFlags>(1u << bit);
  return f == kLimitPosition || f == kLimitBreach || f == kLimitInvalid || f == kLimitMapping;
}

}  // namespace

const char* limit_name(int bit) {
  static const char* const kNames[kLimitFlagCount] = {
      "position", "velocity", "acceleration", "jerk",         "approach",
      "breach",   "invalid",  "jerk_yielded", "coupled_step", "mapping"};
  return bit >= 0 && bit < kLimitFlagCount ? kNames[bit] : "?";
}

SummaryJson make_summary(const LoadedConfig& cfg, const SimulationInput& input,
                         const SimulationRun& run, const SimulationStats& stats,
                         const SimHardware& hardware) {
  const ControllerModel& m = cfg.built.model;
  const double period = 1.0 / m.rate_hz;
  SummaryJson problems = SummaryJson::array();
  SummaryJson s;
  s["input"] = {{"kind", input.kind()}, {"name", input.name()}, {"length_s", r6(input.duration())}};
  s["rig"] = cfg.rig.name;
  s["head"] = cfg.head.name;
  s["rate_hz"] = r6(m.rate_hz);
  s["enable_s"] = r6(run.enable_s);
  s["simulated_s"] = r6(run.show_s);
  s["ticks"] = run.ticks;
  if (!run.enabled) problems.push_back("the head did not reach RUNNING");
  if (stats.faulted()) problems.push_back("the head faulted (FAULT or ESTOP)");

  SummaryJson actuators = SummaryJson::array();
  for (std::size_t i = 0; i < m.actuators.size(); ++i) {
    const ActuatorModel& a = m.actuators[i];
    const SimulationStats::Actuator& st = stats.actuators()[i];
    const double scale = yaml_per_si(a.kind);
    SummaryJson limits = SummaryJson::object();
    for (int b = 0; b < kLimitFlagCount; ++b) {
      const Tally& t = st.limits.bits[static_cast<std::size_t>(b)];
      if (t.count == 0) continue;
      limits[limit_name(b)] = tally(t, period);
      if (is_problem_limit(b)) {
        problems.push_back(a.name + ": " + limit_name(b) + " limit engaged " +
                           std::to_string(t.count) + " time(s)");
      }
    }
    SummaryJson j = {{"name", a.name},
                     {"bus", a.bus},
                     {"unit", yaml_unit(a.kind)},
                     {"tracking_rms", r6(stats.rms(i) * scale)},
                     {"tracking_max", r6(st.max_abs * scale)},
                     {"tracking_max_at_s", r6(st.max_at_s)},
                     {"limits", limits}};
    const BusModel* bus = nullptr;
    for (const BusModel& b : m.buses) {
      if (i >= b.first && i < b.first + b.count) bus = &b;
    }
    const std::size_t bus_index = static_cast<std::size_t>(bus - m.buses.data());
    const sim::PlantStats& p = hardware.buses[bus_index]->plant(i - bus->first).stats();
    // The plant's clock runs from the head's start; report show time (null: never).
    const double over_at = p.over_budget_time_s - run.clock_at_show_start_s;
    j["plant"] = {{"thermal_peak", r6(p.thermal_peak)},
                  {"duty_peak", r6(p.duty_peak)},
                  {"time_at_extreme_s", r6(p.time_at_extreme_s)},
                  {"longest_at_extreme_s", r6(p.longest_at_extreme_s)},
                  {"over_budget", p.over_budget},
                  {"over_budget_at_s", p.over_budget ? SummaryJson(r6(over_at)) : SummaryJson()}};
    if (p.over_budget) problems.push_back(a.name + ": over its time-at-extreme budget");
    actuators.push_back(j);
  }
  s["actuators"] = actuators;

  auto constraints = [&](const CoupledConstraints& c, auto tally_of, const char* what) {
    SummaryJson list = SummaryJson::array();
    for (std::size_t k = 0; k < c.size(); ++k) {
      const Tally& t = tally_of(k);
      SummaryJson j = tally(t, period);
      j["name"] = c.constraint(k).name;
      list.push_back(j);
      if (t.count > 0) {
        problems.push_back(std::string(what) + " " + c.constraint(k).name + " projected " +
                           std::to_string(t.count) + " time(s)");
      }
    }
    return list;
  };
  s["face_constraints"] = constraints(
      m.face_constraints, [&](std::size_t k) -> const Tally& { return stats.face_constraint(k); },
      "face limit");
  s["actuator_constraints"] = constraints(
      m.actuator_constraints,
      [&](std::size_t k) -> const Tally& { return stats.actuator_constraint(k); },
      "actuator limit");
  s["envelope"] = tally(stats.envelope(), period);
  if (stats.envelope().count > 0) problems.push_back("the face envelope clamped the command");

  SummaryJson buses = SummaryJson::array();
  for (std::size_t b = 0; b < m.buses.size(); ++b) {
    SummaryJson j = {{"name", m.buses[b].name}, {"type", m.buses[b].type}};
    for (const BusBudgetResult& budget : cfg.budgets) {
      if (budget.bus == m.buses[b].name) j["budget_load"] = r6(budget.load);
    }
    const BusTiming& timing = hardware.buses[b]->timing();
    j["cycle_time_s"] = r6(timing.cycle_time_s);
    j["load"] = r6(timing.load);
    if (timing.load > 1.0) problems.push_back(m.buses[b].name + ": bus cycle longer than the tick");
    buses.push_back(j);
  }
  s["buses"] = buses;

  SummaryJson states = SummaryJson::array();
  for (const StateSpan& st : stats.states()) {
    states.push_back({{"state", std::string(to_string(st.state))},
                      {"start_s", r6(st.start_s)},
                      {"end_s", r6(st.end_s)}});
  }
  s["states"] = states;
  s["notes"] = input.notes();
  s["problems"] = problems;
  s["result"] = stats.faulted() || !run.enabled ? "faulted" : "ok";
  return s;
}

namespace {

// A number of the summary for the text table, "-" when it is null.
std::string cell(const SummaryJson& v) {
  if (v.is_null()) return "-";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v.get<double>());
  return buf;
}

}  // namespace

std::string summary_text(const SummaryJson& s) {
  std::string out;
  char line[512];
  auto add = [&](const char* fmt, auto... args) {
    std::snprintf(line, sizeof line, fmt, args...);
    out += line;
  };
  add("facectl simulate: %s %s on rig %s (head %s)\n",
      s["input"]["kind"].get<std::string>().c_str(), s["input"]["name"].get<std::string>().c_str(),
      s["rig"].get<std::string>().c_str(), s["head"].get<std::string>().c_str());
  add("simulated %.3f s (%llu ticks at %g Hz) after enabling in %.3f s: %s\n",
      s["simulated_s"].get<double>(), s["ticks"].get<unsigned long long>(),
      s["rate_hz"].get<double>(), s["enable_s"].get<double>(),
      s["result"].get<std::string>().c_str());
  add("\n%-24s %-5s %12s %12s %10s %10s  %s\n", "actuator", "unit", "track rms", "track max",
      "thermal", "duty", "limits (count / s)");
  for (const auto& a : s["actuators"]) {
    std::string limits;
    for (const auto& [name, t] : a["limits"].items()) {
      char buf[96];
      std::snprintf(buf, sizeof buf, "%s%s %llu/%g", limits.empty() ? "" : ", ", name.c_str(),
                    t["count"].get<unsigned long long>(), t["time_s"].get<double>());
      limits += buf;
    }
    add("%-24s %-5s %12.4g %12.4g %10s %10s  %s\n", a["name"].get<std::string>().c_str(),
        a["unit"].get<std::string>().c_str(), a["tracking_rms"].get<double>(),
        a["tracking_max"].get<double>(), cell(a["plant"]["thermal_peak"]).c_str(),
        cell(a["plant"]["duty_peak"]).c_str(), limits.empty() ? "-" : limits.c_str());
  }
  add("\n%-32s %8s %10s\n", "constraint", "count", "time (s)");
  for (const char* group : {"face_constraints", "actuator_constraints"}) {
    for (const auto& c : s[group]) {
      add("%-32s %8llu %10.4g\n", c["name"].get<std::string>().c_str(),
          c["count"].get<unsigned long long>(), c["time_s"].get<double>());
    }
  }
  add("%-32s %8llu %10.4g\n", "face envelope", s["envelope"]["count"].get<unsigned long long>(),
      s["envelope"]["time_s"].get<double>());
  add("\n%-16s %-12s %12s %12s %14s\n", "bus", "type", "budget load", "sim load", "cycle (s)");
  for (const auto& b : s["buses"]) {
    add("%-16s %-12s %12s %12s %14s\n", b["name"].get<std::string>().c_str(),
        b["type"].get<std::string>().c_str(), cell(b.value("budget_load", SummaryJson())).c_str(),
        cell(b["load"]).c_str(), cell(b["cycle_time_s"]).c_str());
  }
  for (const auto& n : s["notes"]) add("note: %s\n", n.get<std::string>().c_str());
  add("\n%zu problem(s)\n", s["problems"].size());
  for (const auto& p : s["problems"]) add("  PROBLEM %s\n", p.get<std::string>().c_str());
  return out;
}

}  // namespace facectl
