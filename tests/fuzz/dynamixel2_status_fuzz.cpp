// Bytes from a DYNAMIXEL Protocol 2.0 bus (docs/PROTOCOLS.md, "Dynamixel"):
// the status reader must find packets or ask for more, never read or write
// out of bounds, always make progress, and hand back only what fits.
#include <cstdint>
#include <cstdlib>
#include <span>

#include "drivers/protocol/dynamixel2_packet.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace facectl::dxl2;
  std::span<const std::uint8_t> in(data, size);
  std::array<std::uint8_t, 32> params{};
  while (!in.empty()) {
    Status st;
    const ParseResult r = parse_status(in, st, params);
    if (st.consumed > in.size() || st.param_count > params.size()) std::abort();
    if (r == ParseResult::kIncomplete && st.consumed == 0) break;  // waits for more bytes
    if (st.consumed == 0) std::abort();                            // anything else must move on
    in = in.subspan(st.consumed);
  }
  return 0;
}
