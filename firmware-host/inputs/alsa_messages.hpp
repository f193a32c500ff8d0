#pragma once

namespace facectl {

// alsa-lib prints its own failures to stderr (parse_card, Unknown PCM...);
// facectl reports them itself, naming the device and what to do. Call before
// opening an ALSA device; process-wide.
void quiet_alsa_lib();

}  // namespace facectl
