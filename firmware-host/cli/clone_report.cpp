#include "firmware-host/cli/clone_report.hpp"

#include <nlohmann/json.hpp>

namespace facectl {

std::string clone_report_json(const std::vector<CloneReportRow>& rows) {
  auto error = [](const face::CloneError& e) {
    return nlohmann::ordered_json{
        {"rms_mm", e.rms_mm}, {"max_mm", e.max_mm}, {"percent", e.percent}};
  };
  nlohmann::ordered_json j = {{"expressions", nlohmann::ordered_json::object()},
                              {"visemes", nlohmann::ordered_json::object()}};
  for (const CloneReportRow& r : rows) {
    const face::ClonedPose& c = r.result;
    j[r.kind][c.pose.name] = {{"copy", error(c.copy)},
                              {"refined", error(c.refined)},
                              {"free_parameters", c.free_parameters},
                              {"iterations", c.iterations},
                              {"evaluations", c.evaluations},
                              {"settled", c.settled}};
  }
  return j.dump(2) + "\n";
}

}  // namespace facectl
