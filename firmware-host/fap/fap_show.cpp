#include "firmware-host/fap/fap_show.hpp"

namespace facectl {

FapShow FapShow::build(const FapSequence& sequence, const FapMapping& mapping) {
  FapShow show;
  show.name_ = sequence.header.name;
  show.track_ = PoseTrack(mapping.layout().size());
  show.track_.reserve(sequence.frames.size());
  FapState state;
  std::vector<FapClamp> frame_clamps;
  for (const FapFrame& frame : sequence.frames) {
    state.apply(frame);
    std::array<double, kMaxFaceSignals> pose{};
    frame_clamps.clear();
    mapping.map(state, frame.number, pose, &frame_clamps);
    for (FapClamp& c : frame_clamps) {
      if (show.clamps_.size() < kMaxClampNotes) {
        show.clamps_.push_back(std::move(c));
      } else {
        ++show.clamps_left_out_;
      }
    }
    show.track_.add(sequence.time_of(frame), pose);
  }
  for (int f = 1; f <= kFapCount; ++f) {
    const auto bit = static_cast<std::size_t>(f - 1);
    if (sequence.used[bit] && !mapping.supported()[bit]) show.ignored_.push_back(f);
    if (sequence.unplayed[bit]) show.unplayed_.push_back(f);
  }
  return show;
}

std::vector<std::string> FapShow::report() const {
  std::vector<std::string> lines;
  for (const FapClamp& c : clamps_) lines.push_back("clamped: " + describe(c));
  if (clamps_left_out_ > 0) {
    lines.push_back("clamped: " + std::to_string(clamps_left_out_) + " more values after frame " +
                    std::to_string(clamps_.back().frame) + " (the first " +
                    std::to_string(kMaxClampNotes) + " are listed)");
  }
  auto list = [&lines](const char* what, const std::vector<int>& faps) {
    if (faps.empty()) return;
    std::string s = what;
    for (std::size_t i = 0; i < faps.size(); ++i) {
      s.append(i == 0 ? " " : ", ");
      s.append(std::to_string(faps[i]));
      s.push_back(' ');
      s.append(fap_info(faps[i]).name);
    }
    lines.push_back(s);
  };
  list("ignored (no counterpart on this head):", ignored_);
  list("ignored (Greta's one-value form, not the standard's fields):", unplayed_);
  return lines;
}

}  // namespace facectl
