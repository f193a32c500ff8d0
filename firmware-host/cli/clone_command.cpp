#include "firmware-host/cli/clone_command.hpp"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>

#include "facectl/face/expression_library.hpp"
#include "facectl/face/input_error.hpp"
#include "facectl/face/motion_clone.hpp"
#include "firmware-host/cli/clone_head_ranges.hpp"
#include "firmware-host/cli/clone_report.hpp"
#include "firmware-host/cli/clone_yaml.hpp"
#include "firmware-host/cli/face_command_support.hpp"
#include "firmware-host/cli/viseme_poses.hpp"
#include "firmware-host/config/config_location.hpp"
#include "firmware-host/config/config_node.hpp"

namespace {

using namespace facectl::face;
using facectl::CloneReportRow;
using facectl::face_cli::write_text_file;

struct CloneArgs {
  std::string from, to, out, report;
  std::string library = facectl::face_cli::default_face_args().library;
  std::string visemes = facectl::shipped_dirs().config + "/fap/visemes.yaml";
  MotionCloneOptions options;
};

void print_row(const char* kind, const ClonedPose& c) {
  std::printf("%-10s %-16s %5d %4d %6d %8.3f %8.3f %8.2f %8.3f %8.3f %8.2f%s\n", kind,
              c.pose.name.c_str(), c.free_parameters, c.iterations, c.evaluations, c.copy.rms_mm,
              c.copy.max_mm, c.copy.percent, c.refined.rms_mm, c.refined.max_mm, c.refined.percent,
              c.settled ? "" : "  (unsettled)");
}

void run_clone(const CloneArgs& a) {
  const auto t0 = std::chrono::steady_clock::now();
  const HeadSpec from = load_head_spec(a.from), to = load_head_spec(a.to);
  // The base meshes: cloning runs the full model some ten times a pose.
  const FaceModel source = build_face_model(from), target = build_face_model(to);
  const CloneMap map = fit_clone_map(source, target);
  const ExpressionLibrary lib = load_expression_library(a.library, from);
  const std::vector<facectl::VisemePose> visemes = facectl::load_viseme_poses(a.visemes, from);
  MotionCloneOptions o = a.options;
  facectl::set_head_ranges(to, o);
  CloneWorkspace w = make_clone_workspace(source, target, map, o);

  std::printf("%-10s %-16s %5s %4s %6s %8s %8s %8s %8s %8s %8s\n", "kind", "pose", "free", "its",
              "runs", "copy_rms", "copy_max", "copy_%", "rms_mm", "max_mm", "eq6.1_%");
  std::vector<CloneReportRow> rows;
  std::vector<Expression> expressions, viseme_poses;
  int runs = 0;
  for (const Expression& e : lib.expressions) {
    rows.push_back({"expressions", clone_pose(source, target, map, e, o, w)});
    print_row("expression", rows.back().result);
    expressions.push_back(rows.back().result.pose);
    runs += rows.back().result.evaluations + 1;
  }
  for (const facectl::VisemePose& v : visemes) {
    rows.push_back({"visemes", clone_pose(source, target, map, v.pose, o, w)});
    print_row("viseme", rows.back().result);
    viseme_poses.push_back(rows.back().result.pose);
    runs += rows.back().result.evaluations + 1;
  }

  std::filesystem::create_directories(a.out);
  const std::string header = "Cloned by `facectl face clone` from " + a.from + " onto " + a.to +
                             " (docs/FACE_MODEL.md, \"Motion cloning\").\nSource: ";
  write_text_file(a.out + "/library.yaml",
                  facectl::library_yaml(expressions, to, lib.sequences, header + a.library));
  write_text_file(a.out + "/visemes.yaml",
                  facectl::visemes_yaml(visemes, viseme_poses, to, header + a.visemes));
  if (!a.report.empty()) write_text_file(a.report, facectl::clone_report_json(rows));
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("%zu poses, %d full-model runs of %d frames, %.1f s\n", rows.size(), runs, o.frames,
              s);
}

}  // namespace

void add_clone_command(CLI::App* face) {
  static CloneArgs args;
  CLI::App* c = face->add_subcommand(
      "clone", "carry a head's expression library and visemes over to another head");
  c->add_option("--from", args.from, "source head folder")->required();
  c->add_option("--to", args.to, "target head folder (same landmark and muscle names)")->required();
  c->add_option("--out", args.out, "output folder for library.yaml and visemes.yaml")->required();
  c->add_option("--library", args.library, "source expression library")->capture_default_str();
  c->add_option("--visemes", args.visemes, "source visemes")->capture_default_str();
  c->add_option("--report", args.report, "also write the errors as JSON");
  c->add_option("--frames", args.options.frames, "full-model frames from rest per run")
      ->capture_default_str()
      ->check(CLI::Range(20, 5000));
  c->add_option("--iterations", args.options.iterations,
                "Levenberg-Marquardt iterations per pose (0: plain copy)")
      ->capture_default_str()
      ->check(CLI::Range(0, 50));
  c->callback([] { facectl::face_cli::guarded("clone", [] { run_clone(args); }); });
}
