#include "firmware-host/report/telemetry_csv.hpp"

#include <charconv>
#include <fstream>
#include <sstream>

#include "firmware-host/config/config_node.hpp"

namespace facectl {
namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  std::istringstream in(line);
  while (std::getline(in, cell, ',')) out.push_back(cell);
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

}  // namespace

int TelemetryTable::find(const std::string& name) const {
  for (std::size_t i = 0; i < columns.size(); ++i) {
    if (columns[i] == name) return static_cast<int>(i);
  }
  return -1;
}

std::vector<double> TelemetryTable::numbers(const std::string& name) const {
  const int c = find(name);
  if (c < 0) throw ConfigError(file + ":1: expected a column '" + name + "', found none");
  std::vector<double> out;
  out.reserve(rows.size());
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const std::string& cell = rows[r][static_cast<std::size_t>(c)];
    double v = 0.0;
    const auto [end, ec] = std::from_chars(cell.data(), cell.data() + cell.size(), v);
    if (ec != std::errc() || end != cell.data() + cell.size()) {
      throw ConfigError(file + ":" + std::to_string(r + 2) + ": column '" + name +
                        "': expected a number, found '" + cell + "'");
    }
    out.push_back(v);
  }
  return out;
}

TelemetryTable read_telemetry_csv(const std::string& path) {
  TelemetryTable t;
  t.file = path;
  std::ifstream in(path);
  if (!in) throw ConfigError(path + ": cannot open file (expected a telemetry CSV)");
  std::string line;
  if (!std::getline(in, line) || line.rfind("tick,", 0) != 0) {
    throw ConfigError(path + ":1: expected the telemetry header 'tick,time_s,...', found '" +
                      line.substr(0, 40) + "'");
  }
  t.columns = split(line);
  std::size_t n = 1;
  while (std::getline(in, line)) {
    ++n;
    auto cells = split(line);
    if (cells.size() != t.columns.size()) {
      throw ConfigError(path + ":" + std::to_string(n) + ": expected " +
                        std::to_string(t.columns.size()) + " columns, found " +
                        std::to_string(cells.size()) + " (a truncated or foreign file?)");
    }
    t.rows.push_back(std::move(cells));
  }
  return t;
}

}  // namespace facectl
