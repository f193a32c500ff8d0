#include "firmware-host/fap/fap_udp_bounds.hpp"

#include <cmath>
#include <cstdio>
#include <string>

namespace facectl {
namespace {

[[noreturn]] void refuse(const FapReader& reader, int line, const std::string& expected,
                         const std::string& found) {
  try {
    reader.fail(line, 0, expected, found);
  } catch (const FapFormatError& e) {
    throw FapBoundError(e.what(), line);
  }
}

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

}  // namespace

void check_header_bounds(const FapReader& reader, const FapUdpLimits& limits, int line) {
  if (!reader.has_header()) return;
  const FapHeader& h = reader.header();
  if (h.name.size() > limits.name_length) {
    refuse(reader, line,
           "a header name of at most " + std::to_string(limits.name_length) + " characters",
           std::to_string(h.name.size()) + " characters");
  }
  if (h.frame_rate < limits.min_frame_rate || h.frame_rate > limits.max_frame_rate) {
    refuse(reader, line,
           "a frame rate in " + number(limits.min_frame_rate) + ".." +
               number(limits.max_frame_rate) + " frames per second",
           number(h.frame_rate));
  }
  if (h.frame_count > limits.frame_count) {
    refuse(reader, line, "a frame count of at most " + std::to_string(limits.frame_count),
           std::to_string(h.frame_count));
  }
}

void check_frame_bounds(const FapReader& reader, const FapFrame& frame, std::optional<long> before,
                        long skipped, const FapUdpLimits& limits) {
  // Refused rather than adopted: a number far ahead would otherwise shut out
  // every later frame of the sender's real numbering. Measured against the
  // time since its previous frame too, so that a sender whose numbers follow
  // its clock is not shut out by its own silence.
  const long base = before.value_or(0);
  const long jump = limits.frame_jump + (before ? skipped : 0);
  if (frame.number - base > jump) {
    refuse(reader, frame.line,
           before ? "a frame number at most " + std::to_string(jump) + " above frame " +
                        std::to_string(base) + ", the sender's last before this datagram"
                  : "a frame number after the header of at most " + std::to_string(jump),
           std::to_string(frame.number));
  }
  for (std::size_t i = 2; i < frame.values.size(); ++i) {
    if (frame.mask[i] && std::fabs(frame.values[i]) > limits.value) {
      refuse(reader, frame.line,
             "FAP " + std::to_string(i + 1) + " within +-" + number(limits.value) + " FAPU",
             number(frame.values[i]));
    }
  }
}

void check_frame_count(const FapReader& reader, std::size_t count, const FapUdpLimits& limits,
                       int line) {
  if (count > limits.frames_per_datagram) {
    refuse(reader, line,
           "at most " + std::to_string(limits.frames_per_datagram) + " frames in one datagram",
           "frame " + std::to_string(count));
  }
}

}  // namespace facectl
