#include "facectl/face/expression_sheet.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "facectl/face/bitmap_font.hpp"
#include "facectl/face/heat_map.hpp"

namespace facectl::face {
namespace {

constexpr int kLabelScale = 2, kPairGap = 2, kCellGap = 14;

void check(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

}  // namespace

void validate(const SheetOptions& o) {
  check(o.tile_width >= 120 && o.tile_width <= 4096,
        "sheet: tile width " + std::to_string(o.tile_width) + " is outside 120..4096 pixels");
  check(o.tile_height >= 120 && o.tile_height <= 4096,
        "sheet: tile height " + std::to_string(o.tile_height) + " is outside 120..4096 pixels");
  check(o.columns >= 1 && o.columns <= 20,
        "sheet: columns " + std::to_string(o.columns) + " is outside 1..20");
  check(o.heat_max_mm > 0 && o.heat_max_mm <= 1000,
        "sheet: heat-map scale " + std::to_string(o.heat_max_mm) + " mm is outside (0, 1000]");
  check(o.frames >= 1, "sheet: frames must be at least 1, not " + std::to_string(o.frames));
}

Points neutral_skin(const FaceModel& m, const ExpressionLibrary& lib, int frames) {
  const Expression* e = lib.find("neutral");
  if (!e) return m.skin.v;
  FaceData d = make_face_data(m);
  simulate_expression(m, d, *e, frames);
  return d.skin_x;
}

Image expression_cell(const FaceModel& m, const FaceData& d, const Points& neutral,
                      const std::string& name, const SheetOptions& o) {
  validate(o);
  RenderOptions ro{o.view, o.tile_width, o.tile_height, false, o.lighting};
  const Image skin = render_face(m, d, ro);
  const std::vector<double> mm = displacement_mm(d.skin_x, neutral);
  ro.heat_mm = &mm;
  ro.heat_max_mm = o.heat_max_mm;
  const Image heat = render_face(m, d, ro);

  const int label_h = kLabelScale * (kGlyphHeight + 4);
  Image cell(2 * o.tile_width + kPairGap, label_h + o.tile_height, 255);
  draw_text(cell, 2, kLabelScale * 2, name, kLabelScale, {30, 30, 30});
  blit(cell, skin, 0, label_h);
  blit(cell, heat, o.tile_width + kPairGap, label_h);
  return cell;
}

Image with_colour_bar(const Image& picture, double heat_max_mm) {
  return stack_vertically(picture, colour_bar(std::clamp(picture.width, 120, 560), heat_max_mm), 6);
}

Image expression_sheet(const FaceModel& m, const ExpressionLibrary& lib, const SheetOptions& o,
                       const std::function<void(const std::string&)>& done) {
  validate(o);
  const Points neutral = neutral_skin(m, lib, o.frames);
  FaceData d = make_face_data(m);
  std::vector<Image> cells;
  for (const Expression& e : lib.expressions) {
    simulate_expression(m, d, e, o.frames);
    cells.push_back(expression_cell(m, d, neutral, e.name, o));
    if (done) done(e.name);
  }
  return with_colour_bar(contact_sheet(cells, o.columns, kCellGap), o.heat_max_mm);
}

}  // namespace facectl::face
