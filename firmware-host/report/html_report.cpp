#include "firmware-host/report/html_report.hpp"

#include <cstdio>

#include "firmware-host/report/markup_escape.hpp"

namespace facectl {
namespace {

std::string number(const SummaryJson& v) {
  if (v.is_null()) return "&ndash;";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v.get<double>());
  return buf;
}

const char* kStyle = R"(<style>
body { font-family: DejaVu Sans, Arial, sans-serif; margin: 24px; color: #111; }
table { border-collapse: collapse; margin: 8px 0 20px; }
th, td { border: 1px solid #ccc; padding: 3px 8px; text-align: right; }
th:first-child, td:first-child { text-align: left; }
tr.problem td { background: #fee2e2; }
.problems li { color: #b91c1c; font-weight: bold; }
.ok { color: #15803d; font-weight: bold; }
img.plot { display: block; width: 960px; max-width: 100%; margin-bottom: 12px; }
img.frame { width: 400px; margin: 2px; }
</style>
)";

}  // namespace

std::string html_report(const SummaryJson& s, const std::vector<std::string>& plots,
                        const std::vector<std::string>& frames) {
  std::string o = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  o += "<title>facectl simulate: " + escape_markup(s["input"]["name"].get<std::string>()) +
       "</title>\n";
  o += kStyle;
  o += "</head>\n<body>\n";
  o += "<h1>facectl simulate: " + escape_markup(s["input"]["kind"].get<std::string>()) + " " +
       escape_markup(s["input"]["name"].get<std::string>()) + "</h1>\n";
  o += "<p>Rig " + escape_markup(s["rig"].get<std::string>()) + ", head " +
       escape_markup(s["head"].get<std::string>()) + ": " + number(s["simulated_s"]) +
       " s simulated at " + number(s["rate_hz"]) + " Hz after enabling in " +
       number(s["enable_s"]) + " s. Files: <a href=\"telemetry.csv\">telemetry.csv</a>, " +
       "<a href=\"summary.json\">summary.json</a>, <a href=\"summary.txt\">summary.txt</a>.</p>\n";

  o += "<h2>Problems</h2>\n";
  if (s["problems"].empty()) {
    o += "<p class=\"ok\">None.</p>\n";
  } else {
    o += "<ul class=\"problems\">\n";
    for (const auto& p : s["problems"])
      o += "<li>" + escape_markup(p.get<std::string>()) + "</li>\n";
    o += "</ul>\n";
  }
  for (const auto& n : s["notes"])
    o += "<p>Note: " + escape_markup(n.get<std::string>()) + "</p>\n";

  o += "<h2>Actuators</h2>\n<table>\n<tr><th>actuator</th><th>bus</th><th>unit</th>"
       "<th>tracking RMS</th><th>tracking max</th><th>thermal peak</th><th>duty peak</th>"
       "<th>limits (count / s)</th></tr>\n";
  for (const auto& a : s["actuators"]) {
    std::string limits;
    for (const auto& [name, t] : a["limits"].items()) {
      limits += (limits.empty() ? "" : ", ") + escape_markup(name) + " " +
                std::to_string(t["count"].get<unsigned long long>()) + " / " + number(t["time_s"]);
    }
    const std::string name = a["name"].get<std::string>();
    bool problem = false;
    for (const auto& p : s["problems"])
      problem = problem || p.get<std::string>().rfind(name + ":", 0) == 0;
    o += std::string("<tr") + (problem ? " class=\"problem\"" : "") + "><td><a href=\"#" +
         escape_markup(name) + "\">" + escape_markup(name) + "</a></td><td>" +
         escape_markup(a["bus"].get<std::string>()) + "</td><td>" +
         escape_markup(a["unit"].get<std::string>()) + "</td><td>" + number(a["tracking_rms"]) +
         "</td><td>" + number(a["tracking_max"]) + "</td><td>" +
         number(a["plant"]["thermal_peak"]) + "</td><td>" + number(a["plant"]["duty_peak"]) +
         "</td><td>" + (limits.empty() ? "&ndash;" : limits) + "</td></tr>\n";
  }
  o += "</table>\n";

  o += "<h2>Coupled limits and envelope</h2>\n<table>\n<tr><th>constraint</th><th>count</th>"
       "<th>time (s)</th></tr>\n";
  auto row = [&](const std::string& name, const SummaryJson& t) {
    const bool hit = t["count"].get<unsigned long long>() > 0;
    o += std::string("<tr") + (hit ? " class=\"problem\"" : "") + "><td>" + escape_markup(name) +
         "</td><td>" + std::to_string(t["count"].get<unsigned long long>()) + "</td><td>" +
         number(t["time_s"]) + "</td></tr>\n";
  };
  for (const char* group : {"face_constraints", "actuator_constraints"}) {
    for (const auto& c : s[group]) row(c["name"].get<std::string>(), c);
  }
  row("face envelope", s["envelope"]);
  o += "</table>\n";

  o += "<h2>Buses</h2>\n<table>\n<tr><th>bus</th><th>type</th><th>budget load</th>"
       "<th>simulated load</th><th>cycle (s)</th></tr>\n";
  for (const auto& b : s["buses"]) {
    const bool over = !b["load"].is_null() && b["load"].get<double>() > 1.0;
    o += std::string("<tr") + (over ? " class=\"problem\"" : "") + "><td>" +
         escape_markup(b["name"].get<std::string>()) + "</td><td>" +
         escape_markup(b["type"].get<std::string>()) + "</td><td>" +
         (b.contains("budget_load") ? number(b["budget_load"]) : "&ndash;") + "</td><td>" +
         number(b["load"]) + "</td><td>" + number(b["cycle_time_s"]) + "</td></tr>\n";
  }
  o += "</table>\n";

  o += "<h2>Actuator plots</h2>\n";
  for (const std::string& p : plots) {
    const std::string name = p.substr(0, p.rfind('.'));
    o += "<h3 id=\"" + escape_markup(name) + "\">" + escape_markup(name) +
         "</h3>\n<img class=\"plot\" src=\"plots/" + escape_markup(p) + "\" alt=\"" +
         escape_markup(name) + "\">\n";
  }
  if (!frames.empty()) {
    // A long show has thousands of frames: the page shows at most kShown of
    // them, evenly spaced; every frame is in the frames folder.
    constexpr std::size_t kShown = 60;
    const std::size_t step = (frames.size() + kShown - 1) / kShown;
    o += "<h2>Face render</h2>\n<p>Left: the full face model for the command. Right: the face "
         "the simulated actuator positions give through the inverse of the mapping. " +
         std::to_string(frames.size()) + " frames in <a href=\"frames/\">frames/</a>" +
         (step > 1 ? ", every " + std::to_string(step) + "th shown" : std::string()) +
         ".</p>\n<div>\n";
    for (std::size_t k = 0; k < frames.size(); k += step) {
      o += "<img class=\"frame\" loading=\"lazy\" src=\"" + escape_markup(frames[k]) + "\" alt=\"" +
           escape_markup(frames[k]) + "\">\n";
    }
    o += "</div>\n";
  }
  o += "</body>\n</html>\n";
  return o;
}

}  // namespace facectl
