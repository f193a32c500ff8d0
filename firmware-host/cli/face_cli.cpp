#include "face_cli.hpp"

#include <chrono>
#include <cstdio>
#include <exception>
#include <memory>
#include <string>

#include "facectl/face/expression_library.hpp"
#include "facectl/face/face_renderer.hpp"
#include "facectl/face/input_error.hpp"
#include "facectl/face/obj_io.hpp"
#include "facectl/face/reduced_model_fit.hpp"
#include "firmware-host/config/config_location.hpp"

namespace {

using namespace facectl::face;

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
  c->add_option("--resolution", a.resolution, "skin vertex count (0 = the base mesh)")
      ->capture_default_str();
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
  FaceModel model;
  FaceData data;
};

std::unique_ptr<Posed> pose(const FaceArgs& a, const std::string& expression) {
  auto p = std::make_unique<Posed>();
  p->spec = load_head_spec(a.head);
  const ExpressionLibrary lib = load_expression_library(a.library, p->spec);
  const Expression* e = lib.find(expression);
  if (!e) {
    std::string names;
    for (const auto& x : lib.expressions) names += " " + x.name;
    throw InputError(a.library + ": expected an expression name, found '" + expression +
                     "'; known:" + names);
  }
  p->model = build_face_model(p->spec, static_cast<std::size_t>(std::max(0, a.resolution)));
  p->data = make_face_data(p->model);
  simulate_expression(p->model, p->data, *e, a.frames);
  return p;
}

View parse_view(const std::string& v) {
  if (v == "front") return View::kFront;
  if (v == "side") return View::kSide;
  return View::kThreeQuarter;
}

}  // namespace

void register_face_commands(CLI::App& app) {
  CLI::App* face =
      app.add_subcommand("face", "the anatomical face model: pictures, OBJ, reduced model");
  face->require_subcommand(1);
  static FaceArgs args;  // CLI11 binds options to storage that must outlive parsing

  static std::string expression = "neutral", out, view = "front";
  static bool muscles = false;
  static int width = 480, height = 600;
  CLI::App* render = face->add_subcommand("render", "render an expression to PNG (headless CPU)");
  add_common(render, args);
  render->add_option("--expression", expression, "expression name from the library")->required();
  render->add_option("--out", out, "output PNG file")->required();
  render->add_option("--view", view, "camera")
      ->check(CLI::IsMember({"front", "side", "three-quarter"}))
      ->capture_default_str();
  render->add_flag("--muscles", muscles, "draw the skull and muscles instead of the skin");
  render->add_option("--width", width)->capture_default_str()->check(CLI::Range(16, 4096));
  render->add_option("--height", height)->capture_default_str()->check(CLI::Range(16, 4096));
  render->callback([] {
    guarded([] {
      auto p = pose(args, expression);
      RenderOptions o{parse_view(view), width, height, muscles};
      write_png(out, render_face(p->model, p->data, o));
      std::printf("wrote %s (%s, %s view)\n", out.c_str(), expression.c_str(), view.c_str());
    });
  });

  static std::string sheet_out;
  static int columns = 5;
  CLI::App* sheet =
      face->add_subcommand("contact-sheet", "render every expression of the library into one PNG");
  add_common(sheet, args);
  sheet->add_option("--out", sheet_out, "output PNG file")->required();
  sheet->add_option("--columns", columns)->capture_default_str()->check(CLI::Range(1, 20));
  sheet->callback([] {
    guarded([] {
      const HeadSpec spec = load_head_spec(args.head);
      const ExpressionLibrary lib = load_expression_library(args.library, spec);
      const FaceModel m =
          build_face_model(spec, static_cast<std::size_t>(std::max(0, args.resolution)));
      FaceData d = make_face_data(m);
      std::vector<Image> tiles;
      for (const Expression& e : lib.expressions) {
        simulate_expression(m, d, e, args.frames);
        tiles.push_back(render_face(m, d, {View::kFront, 240, 300, false}));
        std::printf("  %s\n", e.name.c_str());
      }
      write_png(sheet_out, contact_sheet(tiles, columns, 6));
      std::printf("wrote %s (%zu expressions, row by row in library order)\n", sheet_out.c_str(),
                  tiles.size());
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
          "wrote %s: %zu control points, %d features; train RMS %.3f mm; held-out (%d) RMS %.3f "
          "mm, median %.3f mm, 95th percentile %.3f mm, max %.3f mm; %d full-model runs "
          "unsettled (largest residual %.3f mm); %.1f s\n",
          path.c_str(), red.control_points.size(), red.feature_count(), r.train_rms_mm,
          r.test_samples, r.test_rms_mm, r.test_median_mm, r.test_p95_mm, r.test_max_mm,
          r.unsettled_runs, r.worst_residual_mm, secs);
      if (max_rms_mm > 0 && r.test_rms_mm > max_rms_mm) {
        std::fprintf(stderr, "facectl face reduce: held-out RMS %.3f mm exceeds %.3f mm\n",
                     r.test_rms_mm, max_rms_mm);
        throw CLI::RuntimeError(1);
      }
    });
  });
}
