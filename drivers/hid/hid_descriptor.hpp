#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace facectl {

// One input field of a HID report, as its report descriptor declares it
// (HID 1.11, section 6.2.2): where it sits, how wide it is, what it means.
struct HidInputField {
  int report_id = -1;      // -1: the device uses no report ids
  int bit_offset = 0;      // from the start of the report, after the id byte
  int bit_size = 0;        // 1..32
  std::uint16_t page = 0;  // usage page
  std::uint16_t usage = 0;
  std::int32_t logical_min = 0;
  std::int32_t logical_max = 0;
  bool is_variable = true;  // false: an array field (holds a usage index)
  bool is_relative = false;
  bool has_null_state = false;
  std::uint32_t application = 0;  // page << 16 | usage of its top-level collection
};

// The data input fields (constant padding left out, but counted in the
// offsets) of `descriptor`, in descriptor order. Long items, output and
// feature items are skipped. Throws std::invalid_argument naming the byte
// offset and the item when the descriptor is malformed.
std::vector<HidInputField> parse_hid_descriptor(std::span<const std::uint8_t> descriptor);

}  // namespace facectl
