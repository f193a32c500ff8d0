#pragma once

#include <string>
#include <vector>

#include "firmware-host/simulate/simulation_summary.hpp"

namespace facectl {

// index.html of `facectl simulate`: one self-contained page with relative
// links only (the folder can be moved or served as is): the summary table with
// problems highlighted, every actuator plot, the render frames and links to
// telemetry.csv, summary.json and summary.txt.
std::string html_report(const SummaryJson& summary, const std::vector<std::string>& plots,
                        const std::vector<std::string>& frames);

}  // namespace facectl
