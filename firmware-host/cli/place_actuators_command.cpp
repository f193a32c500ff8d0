#include "place_actuators_command.hpp"

#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "face_command_support.hpp"
#include "facectl/face/actuator_placement.hpp"
#include "facectl/face/input_error.hpp"
#include "facectl/face/yaml_emit.hpp"
#include "placement_yaml.hpp"

namespace {

using namespace facectl::face;
using facectl::face_cli::guarded;
using facectl::face_cli::write_text_file;

struct PlaceArgs {
  int budget = 0;
  std::string head = facectl::face_cli::default_face_args().head;
  std::string library = facectl::face_cli::default_face_args().library;
  std::string out, report;
  std::vector<std::string> expressions;
  PlacementOptions o;
};

std::string placement_json(const PlaceArgs& a, const PlacementProblem& pr, const Placement& p,
                           double seconds) {
  using json = nlohmann::ordered_json;
  auto xyz = [](const Vec3& v) { return json::array({v.x(), v.y(), v.z()}); };
  json actuators = json::array();
  for (const PlacedActuator& x : p.actuators)
    actuators.push_back({{"vertex", x.vertex},
                         {"landmark", x.landmark},
                         {"nearest_control_point", x.nearest_control_point},
                         {"control_point_distance_mm", x.control_point_distance_mm},
                         {"position_mm", xyz(x.position_mm)},
                         {"axis", xyz(x.axis)},
                         {"travel_mm", {x.travel_min_mm, x.travel_max_mm}}});
  json expressions = json::object();
  for (const ExpressionFit& f : p.fits)
    expressions[f.name] = {{"rms_mm", f.rms_mm},
                           {"max_mm", f.max_mm},
                           {"rms_mm_no_actuators", f.rms0_mm},
                           {"max_mm_no_actuators", f.max0_mm},
                           {"worst_vertex", f.worst_vertex},
                           {"settled", f.settled}};
  const json j = {{"budget", a.budget},
                  {"seconds", seconds},
                  {"moving_vertices", pr.moving.size()},
                  {"candidates", pr.candidate_vertex.size()},
                  {"runs", pr.runs + static_cast<int>(p.actuators.size() + p.fits.size())},
                  {"unsettled_runs", pr.unsettled + p.unsettled},
                  {"actuators", actuators},
                  {"expressions", expressions}};
  return j.dump(2) + "\n";
}

void run(PlaceArgs& a) {
  const auto t0 = std::chrono::steady_clock::now();
  const HeadSpec spec = load_head_spec(a.head);
  const ExpressionLibrary lib = load_expression_library(a.library, spec);
  const FaceModel m = build_face_model(spec);  // the base mesh: fit-sized, fastest
  a.o.expressions = a.expressions;
  const auto say = [](const std::string& s) { std::fprintf(stderr, "  %s\n", s.c_str()); };
  const PlacementProblem pr = build_placement_problem(m, lib, a.o, say);
  if (pr.candidate_vertex.empty())
    throw std::invalid_argument("no skin vertex moves more than --threshold-mm " +
                                exact_number(a.o.moving_threshold_mm) + " in the expressions");
  const Placement p = place_actuators(m, pr, a.budget, say);
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const std::string yaml = facectl::placement_yaml(p, "facectl face place-actuators --budget " +
                                                          std::to_string(a.budget) + " --head " +
                                                          a.head + "\n--library " + a.library);
  if (a.out.empty())
    std::fputs(yaml.c_str(), stdout);
  else
    write_text_file(a.out, yaml);
  if (!a.report.empty()) write_text_file(a.report, placement_json(a, pr, p, secs));
  std::printf(
      "%zu actuators (budget %d) from %zu candidates on %zu moving vertices; %d full-model runs, "
      "%d unsettled; %.1f s\n",
      p.actuators.size(), a.budget, pr.candidate_vertex.size(), pr.moving.size(),
      pr.runs + static_cast<int>(p.actuators.size() + p.fits.size()), pr.unsettled + p.unsettled,
      secs);
  std::printf("%-16s %8s %8s %12s %12s\n", "expression", "rms_mm", "max_mm", "rms_mm_none",
              "max_mm_none");
  for (const ExpressionFit& f : p.fits)
    std::printf("%-16s %8.3f %8.3f %12.3f %12.3f%s\n", f.name.c_str(), f.rms_mm, f.max_mm,
                f.rms0_mm, f.max0_mm, f.settled ? "" : "  (unsettled)");
}

}  // namespace

void add_place_actuators_command(CLI::App* face) {
  static PlaceArgs a;  // CLI11 binds options to storage that must outlive parsing
  CLI::App* c = face->add_subcommand(
      "place-actuators",
      "propose N skin points and directions whose actuators best reproduce the library");
  c->add_option("--budget", a.budget, "number of actuators (1-DOF skin points)")
      ->required()
      ->check(CLI::Range(1, 1000));
  c->add_option("--head", a.head, "head folder (face.yaml, landmarks, muscles)")
      ->capture_default_str()
      ->check(CLI::ExistingDirectory);
  c->add_option("--library", a.library, "expression library YAML")->capture_default_str();
  c->add_option("--out", a.out, "write the actuators and errors here as YAML (default: stdout)");
  c->add_option("--report", a.report, "also write the result as JSON");
  c->add_option("--expressions", a.expressions, "only these expressions (default: all)")
      ->delimiter(',');
  c->add_option("--candidates", a.o.max_candidate_vertices, "candidate skin vertices")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000));
  c->add_option("--directions", a.o.directions, "principal directions tried per candidate")
      ->capture_default_str()
      ->check(CLI::Range(1, 3));
  c->add_option("--step-mm", a.o.step_mm, "pin displacement of a response run")
      ->capture_default_str()
      ->check(CLI::Range(0.01, 20.0));
  c->add_option("--threshold-mm", a.o.moving_threshold_mm,
                "a vertex counts as moving above this displacement")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 100.0));
  c->add_option("--frames", a.o.steady.max_frames, "frame cap of each steady-state run")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000000));
  c->add_option("--tolerance-mm", a.o.steady.tolerance_mm, "steady-state tolerance")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  c->callback([] { guarded("place-actuators", [] { run(a); }); });
}
