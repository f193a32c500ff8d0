// write_head_folder (head_writer.hpp) read back by load_head_spec: every value exactly as
// written, and names with YAML's special characters intact.
#include "facectl/face/head_writer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include "default_head.hpp"
#include "facectl/face/yaml_emit.hpp"

namespace facectl::face {
namespace {

// Lengths go through the file in mm and come back exactly...
double via_mm(double metres) {
  return metres;
}
// ...except the rare one that no decimal in mm reaches after the reader's · 1e-3: then
// the mm value is exact and the metres are within a rounding of that product.
void expect_within_rounding(double read, double written) {
  EXPECT_NEAR(read, written, 2 * std::numeric_limits<double>::epsilon() * std::abs(written));
}

void expect_same(const MuscleStiffness& a, const MuscleStiffness& b) {
  EXPECT_EQ(a.up_latitudinal, b.up_latitudinal);
  EXPECT_EQ(a.up_longitudinal, b.up_longitudinal);
  EXPECT_EQ(a.low_latitudinal, b.low_latitudinal);
  EXPECT_EQ(a.low_longitudinal, b.low_longitudinal);
  EXPECT_EQ(a.connection, b.connection);
  EXPECT_EQ(a.up_shear, b.up_shear);
  EXPECT_EQ(a.low_shear, b.low_shear);
  EXPECT_EQ(a.bend, b.bend);
  EXPECT_EQ(a.volume, b.volume);
  EXPECT_EQ(a.position, b.position);
}

void expect_same(const std::vector<PointRef>& a, const std::vector<PointRef>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].landmark, b[i].landmark);
    for (int c = 0; c < 3; ++c) expect_within_rounding(b[i].offset[c], a[i].offset[c]);
  }
}

TEST(YamlEmit, NumbersAreShortestAndExact) {
  EXPECT_EQ(exact_number(0.2), "0.2");
  EXPECT_EQ(exact_number(-0.0), "0");
  EXPECT_EQ(exact_number(1e-5), "1e-05");
  for (double v : {0.1 + 0.2, 1.0 / 3, -2.718281828459045e-7, 12345.678901234567})
    EXPECT_EQ(std::stod(exact_number(v)), v) << exact_number(v);
  EXPECT_THROW(exact_number(std::nan("")), std::invalid_argument);
}

// The default head with awkward numbers and a landmark whose name has a colon, quotes
// and a hash: written, read back, compared field by field.
TEST(HeadWriter, RoundTripsValuesAndNamesExactly) {
  HeadSpec h = testing::default_spec();
  h.tissue_depth = 0.1 + 0.2;  // 0.30000000000000004
  h.teeth_gap = 1.0 / 3 * 1e-3;
  h.upper_lid_share = 0.7999999999999999;
  h.skin.stretch = 1.0 / 7;
  h.sheet.bend = 2.0 / 3;
  h.variants = {1000, 1500};
  const std::string odd = "fdp: 2#1 \"x\" 'y', [z]";
  const std::string old = h.landmarks[0].name;
  h.landmarks[0].name = odd;
  h.landmarks[0].offset = Vec3(1e-3 / 3, -2.5e-3, 0.1 + 0.2);
  for (MuscleSpec& m : h.muscles)
    for (auto* rs : {&m.origin, &m.insertion, &m.inner, &m.outer})
      for (PointRef& r : *rs) {
        if (r.landmark == old) r.landmark = odd;
        r.offset *= 1.0 + 1e-9;  // no longer round in mm
      }
  for (std::string& c : h.control_points)
    if (c == old) c = odd;
  h.control_points.push_back(odd);

  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "head_writer";
  std::filesystem::remove_all(dir);
  write_head_folder(dir.string(), h, {h.skin_file, "cm", h.dir, "note: # 'quoted'\nsecond line"});
  const HeadSpec r = load_head_spec(dir.string());

  EXPECT_EQ(r.openings, h.openings);
  EXPECT_EQ(r.tissue_depth, via_mm(h.tissue_depth));
  EXPECT_EQ(r.teeth_half_width, via_mm(h.teeth_half_width));
  EXPECT_EQ(r.teeth_depth, via_mm(h.teeth_depth));
  EXPECT_EQ(r.teeth_height, via_mm(h.teeth_height));
  EXPECT_EQ(r.teeth_inset, via_mm(h.teeth_inset));
  EXPECT_EQ(r.teeth_gap, via_mm(h.teeth_gap));
  EXPECT_EQ(r.eyelid_band, via_mm(h.eyelid_band));
  EXPECT_EQ(r.eyeball_radius, via_mm(h.eyeball_radius));
  EXPECT_EQ(r.upper_lid_share, h.upper_lid_share);
  EXPECT_EQ(r.oculi_lid_coupling, h.oculi_lid_coupling);
  EXPECT_EQ(r.skin_iterations, h.skin_iterations);
  EXPECT_EQ(r.influence_falloff, via_mm(h.influence_falloff));
  EXPECT_EQ(r.skin.stretch, h.skin.stretch);
  EXPECT_EQ(r.skin.bending, h.skin.bending);
  EXPECT_EQ(r.skin.area, h.skin.area);
  EXPECT_EQ(r.skin.anchor, h.skin.anchor);
  EXPECT_EQ(r.skin.volume, h.skin.volume);
  EXPECT_EQ(r.skin.damping, h.skin.damping);
  EXPECT_EQ(r.skin.min_projected_area, h.skin.min_projected_area);
  expect_same(r.sheet, h.sheet);
  expect_same(r.sphincter, h.sphincter);
  EXPECT_EQ(r.variants, h.variants);
  EXPECT_EQ(r.control_points, h.control_points);
  ASSERT_EQ(r.landmarks.size(), h.landmarks.size());
  for (std::size_t i = 0; i < h.landmarks.size(); ++i) {
    EXPECT_EQ(r.landmarks[i].name, h.landmarks[i].name);
    EXPECT_EQ(r.landmarks[i].vertices, h.landmarks[i].vertices);
    for (int c = 0; c < 3; ++c)
      EXPECT_EQ(r.landmarks[i].offset[c], via_mm(h.landmarks[i].offset[c])) << i;
  }
  ASSERT_EQ(r.muscles.size(), h.muscles.size());
  for (std::size_t i = 0; i < h.muscles.size(); ++i) {
    const MuscleSpec &a = h.muscles[i], &b = r.muscles[i];
    EXPECT_EQ(b.name, a.name);
    EXPECT_EQ(b.kind, a.kind);
    EXPECT_EQ(b.layer, a.layer);
    EXPECT_EQ(b.rows, a.rows);
    EXPECT_EQ(b.cols, a.cols);
    EXPECT_EQ(b.thickness, via_mm(a.thickness));
    expect_same(a.origin, b.origin);
    expect_same(a.insertion, b.insertion);
    expect_same(a.inner, b.inner);
    expect_same(a.outer, b.outer);
  }
}

}  // namespace
}  // namespace facectl::face
