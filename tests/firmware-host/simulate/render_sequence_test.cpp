#include "firmware-host/simulate/render_sequence.hpp"

#include <gtest/gtest.h>
#include <png.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <limits>
#include <numbers>

#include "control/mapping/rig_mapping.hpp"

namespace facectl {
namespace {

namespace fs = std::filesystem;
using Face = std::array<double, kMaxFaceSignals>;
using Positions = std::array<double, kMaxActuators>;

struct Rgb {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;
};

Rgb read_png(const fs::path& path) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  Rgb out;
  if (!png_image_begin_read_from_file(&image, path.c_str())) return out;
  image.format = PNG_FORMAT_RGB;
  out.width = static_cast<int>(image.width);
  out.height = static_cast<int>(image.height);
  out.rgb.resize(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, out.rgb.data(), 0, nullptr)) out.rgb.clear();
  return out;
}

std::string bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

// Mean absolute difference (grey levels) between the left and right views.
double halves_differ(const Rgb& img, int view_width) {
  const int offset = img.width - view_width;  // the right view ends the picture
  double sum = 0.0;
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < 3 * view_width; ++x) {
      const std::size_t row = 3u * static_cast<std::size_t>(img.width * y);
      sum += std::abs(int{img.rgb[row + x]} - int{img.rgb[row + 3 * offset + x]});
    }
  }
  return sum / (3.0 * view_width * img.height);
}

class RenderSequenceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("facectl-render-" + std::to_string(getpid()));
    fs::remove_all(root_);
  }
  void TearDown() override { fs::remove_all(root_); }

  const ControllerModel& model() const { return config_.built.model; }
  Face face(std::initializer_list<std::pair<const char*, double>> values) const {
    Face f = model().neutral;
    for (auto [name, v] : values) f[*model().layout.find(name)] = v;
    return f;
  }
  Positions map(const Face& f) const {
    MappingWorkspace w = make_mapping_workspace(model().mapping);
    Positions p{};
    map_to_actuators(model().mapping, w, f, p);
    return p;
  }

  // Renders (command, positions) pairs into `dir`; returns the frame paths.
  std::vector<std::string> render(const fs::path& dir,
                                  const std::vector<std::pair<Face, Positions>>& frames,
                                  double* seconds_per_frame = nullptr) const {
    RenderSequence seq(config_, dir, {25, kSize, kSize});
    const auto t0 = std::chrono::steady_clock::now();
    for (const auto& [f, p] : frames) seq.add_frame(f, p);
    const auto t1 = std::chrono::steady_clock::now();
    if (seconds_per_frame) {
      *seconds_per_frame =
          std::chrono::duration<double>(t1 - t0).count() / static_cast<double>(frames.size());
    }
    return seq.frames();
  }

  static constexpr int kSize = 160;
  LoadedConfig config_ = load_config(default_config_path());
  fs::path root_;
};

TEST_F(RenderSequenceTest, WritesFramesWithIdenticalBytesOnASecondRun) {
  const double deg = std::numbers::pi / 180;
  const Face smile = face({{"zygomaticus_major_l", 0.8}, {"zygomaticus_major_r", 0.8}});
  const Face open = face({{"jaw_pitch", 12 * deg}, {"frontalis_l", 0.6}});
  const std::vector<std::pair<Face, Positions>> frames = {
      {model().neutral, map(model().neutral)}, {smile, map(smile)}, {open, map(open)}};
  const std::vector<std::string> a = render(root_ / "a", frames);
  const std::vector<std::string> b = render(root_ / "b", frames);
  ASSERT_EQ(a, (std::vector<std::string>{"frames/frame_00000.png", "frames/frame_00001.png",
                                         "frames/frame_00002.png"}));
  ASSERT_EQ(a, b);
  for (const std::string& f : a) {
    const Rgb img = read_png(root_ / "a" / f);
    EXPECT_EQ(img.width, 2 * kSize + 4) << f;  // two views and the divider
    EXPECT_EQ(img.height, kSize) << f;
    const std::string first = bytes(root_ / "a" / f);
    EXPECT_FALSE(first.empty());
    EXPECT_EQ(first, bytes(root_ / "b" / f)) << f;
  }
  // The frames show what was commanded: the smile and the open jaw differ from neutral.
  const Rgb neutral = read_png(root_ / "a" / a[0]);
  for (int k : {1, 2}) EXPECT_NE(read_png(root_ / "a" / a[k]).rgb, neutral.rgb) << a[k];
}

// The pair shows how faithful the mapping is: views agree where the rig
// reproduces the face, and differ where it does not.
TEST_F(RenderSequenceTest, ViewsDifferWhereTheRigDoesNotReproduceTheFace) {
  const double deg = std::numbers::pi / 180;
  // Everything involved is driven: the jaw by the mechanism. (Not an eyelid: its servo
  // reads the lid closure and the orbicularis oculi together, and since the cheek servo
  // follows the cheek point, which that muscle does not move, nothing else tells them
  // apart; a closure alone comes back split between the two.)
  const Face jaw = face({{"jaw_pitch", 14 * deg}, {"jaw_yaw", 2 * deg}});
  // The middle frontalis has no actuator of its own: the brow servos follow the inner and
  // outer brow points, so the rig gives its lift back as the inner and outer frontalis.
  // (Not the risorius: the corner servo sees it through the lip corner, and how far the
  // views differed for it turned on the reduced model's fit.)
  const Face frontalis = face({{"frontalis_l", 1.0}, {"frontalis_r", 1.0}});
  // The head did not follow at all (positions of the neutral face).
  const Face smile = face({{"zygomaticus_major_l", 1.0}, {"zygomaticus_major_r", 1.0}});
  double seconds = 0;
  const std::vector<std::string> f =
      render(root_, {{jaw, map(jaw)}, {frontalis, map(frontalis)}, {smile, map(model().neutral)}},
             &seconds);
  const double faithful = halves_differ(read_png(root_ / f[0]), kSize);
  const double unfaithful = halves_differ(read_png(root_ / f[1]), kSize);
  const double unmoved = halves_differ(read_png(root_ / f[2]), kSize);
  EXPECT_LT(faithful, 0.05);
  EXPECT_GT(unfaithful, 10 * faithful + 0.05);
  EXPECT_GT(unmoved, 10 * faithful + 0.05);
  RecordProperty("seconds_per_frame", std::to_string(seconds));
  std::printf(
      "differences (grey levels): faithful %.4f, frontalis %.4f, unmoved %.4f; %.1f ms/frame\n",
      faithful, unfaithful, unmoved, 1e3 * seconds);
}

// A malformed command is drawn as the controller takes it: a non-finite value
// holds the last good one, an out-of-range one is clamped.
TEST_F(RenderSequenceTest, DrawsAMalformedCommandAsTheControllerTakesIt) {
  const double deg = std::numbers::pi / 180;
  const Face smile = face({{"zygomaticus_major_l", 1.0}, {"jaw_pitch", 10 * deg}});
  Face bad = smile;
  bad[*model().layout.find("zygomaticus_major_l")] = std::numeric_limits<double>::quiet_NaN();
  bad[model().layout.jaw_pitch()] = 90 * deg;
  const Face clamped = face({{"zygomaticus_major_l", 1.0}, {"jaw_pitch", 18 * deg}});
  const std::vector<std::string> a = render(root_ / "a", {{smile, map(smile)}, {bad, map(smile)}});
  const std::vector<std::string> b =
      render(root_ / "b", {{smile, map(smile)}, {clamped, map(smile)}});
  EXPECT_EQ(bytes(root_ / "a" / a[1]), bytes(root_ / "b" / b[1]));
}

TEST_F(RenderSequenceTest, RejectsSpansOfTheWrongSize) {
  RenderSequence seq(config_, root_, {25, kSize, kSize});
  const Face f = model().neutral;
  const Positions p = map(f);
  EXPECT_THROW(seq.add_frame(std::span<const double>(f.data(), 3), p), std::invalid_argument);
  EXPECT_THROW(seq.add_frame(f, std::span<const double>(p.data(), 2)), std::invalid_argument);
  EXPECT_TRUE(seq.frames().empty());
}

}  // namespace
}  // namespace facectl
