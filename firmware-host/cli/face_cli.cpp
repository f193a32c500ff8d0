#include "face_cli.hpp"

#include <cstdio>
#include <memory>
#include <string>

#include "clone_command.hpp"
#include "face_command_support.hpp"
#include "facectl/face/expression_library.hpp"
#include "facectl/face/expression_sheet.hpp"
#include "facectl/face/face_renderer.hpp"
#include "facectl/face/obj_io.hpp"
#include "fit_head_command.hpp"
#include "place_actuators_command.hpp"
#include "reduce_command.hpp"

namespace {

using namespace facectl::face;
using namespace facectl::face_cli;

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
  add_fit_head_command(face);
  add_place_actuators_command(face);
  // CLI11 binds options to storage that must outlive parsing.
  static FaceArgs args = default_face_args();
  static FaceArgs picture_args = [] {
    FaceArgs a = default_face_args();
    a.resolution = kLargestVariant;
    return a;
  }();
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
    guarded("render", [] {
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
    guarded("contact-sheet", [] {
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
    guarded("export-obj", [] {
      auto p = pose(args, obj_expression);
      TriMesh skin{p->data.skin_x, p->model.skin.tris};
      write_obj(obj_out, skin, 1.0);
      std::printf("wrote %s (%zu vertices, %zu triangles, metres)\n", obj_out.c_str(),
                  skin.v.size(), skin.tris.size());
    });
  });

  add_reduce_commands(face);
}
