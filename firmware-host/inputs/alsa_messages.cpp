#include "firmware-host/inputs/alsa_messages.hpp"

#include <alsa/asoundlib.h>

namespace facectl {
namespace {

void discard(const char*, int, const char*, int, const char*, ...) {}

}  // namespace

void quiet_alsa_lib() {
  snd_lib_error_set_handler(discard);
}

}  // namespace facectl
