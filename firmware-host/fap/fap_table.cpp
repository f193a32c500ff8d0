#include "firmware-host/fap/fap_table.hpp"

#include <stdexcept>
#include <string>

namespace facectl {
namespace {

using U = FapUnit;
using D = FapDirection;

// Names, units, uni-/bidirectionality, positive direction and the feature point
// moved, as tabulated by the standard (checked against the descriptor tables of
// public FAP players; docs/FAP.md cites them).
constexpr std::array<FapInfo, kFapCount> kTable = {{
    {1, "viseme", U::kNone, false, D::kNone, ""},
    {2, "expression", U::kNone, false, D::kNone, ""},
    {3, "open_jaw", U::kMNS, false, D::kDown, "2.1"},
    {4, "lower_t_midlip", U::kMNS, true, D::kDown, "2.2"},
    {5, "raise_b_midlip", U::kMNS, true, D::kUp, "2.3"},
    {6, "stretch_l_cornerlip", U::kMW, true, D::kLeft, "2.4"},
    {7, "stretch_r_cornerlip", U::kMW, true, D::kRight, "2.5"},
    {8, "lower_t_lip_lm", U::kMNS, true, D::kDown, "2.6"},
    {9, "lower_t_lip_rm", U::kMNS, true, D::kDown, "2.7"},
    {10, "raise_b_lip_lm", U::kMNS, true, D::kUp, "2.8"},
    {11, "raise_b_lip_rm", U::kMNS, true, D::kUp, "2.9"},
    {12, "raise_l_cornerlip", U::kMNS, true, D::kUp, "2.4"},
    {13, "raise_r_cornerlip", U::kMNS, true, D::kUp, "2.5"},
    {14, "thrust_jaw", U::kMNS, false, D::kForward, "2.1"},
    {15, "shift_jaw", U::kMW, true, D::kRight, "2.1"},
    {16, "push_b_lip", U::kMNS, true, D::kForward, "2.3"},
    {17, "push_t_lip", U::kMNS, true, D::kForward, "2.2"},
    {18, "depress_chin", U::kMNS, true, D::kUp, "2.10"},
    {19, "close_t_l_eyelid", U::kIRISD, true, D::kDown, "3.1"},
    {20, "close_t_r_eyelid", U::kIRISD, true, D::kDown, "3.2"},
    {21, "close_b_l_eyelid", U::kIRISD, true, D::kUp, "3.3"},
    {22, "close_b_r_eyelid", U::kIRISD, true, D::kUp, "3.4"},
    {23, "yaw_l_eyeball", U::kAU, true, D::kLeft, "3.5"},
    {24, "yaw_r_eyeball", U::kAU, true, D::kLeft, "3.6"},
    {25, "pitch_l_eyeball", U::kAU, true, D::kDown, "3.5"},
    {26, "pitch_r_eyeball", U::kAU, true, D::kDown, "3.6"},
    {27, "thrust_l_eyeball", U::kES, true, D::kForward, "3.5"},
    {28, "thrust_r_eyeball", U::kES, true, D::kForward, "3.6"},
    {29, "dilate_l_pupil", U::kIRISD, true, D::kGrowing, "3.5"},
    {30, "dilate_r_pupil", U::kIRISD, true, D::kGrowing, "3.6"},
    {31, "raise_l_i_eyebrow", U::kENS, true, D::kUp, "4.1"},
    {32, "raise_r_i_eyebrow", U::kENS, true, D::kUp, "4.2"},
    {33, "raise_l_m_eyebrow", U::kENS, true, D::kUp, "4.3"},
    {34, "raise_r_m_eyebrow", U::kENS, true, D::kUp, "4.4"},
    {35, "raise_l_o_eyebrow", U::kENS, true, D::kUp, "4.5"},
    {36, "raise_r_o_eyebrow", U::kENS, true, D::kUp, "4.6"},
    {37, "squeeze_l_eyebrow", U::kES, true, D::kRight, "4.1"},
    {38, "squeeze_r_eyebrow", U::kES, true, D::kLeft, "4.2"},
    {39, "puff_l_cheek", U::kES, true, D::kLeft, "5.1"},
    {40, "puff_r_cheek", U::kES, true, D::kRight, "5.2"},
    {41, "lift_l_cheek", U::kENS, false, D::kUp, "5.3"},
    {42, "lift_r_cheek", U::kENS, false, D::kUp, "5.4"},
    {43, "shift_tongue_tip", U::kMW, true, D::kRight, "6.1"},
    {44, "raise_tongue_tip", U::kMNS, true, D::kUp, "6.1"},
    {45, "thrust_tongue_tip", U::kMW, true, D::kForward, "6.1"},
    {46, "raise_tongue", U::kMNS, true, D::kUp, "6.2"},
    {47, "tongue_roll", U::kAU, false, D::kUp, "6.3"},
    {48, "head_pitch", U::kAU, true, D::kDown, "7.1"},
    {49, "head_yaw", U::kAU, true, D::kLeft, "7.1"},
    {50, "head_roll", U::kAU, true, D::kRight, "7.1"},
    {51, "lower_t_midlip_o", U::kMNS, true, D::kDown, "8.1"},
    {52, "raise_b_midlip_o", U::kMNS, true, D::kUp, "8.2"},
    {53, "stretch_l_cornerlip_o", U::kMW, true, D::kLeft, "8.3"},
    {54, "stretch_r_cornerlip_o", U::kMW, true, D::kRight, "8.4"},
    {55, "lower_t_lip_lm_o", U::kMNS, true, D::kDown, "8.5"},
    {56, "lower_t_lip_rm_o", U::kMNS, true, D::kDown, "8.6"},
    {57, "raise_b_lip_lm_o", U::kMNS, true, D::kUp, "8.7"},
    {58, "raise_b_lip_rm_o", U::kMNS, true, D::kUp, "8.8"},
    {59, "raise_l_cornerlip_o", U::kMNS, true, D::kUp, "8.3"},
    {60, "raise_r_cornerlip_o", U::kMNS, true, D::kUp, "8.4"},
    {61, "stretch_l_nose", U::kENS, true, D::kLeft, "9.1"},
    {62, "stretch_r_nose", U::kENS, true, D::kRight, "9.2"},
    {63, "raise_nose", U::kENS, true, D::kUp, "9.3"},
    {64, "bend_nose", U::kENS, true, D::kRight, "9.3"},
    {65, "raise_l_ear", U::kENS, true, D::kUp, "10.1"},
    {66, "raise_r_ear", U::kENS, true, D::kUp, "10.2"},
    {67, "pull_l_ear", U::kENS, true, D::kLeft, "10.3"},
    {68, "pull_r_ear", U::kENS, true, D::kRight, "10.4"},
}};

}  // namespace

const std::array<FapInfo, kFapCount>& fap_table() {
  return kTable;
}

const FapInfo& fap_info(int number) {
  if (number < 1 || number > kFapCount) {
    throw std::out_of_range("FAP number " + std::to_string(number) + " outside 1..68");
  }
  return kTable[static_cast<std::size_t>(number - 1)];
}

std::string_view fap_unit_name(FapUnit unit) {
  switch (unit) {
    case FapUnit::kMNS:
      return "MNS";
    case FapUnit::kMW:
      return "MW";
    case FapUnit::kENS:
      return "ENS";
    case FapUnit::kES:
      return "ES";
    case FapUnit::kIRISD:
      return "IRISD";
    case FapUnit::kAU:
      return "AU";
    case FapUnit::kNone:
      break;
  }
  return "-";
}

}  // namespace facectl
