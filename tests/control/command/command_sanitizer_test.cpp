#include "control/command/command_sanitizer.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace facectl {
namespace {

TEST(CommandSanitizer, RejectsNanInfAndOutOfDomainAndHoldsTheLastGoodValue) {
  const FaceLayout layout({"zygomaticus_major_l", "zygomaticus_major_r"});
  CommandSanitizer s(layout);
  std::array<double, kMaxFaceSignals> good{};
  s.reset(good);

  FaceCommand c;
  c.values[0] = 0.5;
  c.values[1] = 0.25;
  EXPECT_EQ(s.apply(c), 0u);
  EXPECT_DOUBLE_EQ(s.values()[0], 0.5);

  c.values[0] = std::numeric_limits<double>::quiet_NaN();
  c.values[1] = std::numeric_limits<double>::infinity();
  EXPECT_EQ(s.apply(c), 2u);
  EXPECT_DOUBLE_EQ(s.values()[0], 0.5);
  EXPECT_DOUBLE_EQ(s.values()[1], 0.25);

  c.values[0] = 1e30;  // far outside the contraction domain
  c.values[1] = -0.2;
  EXPECT_EQ(s.apply(c), 2u);
  EXPECT_DOUBLE_EQ(s.values()[0], 0.5);
  EXPECT_EQ(s.rejected(0), 2u);
  EXPECT_EQ(s.rejected(1), 2u);
  EXPECT_EQ(s.rejected_total(), 4u);
}

TEST(CommandSanitizer, SnapsRoundingNoiseAtTheDomainEdge) {
  const FaceLayout layout({"m_l"});
  CommandSanitizer s(layout);
  s.reset({});
  FaceCommand c;
  c.values[0] = 1.0 + 1e-12;
  EXPECT_EQ(s.apply(c), 0u);
  EXPECT_DOUBLE_EQ(s.values()[0], 1.0);
}

TEST(CommandSanitizer, ChecksTheMandibleAndRigidDomains) {
  const FaceLayout layout({"m_l"});
  CommandSanitizer s(layout);
  s.reset({});
  FaceCommand c;
  c.values[layout.jaw_pitch()] = 3.0;  // rad: beyond any jaw
  c.values[*layout.find("eyelid_closure_l")] = 1.5;
  EXPECT_EQ(s.apply(c), 2u);
}

}  // namespace
}  // namespace facectl
