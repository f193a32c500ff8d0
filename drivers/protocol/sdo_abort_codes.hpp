#pragma once

#include <cstdint>

namespace facectl::cia402 {

// The meaning of a CiA 301 SDO abort code (CiA 301 v4.2, table 22), e.g.
// 0x06020000 -> "object does not exist"; "unknown abort code" otherwise.
// A static string: safe to use from the tick.
const char* sdo_abort_text(std::uint32_t code);

}  // namespace facectl::cia402
