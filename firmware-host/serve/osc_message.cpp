#include "firmware-host/serve/osc_message.hpp"

#include <lo/lo.h>

#include <cstdint>
#include <cstring>
#include <memory>

namespace facectl {
namespace {

constexpr int kMaxBundleDepth = 4;
constexpr std::size_t kMaxMessages = 64;

// An argument's value. liblo's argv points into its packed argument data,
// where a number need not sit on its type's alignment: read the bytes, do
// not dereference an lo_arg.
template <typename T>
T read_arg(const lo_arg* a) {
  T v;
  std::memcpy(&v, a, sizeof v);
  return v;
}

std::uint32_t big_endian_u32(const char* p) {
  const auto* b = reinterpret_cast<const unsigned char*>(p);
  return (std::uint32_t{b[0]} << 24) | (std::uint32_t{b[1]} << 16) | (std::uint32_t{b[2]} << 8) |
         std::uint32_t{b[3]};
}

OscMessage decode_message(std::string_view data) {
  // liblo reads (never writes) through a non-const pointer.
  void* raw = const_cast<char*>(data.data());
  int result = 0;
  const std::unique_ptr<std::remove_pointer_t<lo_message>, void (*)(lo_message)> m(
      lo_message_deserialise(raw, data.size(), &result), lo_message_free);
  if (!m) {
    throw OscFormatError("expected an OSC message, found one liblo refuses (error " +
                         std::to_string(result) + ")");
  }
  const char* path = lo_get_path(raw, static_cast<ssize_t>(data.size()));
  OscMessage out;
  out.address = path != nullptr ? path : "";
  const char* types = lo_message_get_types(m.get());
  lo_arg** argv = lo_message_get_argv(m.get());
  for (int i = 0; i < lo_message_get_argc(m.get()); ++i) {
    switch (types[i]) {
      case LO_INT32:
        out.args.emplace_back(static_cast<double>(read_arg<std::int32_t>(argv[i])));
        break;
      case LO_INT64:
        out.args.emplace_back(static_cast<double>(read_arg<std::int64_t>(argv[i])));
        break;
      case LO_FLOAT:
        out.args.emplace_back(static_cast<double>(read_arg<float>(argv[i])));
        break;
      case LO_DOUBLE:
        out.args.emplace_back(read_arg<double>(argv[i]));
        break;
      case LO_STRING:
      case LO_SYMBOL:
        out.args.emplace_back(std::string(reinterpret_cast<const char*>(argv[i])));
        break;
      default:
        throw OscFormatError(out.address + ": expected number or string arguments, found type '" +
                             std::string(1, types[i]) + "'");
    }
  }
  return out;
}

void decode(std::string_view data, int depth, std::vector<OscMessage>& out) {
  static constexpr std::string_view kBundle("#bundle\0", 8);
  if (data.substr(0, 8) != kBundle) {
    if (out.size() >= kMaxMessages) {
      throw OscFormatError("expected at most " + std::to_string(kMaxMessages) +
                           " messages in a datagram, found more");
    }
    out.push_back(decode_message(data));
    return;
  }
  if (depth >= kMaxBundleDepth) {
    throw OscFormatError("expected bundles nested at most " + std::to_string(kMaxBundleDepth) +
                         " deep, found deeper");
  }
  if (data.size() < 16) throw OscFormatError("expected a bundle's time tag, found the end");
  std::size_t at = 16;  // "#bundle\0" and the 8-byte time tag
  while (at < data.size()) {
    if (data.size() - at < 4)
      throw OscFormatError("expected a bundle element's size, found the end");
    const std::uint32_t n = big_endian_u32(data.data() + at);
    at += 4;
    if (n == 0 || n % 4 != 0 || n > data.size() - at) {
      throw OscFormatError(
          "expected a bundle element of a multiple of 4 bytes within the "
          "datagram, found a size of " +
          std::to_string(n));
    }
    decode(data.substr(at, n), depth + 1, out);
    at += n;
  }
}

}  // namespace

std::vector<OscMessage> decode_osc_datagram(std::string_view datagram) {
  std::vector<OscMessage> out;
  decode(datagram, 0, out);
  return out;
}

}  // namespace facectl
