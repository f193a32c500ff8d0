// The pictures: the displacement heat map (zero colour at neutral, hot where the jaw
// opened), its colour bar, the labelled expression cell, option errors, determinism.
#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>

#include "default_head.hpp"
#include "facectl/face/bitmap_font.hpp"
#include "facectl/face/expression_sheet.hpp"
#include "facectl/face/heat_map.hpp"

namespace facectl::face {
namespace {

using testing::default_model;

const ExpressionLibrary& library() {
  return testing::default_library();
}

FaceData posed(const std::string& name) {
  FaceData d = make_face_data(default_model());
  simulate_expression(default_model(), d, *library().find(name), 300);
  return d;
}

const Points& neutral() {
  static const Points n = neutral_skin(default_model(), library(), 300);
  return n;
}

struct Rgbi {
  int r, g, b;
};
Rgbi at(const Image& img, int x, int y) {
  const std::uint8_t* p = &img.rgb[3 * (y * img.width + x)];
  return {p[0], p[1], p[2]};
}
// Warm enough that only the upper part of the ramp (about 5 mm of 10 and more) gives it;
// the background, greys and the cool end never do.
Rgb8 rgb8(const Rgbi& c) {
  return {static_cast<std::uint8_t>(c.r), static_cast<std::uint8_t>(c.g),
          static_cast<std::uint8_t>(c.b)};
}
bool hot(const Rgbi& c) {
  return c.r > c.b + 40;
}
bool cold(const Rgbi& c) {
  return c.b > c.r + 60;
}

RenderOptions heat_view(const std::vector<double>& mm) {
  RenderOptions o{View::kThreeQuarter, 240, 300, false, Lighting::kRaking};
  o.heat_mm = &mm;
  return o;
}

TEST(HeatMap, RampEndsAndClamping) {
  EXPECT_EQ(heat_colour(0), (Rgb8{35, 55, 140}));
  EXPECT_EQ(heat_colour(1), (Rgb8{215, 40, 30}));
  EXPECT_EQ(heat_colour(-3), heat_colour(0));
  EXPECT_EQ(heat_colour(7), heat_colour(1));
  EXPECT_EQ(heat_colour(std::nan("")), heat_colour(0));
  EXPECT_FALSE(hot({35, 55, 140}));
  const Rgb8 warm = heat_colour(0.6);
  EXPECT_TRUE(hot({warm[0], warm[1], warm[2]}));
}

TEST(HeatMap, NeutralIsAllTheZeroColour) {
  const FaceData d = posed("neutral");
  const std::vector<double> mm = displacement_mm(d.skin_x, neutral());
  EXPECT_EQ(*std::max_element(mm.begin(), mm.end()), 0.0);  // the solver is deterministic
  const Image img = render_face(default_model(), d, heat_view(mm));
  int n_hot = 0, n_cold = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      n_hot += hot(at(img, x, y));
      n_cold += cold(at(img, x, y));
    }
  EXPECT_EQ(n_hot, 0);
  EXPECT_GT(n_cold, img.width * img.height / 5);  // the skin covers much of the picture
}

TEST(HeatMap, MouthIsHotAndForeheadColdWhenTheJawOpens) {
  const FaceData d = posed("jaw_open");
  const std::vector<double> mm = displacement_mm(d.skin_x, neutral());
  const RenderOptions o = heat_view(mm);
  const Image img = render_face(default_model(), d, o);
  // 5×5 pixel patches around where the lower lip and the mid-forehead are drawn.
  auto patch = [&](int vertex, bool (*pred)(const Rgbi&)) {
    const Eigen::Vector2d s = project_to_image(default_model(), o, d.skin_x.get(vertex));
    int n = 0;
    for (int dy = -2; dy <= 2; ++dy)
      for (int dx = -2; dx <= 2; ++dx)
        n += pred(at(img, static_cast<int>(s.x()) + dx, static_cast<int>(s.y()) + dy));
    return n;
  };
  const FaceModel& m = default_model();
  auto landmark = [&](const char* name) { return m.landmark_vertices[m.landmark_index(name)][0]; };
  const int lower_lip = landmark("fdp_8_2");
  // The skin vertex nearest the point halfway from the hairline to between the brows (the
  // hairline itself is on the mask's edge, half background in the picture).
  const Vec3 target =
      0.5 * (m.skin.v.get(landmark("fdp_11_1")) +
             0.5 * (m.skin.v.get(landmark("fdp_4_1")) + m.skin.v.get(landmark("fdp_4_2"))));
  int forehead = 0;
  for (int i = 0; i < static_cast<int>(m.skin.v.size()); ++i)
    if ((m.skin.v.get(i) - target).norm() < (m.skin.v.get(forehead) - target).norm()) forehead = i;
  EXPECT_GT(mm[lower_lip], 6.0);
  EXPECT_LT(mm[forehead], 1.0);
  EXPECT_GE(patch(lower_lip, hot), 20);
  EXPECT_EQ(patch(forehead, cold), 25);
}

TEST(HeatMap, ColourBarShowsTheRampAndItsScale) {
  const Image bar = colour_bar(400, 10);
  // Some row runs through the ramp from the zero colour to the full colour.
  bool found = false;
  for (int y = 0; y < bar.height && !found; ++y) {
    int x0 = 0;
    while (x0 < bar.width && !cold(at(bar, x0, y))) ++x0;
    if (x0 == bar.width) continue;
    int x1 = bar.width - 1;
    while (x1 > x0 && !hot(at(bar, x1, y))) --x1;
    const Rgbi a = at(bar, x0, y), b = at(bar, x1, y);
    found = rgb8(a) == heat_colour(0) && rgb8(b) == heat_colour(1);
  }
  EXPECT_TRUE(found);
  EXPECT_THROW(colour_bar(400, 0), std::invalid_argument);
  EXPECT_THROW(colour_bar(60, 10), std::invalid_argument);
}

TEST(Render, CellIsLabelledWithTheName) {
  const FaceData d = posed("neutral");
  SheetOptions o;
  o.tile_width = 160;
  o.tile_height = 200;
  const Image cell = expression_cell(default_model(), d, neutral(), "AAA", o);
  EXPECT_EQ(cell.width, 2 * 160 + 2);
  const int label_h = cell.height - 200;
  int ink = 0;
  for (int y = 0; y < label_h; ++y)
    for (int x = 0; x < cell.width; ++x) {
      const Rgbi c = at(cell, x, y);
      ink += c.r == 30 && c.g == 30 && c.b == 30;
    }
  EXPECT_EQ(ink, 3 * 18 * 4);  // three A's of 18 dots, each dot 2×2 pixels
}

TEST(Render, RakingLightIsDeterministicAndDiffersFromFrontal) {
  const FaceData d = posed("sadness");
  RenderOptions o{View::kThreeQuarter, 120, 150, false, Lighting::kRaking};
  const Image a = render_face(default_model(), d, o);
  EXPECT_EQ(a.rgb, render_face(default_model(), d, o).rgb);
  o.lighting = Lighting::kFrontal;
  EXPECT_NE(a.rgb, render_face(default_model(), d, o).rgb);
}

template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no error";
}

TEST(Render, BadOptionsAreRefusedWithWhatWasWrong) {
  const FaceData d = posed("neutral");
  RenderOptions o;
  o.width = 8;
  EXPECT_EQ(error_of([&] { render_face(default_model(), d, o); }),
            "render: picture size 8x600 is outside 16..8192 pixels");
  const std::vector<double> three(3, 0.0);
  o = heat_view(three);
  EXPECT_EQ(error_of([&] { render_face(default_model(), d, o); }),
            "render: heat map has 3 values for 468 skin vertices");
  SheetOptions s;
  s.columns = 0;
  EXPECT_EQ(error_of([&] { validate(s); }), "sheet: columns 0 is outside 1..20");
  s = {};
  s.heat_max_mm = -1;
  EXPECT_NE(error_of([&] { validate(s); }).find("heat-map scale -1"), std::string::npos);
  s = {};
  s.tile_width = 50;
  EXPECT_EQ(error_of([&] { validate(s); }), "sheet: tile width 50 is outside 120..4096 pixels");
  EXPECT_NE(error_of([&] { displacement_mm(d.skin_x, Points{}); }).find("468 against 0"),
            std::string::npos);
}

}  // namespace
}  // namespace facectl::face
