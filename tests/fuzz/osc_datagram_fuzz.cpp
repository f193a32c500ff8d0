// One datagram of `facectl serve`'s OSC control (docs/INPUTS.md, "OSC show
// control"): liblo and the bundle splitter must read it or refuse it with
// OscFormatError, and what they read must be what the address space can
// take: at most 64 messages, no string longer than the datagram. Numbers may
// be anything; the head service's checks refuse what is not finite.
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>
#include <variant>

#include "firmware-host/serve/osc_message.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view datagram(reinterpret_cast<const char*>(data), size);
  try {
    const auto messages = facectl::decode_osc_datagram(datagram);
    if (messages.size() > 64) std::abort();
    for (const auto& m : messages) {
      if (m.address.size() > size) std::abort();
      for (const auto& a : m.args) {
        if (const auto* s = std::get_if<std::string>(&a); s != nullptr && s->size() > size) {
          std::abort();
        }
      }
    }
  } catch (const facectl::OscFormatError&) {
  }
  return 0;
}
