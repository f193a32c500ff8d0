#include "fit_head_command.hpp"

#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <system_error>

#include "face_command_support.hpp"
#include "facectl/face/bitmap_font.hpp"
#include "facectl/face/face_finder.hpp"
#include "facectl/face/face_renderer.hpp"
#include "facectl/face/head_fit.hpp"
#include "facectl/face/head_writer.hpp"
#include "facectl/face/input_error.hpp"
#include "facectl/face/obj_io.hpp"
#include "firmware-host/config/config_location.hpp"

namespace {

using namespace facectl::face;
using facectl::face_cli::write_text_file;

struct FitHeadArgs {
  std::string obj, out, report, picture, units = "cm";
  std::string from = facectl::shipped_dirs().config + "/heads/default";
};

// Below this vertex_area_ratio fit-head notes that the skin will settle slowly.
constexpr double kDenseSkinRatio = 0.1;

nlohmann::ordered_json json_report(const HeadFit& f, const FitHeadArgs& a,
                                   const std::optional<FoundFace>& found) {
  nlohmann::ordered_json landmarks = nlohmann::ordered_json::array();
  for (const PlacedLandmark& l : f.landmarks)
    landmarks.push_back({{"name", l.name},
                         {"bone", l.bone},
                         {"vertex", l.vertices[0]},
                         {"initial_mm", l.initial_mm},
                         {"snap_mm", l.snap_mm}});
  return {{"obj", a.obj},
          {"iterations", f.iterations},
          {"converged", f.converged},
          {"last_change_mm", f.last_change_mm},
          {"loose_vertices", f.loose_vertices},
          {"size_ratio", f.size_ratio},
          {"vertex_area_ratio", f.vertex_area_ratio},
          {"skin_stiffness",
           {{"stretch", f.spec.skin.stretch},
            {"bending", f.spec.skin.bending},
            {"area", f.spec.skin.area},
            {"anchor", f.spec.skin.anchor}}},
          {"found_face", found ? nlohmann::ordered_json{{"turn_degrees", found->turn_degrees},
                                                        {"cut", found->cut},
                                                        {"kept_vertices", found->kept_vertices},
                                                        {"head_vertices", found->head_vertices}}
                               : nlohmann::ordered_json(nullptr)},
          {"landmarks", landmarks},
          {"problems", f.problems}};
}

// The new head from the front, neutral, with every landmark marked and labelled.
void write_picture(const std::string& path, const FaceModel& m) {
  const FaceData d = make_face_data(m);
  const RenderOptions ro{View::kFront, 720, 900, false, Lighting::kFrontal};
  Image img = render_face(m, d, ro);
  for (std::size_t l = 0; l < m.landmark_names.size(); ++l) {
    const Eigen::Vector2d p =
        project_to_image(m, ro, landmark_position(m, d.skin_x, static_cast<int>(l)));
    const bool bone = m.landmark_offset[l].norm() > 0;
    const std::array<std::uint8_t, 3> c =
        bone ? std::array<std::uint8_t, 3>{30, 60, 220} : std::array<std::uint8_t, 3>{220, 20, 20};
    const int x = static_cast<int>(p.x()), y = static_cast<int>(p.y());
    for (int dy = -2; dy <= 2; ++dy)
      for (int dx = -2; dx <= 2; ++dx) {
        const int px = x + dx, py = y + dy;
        if (px < 0 || py < 0 || px >= img.width || py >= img.height) continue;
        for (int k = 0; k < 3; ++k) img.rgb[3 * (py * img.width + px) + k] = c[k];
      }
    std::string name = m.landmark_names[l];
    if (name.starts_with("fdp_")) name = name.substr(4);
    draw_text(img, x + 4, y - 3, name, 1, c);
  }
  write_png(path, img);
}

int run(const FitHeadArgs& a) {
  // The folder is written before it is checked: never over the head it is fitted from.
  std::error_code ec;
  if (std::filesystem::equivalent(a.out, a.from, ec))
    throw std::invalid_argument("--out " + a.out +
                                " is the --from head folder; refusing to "
                                "overwrite its skin, landmarks and muscles");
  const HeadSpec source = load_head_spec(a.from);
  const TriMesh source_skin = read_obj(source.skin_file, source.skin_scale);
  TriMesh target = read_obj(a.obj, metres_per_unit(a.units));
  check_mesh_basics(target, a.obj);
  // A whole head, or a face looking another way about y: find the face, turn and cut it.
  std::optional<FoundFace> found;
  try {
    check_face_region(target, a.obj);
  } catch (const InputError& e) {
    try {
      found = find_face(target, source_skin, a.obj);
      check_face_region(found->mesh, a.obj + " (the face found on it)");
    } catch (const InputError& f) {
      throw InputError(std::string(e.what()) + "; finding the face on it failed: " + f.what());
    }
    std::printf(
        "%s is not a face looking along +z (%s); found the face on it: turned %.1f "
        "degrees about y%s, %zu of %zu vertices kept\n",
        a.obj.c_str(), e.what(), found->turn_degrees,
        found->cut ? " and cut to the region the --from face covers" : "", found->kept_vertices,
        found->head_vertices);
    target = found->mesh;
  }
  HeadFit f = fit_head(source, source_skin, target, HeadFitOptions{});
  // The alignment is scale-free, so a mesh read in the wrong unit still fits; only the
  // size says so (and every size in face.yaml would be scaled with it).
  if (f.size_ratio < 0.5 || f.size_ratio > 2.0)
    f.problems.push_back("the head is " + std::to_string(f.size_ratio) +
                         " times the size of the --from head: is --units " + a.units +
                         " the unit of its vertices?");

  std::printf(
      "fit %s (%zu vertices, %zu triangles) to %s: %d iterations, %d refinement pairs, last move "
      "%.3f mm, size ratio %.3f\n",
      a.obj.c_str(), target.v.size(), target.tris.size(), a.from.c_str(), f.iterations,
      f.refined_pairs, f.last_change_mm, f.size_ratio);
  std::printf(
      "skin area per vertex for its size %.3f times the --from head's: skin stiffness stretch "
      "%.4g, bending %.4g, area %.4g, anchor %.4g (docs/FACE_MODEL.md, \"Skin stiffness per "
      "unit area\")\n",
      f.vertex_area_ratio, f.spec.skin.stretch, f.spec.skin.bending, f.spec.skin.area,
      f.spec.skin.anchor);
  // Small stiffnesses converge slowly: a 20000-vertex copy of the default (ratio 0.023) had
  // not settled joy after 3000 frames.
  if (f.vertex_area_ratio < kDenseSkinRatio)
    std::printf(
        "note: %.0f times the --from head's vertices for its size; its skin settles slowly "
        "(more frames for `face reduce`, `render` and `clone`); a coarser mesh settles "
        "sooner\n",
        1.0 / f.vertex_area_ratio);
  if (f.converged)
    std::printf("converged: the correspondences stopped moving\n");
  else
    std::printf(
        "not converged: stopped at the round limit (%d) with a last move of %.3f mm and %d pairs "
        "added in the last round\n",
        f.iterations, f.last_change_mm, f.last_added_pairs);
  if (!f.loose_vertices.empty())
    std::printf(
        "note: %zu vertices used by no face (the first is vertex %d of the OBJ) are left out of "
        "the fit; they stay in skin.obj\n",
        f.loose_vertices.size(), f.loose_vertices.front() + 1);
  for (const std::string& n : f.opening_notes) std::printf("opening %s\n", n.c_str());
  std::printf("%-10s %5s %7s %10s %8s\n", "landmark", "bone", "vertex", "initial_mm", "snap_mm");
  for (const PlacedLandmark& l : f.landmarks)
    std::printf("%-10s %5s %7d %10.2f %8.2f\n", l.name.c_str(), l.bone ? "yes" : "", l.vertices[0],
                l.initial_mm, l.snap_mm);

  // The found face replaces the copy of the input: the folder's skin is what was fitted. It
  // is written into the folder first and renamed over the copy last (one atomic step), so
  // no failure leaves landmarks beside a skin they do not index.
  const std::filesystem::path found_skin = std::filesystem::path(a.out) / "skin.found.obj";
  if (found) {
    std::filesystem::create_directories(a.out);
    write_obj(found_skin.string(), target, metres_per_unit(a.units));
  }
  write_head_folder(
      a.out, f.spec,
      {a.obj, a.units, a.from,
       "Head fitted by `facectl face fit-head --obj " + a.obj + " --from " + a.from + "`"});
  if (found) {
    std::filesystem::rename(found_skin, std::filesystem::path(a.out) / "skin.obj");
    std::printf("skin.obj is the face found on %s (turned %.1f degrees about y%s)\n", a.obj.c_str(),
                found->turn_degrees, found->cut ? ", cut" : "");
  }
  std::printf(
      "wrote %s (skin.obj, face.yaml, landmarks.yaml, muscles.yaml, head.yaml); "
      "`facectl face reduce --head %s` fits its reduced model\n",
      a.out.c_str(), a.out.c_str());
  if (!a.report.empty()) write_text_file(a.report, json_report(f, a, found).dump(2) + "\n");
  if (!f.problems.empty()) {
    for (const std::string& p : f.problems)
      std::fprintf(stderr, "facectl face fit-head: %s: %s\n", a.obj.c_str(), p.c_str());
    return 2;
  }
  // The folder must build as it will for render and reduce (e.g. an eye contour that
  // encloses vertices of a closed mesh leaves no eye opening).
  FaceModel m;
  try {
    m = build_face_model(load_head_spec(a.out));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "facectl face fit-head: %s: the written head does not build: %s\n",
                 a.out.c_str(), e.what());
    for (const std::string& n : f.opening_notes)
      if (n.find("joined along edges") != std::string::npos)
        std::fprintf(stderr,
                     "facectl face fit-head: %s: opening %s; the model opens it only when no "
                     "vertex lies inside the contour: cut the mouth and eye holes in the mesh\n",
                     a.obj.c_str(), n.c_str());
    return 2;
  }
  std::printf("%s builds: %zu skin vertices, %zu muscles\n", a.out.c_str(), m.skin.v.size(),
              m.muscles.size());
  if (!a.picture.empty()) {
    write_picture(a.picture, m);
    std::printf("wrote %s (landmarks: red on the skin, blue bone points)\n", a.picture.c_str());
  }
  return 0;
}

}  // namespace

void add_fit_head_command(CLI::App* face) {
  static FitHeadArgs a;
  CLI::App* c = face->add_subcommand(
      "fit-head", "place the landmarks and muscle map on a new head mesh; write a head folder");
  c->add_option("--obj", a.obj,
                "the new skin: OBJ, y up, neutral face; a face looking along +z, or a whole "
                "head whose face is then found")
      ->required();
  c->add_option("--out", a.out, "head folder to write")->required();
  c->add_option("--from", a.from, "head folder whose landmarks and muscles are carried over")
      ->capture_default_str();
  c->add_option("--units", a.units, "the OBJ's length unit")
      ->check(CLI::IsMember({"m", "cm", "mm"}))
      ->capture_default_str();
  c->add_option("--report", a.report, "also write the per-landmark report as JSON");
  c->add_option("--picture", a.picture, "PNG of the new head with the landmarks marked");
  c->callback([] {
    facectl::face_cli::guarded("fit-head", [] {
      if (const int rc = run(a); rc != 0) throw CLI::RuntimeError(rc);
    });
  });
}
