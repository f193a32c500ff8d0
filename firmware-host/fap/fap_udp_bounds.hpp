#pragma once

#include <optional>

#include "firmware-host/config/fap_stream_config.hpp"
#include "firmware-host/fap/fap_file.hpp"

namespace facectl {

// A well-formed FAP datagram with a field past FapUdpLimits. Its own type,
// so that the stream counts it apart from malformed ones.
class FapBoundError : public FapFormatError {
 public:
  using FapFormatError::FapFormatError;
};

// Each throws FapBoundError naming the reader's source and `line`.
// The reader's current header (checked after every line: the first line
// where it fails is the header's).
void check_header_bounds(const FapReader& reader, const FapUdpLimits& limits, int line);
// A frame just read; `before` is the sender's last frame number before this
// datagram (none if the datagram or the frames before it began with a
// header). The number may be limits.frame_jump + `skipped` above it, for the
// whole datagram, not per frame: `skipped` is how many frames the sender's
// clock ran on while it was silent.
void check_frame_bounds(const FapReader& reader, const FapFrame& frame, std::optional<long> before,
                        long skipped, const FapUdpLimits& limits);
// The datagram's frames so far, `count`, read up to `line`.
void check_frame_count(const FapReader& reader, std::size_t count, const FapUdpLimits& limits,
                       int line);

}  // namespace facectl
