#include "firmware-host/simulate/actuator_plots.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "firmware-host/cli/plot_command.hpp"
#include "firmware-host/report/svg_plot.hpp"
#include "firmware-host/simulate/limit_flags_or.hpp"

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
  if (v < lo) {
    lo = v, t_lo = t;
  } else if (v > hi) {  // not both: lo <= hi
    hi = v, t_hi = t;
  }
}

ActuatorPlots::ActuatorPlots(const ControllerModel& model, double duration_s, int columns)
    : model_(model),
      duration_s_(std::max(duration_s, 1e-9)),
      columns_(static_cast<std::size_t>(std::max(columns, 1))),
      actuators_(model.actuators.size()),
      cells_(columns_ * actuators_),
      flags_(columns_),
      used_(columns_, false) {}

std::size_t ActuatorPlots::column_of(double t) const {
  const double u = std::clamp(t / duration_s_, 0.0, 1.0);
  return std::min(columns_ - 1, static_cast<std::size_t>(u * static_cast<double>(columns_)));
}

void ActuatorPlots::add(double t, const TelemetryRecord& r, std::span<const double> positions) {
  const std::size_t c = column_of(t);
  Cell* const row = cells_.data() + c * actuators_;
  if (!used_[c]) {
    for (std::size_t i = 0; i < actuators_; ++i) {
      row[i].command.start(t, r.command[i]);
      row[i].position.start(t, positions[i]);
    }
    used_[c] = true;
  } else {
    for (std::size_t i = 0; i < actuators_; ++i) {
      row[i].command.see(t, r.command[i]);
      row[i].position.see(t, positions[i]);
    }
  }
  or_limit_flags(flags_[c], r.limits);
}

std::vector<std::string> ActuatorPlots::write(const std::string& dir,
                                              const std::vector<StateSpan>& states) const {
  std::filesystem::create_directories(dir);
  std::vector<std::string> files;
  for (std::size_t i = 0; i < actuators_; ++i) {
    const ActuatorModel& a = model_.actuators[i];
    double scale = 1.0;
    std::string unit;
    Plot plot = actuator_plot_frame(a, scale, unit);
    auto points = [&](Column Cell::*series) {
      std::vector<std::pair<double, double>> p;
      for (std::size_t c = 0; c < columns_; ++c) {
        if (!used_[c]) continue;
        const Column& col = cells_[c * actuators_ + i].*series;
        const bool low_first = col.t_lo <= col.t_hi;
        p.emplace_back(low_first ? col.t_lo : col.t_hi, (low_first ? col.lo : col.hi) * scale);
        p.emplace_back(low_first ? col.t_hi : col.t_lo, (low_first ? col.hi : col.lo) * scale);
      }
      return p;
    };
    plot.series.push_back(series_of("simulated position", "#f59e0b", 1.4, points(&Cell::position)));
    plot.series.push_back(series_of("command", "#1d4ed8", 1.6, points(&Cell::command)));
    for (const StateSpan& s : states) {
      if (const char* color = state_color(to_string(s.state))) {
        plot.spans.push_back({std::string(to_string(s.state)), color, s.start_s, s.end_s});
      }
    }
    const double width = duration_s_ / static_cast<double>(columns_);
    for (std::size_t c = 0; c < columns_; ++c) {
      for (std::size_t row = 0; row < kLimitMarkRows.size(); ++row) {
        if ((flags_[c][i] & kLimitMarkRows[row].bit) != 0) {
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
