#include "firmware-host/simulate/actuator_plots.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "firmware-host/plot_command.hpp"
#include "firmware-host/svg_plot.hpp"

namespace facectl {
namespace {

// A column's extremes as points in time order.
Plot::Series series_of(const std::string& label, const char* color, double width,
                       const std::vector<std::pair<double, double>>& points) {
  Plot::Series s{label, color, {}, {}, width};
  for (const auto& [t, v] : points) {
    s.x.push_back(t);
    s.y.push_back(v);
  }
  return s;
}

}  // namespace

void ActuatorPlots::Column::see(double t, double v) {
  if (!used || v < lo) lo = v, t_lo = t;
  if (!used || v > hi) hi = v, t_hi = t;
  used = true;
}

ActuatorPlots::ActuatorPlots(const ControllerModel& model, double duration_s, int columns)
    : model_(model), duration_s_(std::max(duration_s, 1e-9)) {
  const auto n = static_cast<std::size_t>(std::max(columns, 1));
  tracks_.assign(model.actuators.size(), Track{std::vector<Column>(n), std::vector<Column>(n),
                                               std::vector<LimitFlags>(n, 0)});
}

std::size_t ActuatorPlots::column_of(double t) const {
  const std::size_t n = tracks_.empty() ? 1 : tracks_[0].command.size();
  const double u = std::clamp(t / duration_s_, 0.0, 1.0);
  return std::min(n - 1, static_cast<std::size_t>(u * static_cast<double>(n)));
}

void ActuatorPlots::add(double t, const TelemetryRecord& r, std::span<const double> positions) {
  const std::size_t c = column_of(t);
  for (std::size_t i = 0; i < tracks_.size(); ++i) {
    tracks_[i].command[c].see(t, r.command[i]);
    tracks_[i].position[c].see(t, positions[i]);
    tracks_[i].flags[c] |= r.limits[i];
  }
}

std::vector<std::string> ActuatorPlots::write(const std::string& dir,
                                              const std::vector<StateSpan>& states) const {
  std::filesystem::create_directories(dir);
  std::vector<std::string> files;
  for (std::size_t i = 0; i < tracks_.size(); ++i) {
    const ActuatorModel& a = model_.actuators[i];
    const Track& track = tracks_[i];
    double scale = 1.0;
    std::string unit;
    Plot plot = actuator_plot_frame(a, scale, unit);
    auto points = [&](const std::vector<Column>& columns) {
      std::vector<std::pair<double, double>> p;
      for (const Column& c : columns) {
        if (!c.used) continue;
        const bool low_first = c.t_lo <= c.t_hi;
        p.emplace_back(low_first ? c.t_lo : c.t_hi, (low_first ? c.lo : c.hi) * scale);
        p.emplace_back(low_first ? c.t_hi : c.t_lo, (low_first ? c.hi : c.lo) * scale);
      }
      return p;
    };
    plot.series.push_back(series_of("simulated position", "#f59e0b", 1.4, points(track.position)));
    plot.series.push_back(series_of("command", "#1d4ed8", 1.6, points(track.command)));
    for (const StateSpan& s : states) {
      if (const char* color = state_color(to_string(s.state))) {
        plot.spans.push_back({std::string(to_string(s.state)), color, s.start_s, s.end_s});
      }
    }
    const double width = duration_s_ / static_cast<double>(track.flags.size());
    for (std::size_t c = 0; c < track.flags.size(); ++c) {
      for (std::size_t row = 0; row < kLimitMarkRows.size(); ++row) {
        if ((track.flags[c] & kLimitMarkRows[row].bit) != 0) {
          plot.marks.push_back({kLimitMarkRows[row].color, (static_cast<double>(c) + 0.5) * width,
                                static_cast<int>(row)});
        }
      }
    }
    const std::string name = a.name + ".svg";
    std::ofstream out(dir + "/" + name);
    out << render_svg(plot);
    if (!out) throw std::runtime_error(dir + "/" + name + ": cannot write");
    files.push_back(name);
  }
  return files;
}

}  // namespace facectl
