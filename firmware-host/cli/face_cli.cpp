#include "face_cli.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <memory>
#include <string>

#include "facectl/face/expression_library.hpp"
#include "facectl/face/expression_sheet.hpp"
#include "facectl/face/face_renderer.hpp"
#include "facectl/face/input_error.hpp"
#include "facectl/face/obj_io.hpp"
#include "facectl/face/reduced_model_fit.hpp"
#include "facectl/face/reduced_test_sets.hpp"
#include "firmware-host/cli/clone_command.hpp"
#include "firmware-host/config/config_location.hpp"

namespace {

using namespace facectl::face;

// Pictures default to the head's finest variant: at the base mesh's 468 vertices
// sadness, disgust and fear barely differ from neutral (issue #20).
constexpr int kLargestVariant = -1;

struct FaceArgs {
  std::string head = facectl::shipped_dirs().config + "/heads/default";
  std::string library = facectl::shipped_dirs().config + "/expressions/library.yaml";
  int frames = 300;
  int resolution = 0;
};

void add_common(CLI::App* c, FaceArgs& a) {
  c->add_option("--head", a.head, "head folder (face.yaml, landmarks, muscles)")
      ->capture_default_str();
  c->add_option("--library", a.library, "expression library YAML")->capture_default_str();
  c->add_option("--frames", a.frames, "full-model frames to steady state")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  auto* r = c->add_option("--resolution", a.resolution,
                          "skin vertex count: 0 = the base mesh, or more (edge splitting)")
                ->check(CLI::Range(0, 100000));
  if (a.resolution == kLargestVariant)
    r->default_str("the largest of face.yaml's variants");
  else
    r->capture_default_str();
}

// The model at the requested skin resolution; a count the base mesh cannot be refined to
// is an error rather than a silent fallback to the base mesh.
FaceModel build_model(const HeadSpec& spec, int resolution) {
  int n = resolution;
  if (n == kLargestVariant)
    n = spec.variants.empty() ? 0 : *std::max_element(spec.variants.begin(), spec.variants.end());
  FaceModel m = build_face_model(spec, static_cast<std::size_t>(n));
  if (n != 0 && m.skin.v.size() != static_cast<std::size_t>(n))
    throw std::invalid_argument("--resolution " + std::to_string(n) +
                                ": must be 0, or at least the base mesh's " +
                                std::to_string(m.skin.v.size()) + " vertices");
  return m;
}

// Runs `body`; unusable input becomes exit code 2 with the InputError's file:line message.
template <class F>
void guarded(F&& body) {
  try {
    body();
  } catch (const InputError& e) {
    std::fprintf(stderr, "facectl face: %s\n", e.what());
    throw CLI::RuntimeError(2);
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "facectl face: %s\n", e.what());
    throw CLI::RuntimeError(2);
  }
}

struct Posed {
  HeadSpec spec;
  ExpressionLibrary library;
  FaceModel model;
  FaceData data;
};

std::unique_ptr<Posed> pose(const FaceArgs& a, const std::string& expression) {
  auto p = std::make_unique<Posed>();
  p->spec = load_head_spec(a.head);
  p->library = load_expression_library(a.library, p->spec);
  const ExpressionLibrary& lib = p->library;
  const Expression* e = lib.find(expression);
  if (!e) {
    std::string names;
    for (const auto& x : lib.expressions) names += " " + x.name;
    throw InputError(a.library + ": expected an expression name, found '" + expression +
                     "'; known:" + names);
  }
  p->model = build_model(p->spec, a.resolution);
  p->data = make_face_data(p->model);
  simulate_expression(p->model, p->data, *e, a.frames);
  return p;
}

// Prints one line per named set; true when every set meets the targets.
bool print_set_errors(const std::vector<SetError>& errors, double rms_mm, double p99_mm) {
  bool ok = true;
  std::printf("%-20s %7s %9s %8s %8s %8s  %s\n", "set", "samples", "unsettled", "rms_mm", "p99_mm",
              "max_mm", "worst");
  for (const SetError& e : errors) {
    const bool pass = e.rms_mm <= rms_mm && e.p99_mm <= p99_mm;
    ok = ok && pass;
    std::printf("%-20s %7d %9d %8.3f %8.3f %8.3f  %s%s\n", e.name.c_str(), e.samples, e.unsettled,
                e.rms_mm, e.p99_mm, e.max_mm, e.worst.c_str(), pass ? "" : "  (over target)");
  }
  return ok;
}

void write_text_file(const std::string& path, const std::string& text) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) throw InputError(path + ": cannot open file for writing");
  const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
  if (std::fclose(f) != 0 || !ok) throw InputError(path + ": write failed");
}

View parse_view(const std::string& v) {
  if (v == "front") return View::kFront;
  if (v == "side") return View::kSide;
  return View::kThreeQuarter;
}

void add_picture_options(CLI::App* c, std::string& view, std::string& lighting,
                         double& heat_max_mm) {
  c->add_option("--view", view, "camera")
      ->check(CLI::IsMember({"front", "side", "three-quarter"}))
      ->capture_default_str();
  c->add_option("--lighting", lighting,
                "raking: a grazing key light that shades folds; frontal: flat and even")
      ->check(CLI::IsMember({"raking", "frontal"}))
      ->capture_default_str();
  c->add_option("--heat-max-mm", heat_max_mm,
                "displacement shown red in the heat map (fixed scale, mm)")
      ->check(CLI::Range(0.1, 1000.0))
      ->capture_default_str();
}

}  // namespace

void register_face_commands(CLI::App& app) {
  CLI::App* face =
      app.add_subcommand("face", "the anatomical face model: pictures, OBJ, reduced model");
  face->require_subcommand(1);
  add_clone_command(face);
  static FaceArgs args;  // CLI11 binds options to storage that must outlive parsing

  static FaceArgs picture_args{.resolution = kLargestVariant};
  static std::string expression = "neutral", out, view = "three-quarter", lighting = "raking";
  static bool muscles = false, heat_map = false;
  static int width = 480, height = 600;
  static double heat_max_mm = 10;
  CLI::App* render = face->add_subcommand("render", "render an expression to PNG (headless CPU)");
  add_common(render, picture_args);
  render->add_option("--expression", expression, "expression name from the library")->required();
  render->add_option("--out", out, "output PNG file")->required();
  add_picture_options(render, view, lighting, heat_max_mm);
  render->add_flag("--muscles", muscles, "draw the skull and muscles instead of the skin");
  render
      ->add_flag("--heat-map", heat_map,
                 "also draw the displacement from neutral beside it, labelled, with its scale")
      ->excludes("--muscles");
  render->add_option("--width", width)->capture_default_str()->check(CLI::Range(16, 4096));
  render->add_option("--height", height)->capture_default_str()->check(CLI::Range(16, 4096));
  render->callback([] {
    guarded([] {
      auto p = pose(picture_args, expression);
      const Lighting light = lighting == "frontal" ? Lighting::kFrontal : Lighting::kRaking;
      if (heat_map) {
        SheetOptions so;
        so.view = parse_view(view);
        so.lighting = light;
        so.tile_width = width;
        so.tile_height = height;
        so.heat_max_mm = heat_max_mm;
        so.frames = picture_args.frames;
        const Points neutral = neutral_skin(p->model, p->library, so.frames);
        write_png(out, with_colour_bar(expression_cell(p->model, p->data, neutral, expression, so),
                                       heat_max_mm));
      } else {
        write_png(
            out, render_face(p->model, p->data, {parse_view(view), width, height, muscles, light}));
      }
      std::printf("wrote %s (%s, %s view, %zu skin vertices)\n", out.c_str(), expression.c_str(),
                  view.c_str(), p->model.skin.v.size());
    });
  });

  static std::string sheet_out, sheet_view = "three-quarter", sheet_lighting = "raking";
  static SheetOptions sheet_options;
  CLI::App* sheet = face->add_subcommand(
      "contact-sheet",
      "render every expression of the library beside its displacement heat map into one PNG");
  add_common(sheet, picture_args);
  sheet->add_option("--out", sheet_out, "output PNG file")->required();
  add_picture_options(sheet, sheet_view, sheet_lighting, sheet_options.heat_max_mm);
  sheet->add_option("--columns", sheet_options.columns, "expressions (picture + heat map) a row")
      ->capture_default_str()
      ->check(CLI::Range(1, 20));
  sheet->add_option("--tile-width", sheet_options.tile_width, "pixels of each picture")
      ->capture_default_str()
      ->check(CLI::Range(120, 4096));
  sheet->add_option("--tile-height", sheet_options.tile_height, "pixels of each picture")
      ->capture_default_str()
      ->check(CLI::Range(120, 4096));
  sheet->callback([] {
    guarded([] {
      const HeadSpec spec = load_head_spec(picture_args.head);
      const ExpressionLibrary lib = load_expression_library(picture_args.library, spec);
      const FaceModel m = build_model(spec, picture_args.resolution);
      sheet_options.view = parse_view(sheet_view);
      sheet_options.lighting = sheet_lighting == "frontal" ? Lighting::kFrontal : Lighting::kRaking;
      sheet_options.frames = picture_args.frames;
      const Image img = expression_sheet(m, lib, sheet_options, [](const std::string& name) {
        std::printf("  %s\n", name.c_str());
      });
      write_png(sheet_out, img);
      std::printf("wrote %s (%zu expressions, row by row in library order, %zu skin vertices)\n",
                  sheet_out.c_str(), lib.expressions.size(), m.skin.v.size());
    });
  });

  static std::string obj_expression = "neutral", obj_out;
  CLI::App* obj = face->add_subcommand("export-obj",
                                       "write the deformed skin of an expression as OBJ (metres)");
  add_common(obj, args);
  obj->add_option("--expression", obj_expression, "expression name")->capture_default_str();
  obj->add_option("--out", obj_out, "output OBJ file")->required();
  obj->callback([] {
    guarded([] {
      auto p = pose(args, obj_expression);
      TriMesh skin{p->data.skin_x, p->model.skin.tris};
      write_obj(obj_out, skin, 1.0);
      std::printf("wrote %s (%zu vertices, %zu triangles, metres)\n", obj_out.c_str(),
                  skin.v.size(), skin.tris.size());
    });
  });

  static std::string reduced_out;
  static ReduceOptions ro;
  static double max_rms_mm = 0;
  CLI::App* reduce =
      face->add_subcommand("reduce", "fit the reduced real-time model to the full model");
  add_common(reduce, args);
  reduce->add_option("--out", reduced_out, "output file (default <head>/reduced_face.txt)");
  reduce->add_option("--samples", ro.train_samples, "training inputs")->capture_default_str();
  reduce->add_option("--test-samples", ro.test_samples, "held-out inputs")->capture_default_str();
  reduce->add_option("--seed", ro.seed)->capture_default_str();
  reduce->add_option("--check-rms-mm", max_rms_mm, "exit 1 if the held-out RMS error exceeds this");
  reduce
      ->add_option("--tolerance-mm", ro.steady.tolerance_mm,
                   "a sample is settled when no skin vertex moved more than this over the "
                   "last 20 frames (--frames caps the frames, default 2000)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  reduce->callback([reduce] {
    guarded([reduce] {
      const HeadSpec spec = load_head_spec(args.head);
      // The file does not record a resolution, and none has converged (docs/FACE_MODEL.md,
      // "Known issues"): the model is fitted on the base mesh, which is also the fastest.
      if (args.resolution != 0)
        throw std::invalid_argument("--resolution " + std::to_string(args.resolution) +
                                    ": the reduced model is fitted on the base mesh; "
                                    "check-reduced --resolution measures it against a finer one");
      const FaceModel m = build_face_model(spec);
      // Each sample runs to a steady state; --frames, if given, caps it.
      if (reduce->count("--frames") > 0) ro.steady.max_frames = args.frames;
      ReduceReport r;
      const auto t0 = std::chrono::steady_clock::now();
      const ReducedFaceModel red = build_reduced_model(m, ro, &r);
      const double secs =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      const std::string path = reduced_out.empty() ? args.head + "/reduced_face.txt" : reduced_out;
      save_reduced_model(red, path);
      std::printf(
          "wrote %s: %zu control points, %d features; train (%d) RMS %.3f mm; held-out (%d) RMS "
          "%.3f mm, median %.3f mm, 95th percentile %.3f mm, max %.3f mm; %d full-model runs "
          "unsettled (largest residual %.3f mm); %.1f s\n",
          path.c_str(), red.control_points.size(), red.feature_count(), r.train_samples,
          r.train_rms_mm, r.test_samples, r.test_rms_mm, r.test_median_mm, r.test_p95_mm,
          r.test_max_mm, r.unsettled_runs, r.worst_residual_mm, secs);
      // The same named sets as check-reduced, with its defaults.
      const ExpressionLibrary lib = load_expression_library(args.library, spec);
      print_set_errors(reduced_errors(m, red, reduced_test_sets(spec, lib, 200, 1), ro.steady), 0.5,
                       2.0);
      if (max_rms_mm > 0 && r.test_rms_mm > max_rms_mm) {
        std::fprintf(stderr, "facectl face reduce: held-out RMS %.3f mm exceeds %.3f mm\n",
                     r.test_rms_mm, max_rms_mm);
        throw CLI::RuntimeError(1);
      }
    });
  });

  static std::string check_json;
  static int check_samples = 200;
  static unsigned check_seed = 1;
  static double target_rms_mm = 0.5, target_p99_mm = 2.0;
  CLI::App* check = face->add_subcommand(
      "check-reduced", "the shipped reduced model's error against the full model, per test set");
  add_common(check, args);
  check->add_option("--samples", check_samples, "inputs in each random set")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  check->add_option("--seed", check_seed)->capture_default_str();
  check->add_option("--json", check_json, "also write the errors as JSON, keyed by set name");
  check->add_option("--rms-mm", target_rms_mm, "exit 1 if a set's RMS error exceeds this")
      ->capture_default_str();
  check->add_option("--p99-mm", target_p99_mm, "exit 1 if a set's 99th percentile exceeds this")
      ->capture_default_str();
  check->callback([check] {
    guarded([check] {
      const HeadSpec spec = load_head_spec(args.head);
      const ReducedFaceModel red = load_reduced_model(args.head + "/reduced_face.txt", spec);
      const FaceModel m =
          build_face_model(spec, static_cast<std::size_t>(std::max(0, args.resolution)));
      const ExpressionLibrary lib = load_expression_library(args.library, spec);
      // Each input runs to a steady state; --frames, if given, caps it.
      SteadyStateOptions steady;
      if (check->count("--frames") > 0) steady.max_frames = args.frames;
      const auto errors =
          reduced_errors(m, red, reduced_test_sets(spec, lib, check_samples, check_seed), steady);
      const bool ok = print_set_errors(errors, target_rms_mm, target_p99_mm);
      if (!check_json.empty()) write_text_file(check_json, set_errors_json(errors));
      if (!ok) {
        std::fprintf(stderr,
                     "facectl face check-reduced: a set is over %.3f mm RMS or %.3f mm at the "
                     "99th percentile\n",
                     target_rms_mm, target_p99_mm);
        throw CLI::RuntimeError(1);
      }
    });
  });
}
