#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace facectl {

// One OSC message as the control address space reads it: its address and
// its arguments, numbers as double (OSC's i, h, f and d) and strings (s, S).
struct OscMessage {
  using Arg = std::variant<double, std::string>;
  std::string address;
  std::vector<Arg> args;
};

// A datagram that is not OSC 1.0, or holds an argument type the address
// space never takes (blobs, MIDI, ...); the message says which.
class OscFormatError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The messages of one datagram: a message, or a bundle of messages and
// bundles (nested at most 4 deep), in order. Bundle time tags are not
// honoured: everything plays on arrival. Decoded by liblo
// (lo_message_deserialise); bundles are split here, as liblo keeps that
// for its own servers. At most 64 messages a datagram.
std::vector<OscMessage> decode_osc_datagram(std::string_view datagram);

}  // namespace facectl
