// Bytes from a Feetech SCS/STS bus (docs/PROTOCOLS.md, "Feetech"): the
// packet reader must find packets or ask for more, never read or write out
// of bounds, always make progress, and hand back only what fits.
#include <array>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "drivers/protocol/feetech_packet.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace facectl::scs;
  std::span<const std::uint8_t> in(data, size);
  std::array<std::uint8_t, 16> params{};
  while (!in.empty()) {
    Packet p;
    const ParseResult r = parse_packet(in, p, params);
    if (p.consumed > in.size() || p.param_count > params.size()) std::abort();
    if (r == ParseResult::kOk && p.consumed < kOverhead + p.param_count) std::abort();
    if (r == ParseResult::kIncomplete && p.consumed == 0) break;  // waits for more bytes
    if (p.consumed == 0) std::abort();                            // anything else must move on
    in = in.subspan(p.consumed);
  }
  return 0;
}
