#pragma once

#include <array>
#include <string>
#include <vector>

#include "control/capacity.hpp"
#include "firmware-host/fap/fap_file.hpp"
#include "firmware-host/fap/fap_mapping.hpp"
#include "firmware-host/inputs/pose_track.hpp"

namespace facectl {

// A parsed FAP sequence turned into face poses, one per frame at t = frame
// number / frame rate, so that it plays like a Show: evaluate(t) interpolates
// linearly between frames and holds the ends. Carries the clamp report and
// the FAPs the file uses that this head ignores.
class FapShow {
 public:
  static FapShow build(const FapSequence& sequence, const FapMapping& mapping);

  const std::string& name() const { return name_; }
  double start() const { return track_.start(); }
  double duration() const { return track_.duration(); }
  std::size_t frame_count() const { return track_.size(); }
  void evaluate(double t, std::array<double, kMaxFaceSignals>& out) const {
    track_.evaluate(t, out);
  }
  const PoseTrack& track() const { return track_; }

  // The first kMaxClampNotes clamps, in frame order; clamps_left_out() more.
  // (A file may clamp in every frame: the report must stay readable and small.)
  static constexpr std::size_t kMaxClampNotes = 100;
  const std::vector<FapClamp>& clamps() const { return clamps_; }
  std::size_t clamps_left_out() const { return clamps_left_out_; }
  const std::vector<int>& ignored_faps() const { return ignored_; }
  // FAPs the file carries in a form that is not played (Greta's one-value FAP 1, 2).
  const std::vector<int>& unplayed_faps() const { return unplayed_; }
  // One line per clamp kept, one for those left out, one for the ignored
  // FAPs and one for the unplayed;
  // empty when there is nothing to say.
  std::vector<std::string> report() const;

 private:
  std::string name_;
  PoseTrack track_;
  std::vector<FapClamp> clamps_;
  std::size_t clamps_left_out_ = 0;
  std::vector<int> ignored_;
  std::vector<int> unplayed_;
};

}  // namespace facectl
