#include "drivers/hid/hid_descriptor.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace facectl {
namespace {

// Bounds that keep a hostile descriptor from costing unbounded memory; the
// Linux HID core uses the same report size limit (256) and a 12288 usage
// limit (HID_MAX_USAGES, include/linux/hid.h).
constexpr std::uint32_t kMaxReportSize = 256;
constexpr std::uint32_t kMaxReportCount = 4096;
constexpr std::size_t kMaxFields = 4096;
constexpr std::size_t kMaxUsages = 4096;
constexpr std::size_t kMaxPushDepth = 16;
constexpr std::size_t kMaxCollectionDepth = 32;
constexpr int kMaxReportBits = 1 << 16;

// Item tags (HID 1.11, 6.2.2.4 to 6.2.2.8).
enum : int { kMain = 0, kGlobal = 1, kLocal = 2 };
enum : int { kInput = 0x8, kOutput = 0x9, kCollection = 0xA, kFeature = 0xB, kEndCollection = 0xC };
enum : int {
  kUsagePage = 0x0,
  kLogicalMin = 0x1,
  kLogicalMax = 0x2,
  kReportSize = 0x7,
  kReportId = 0x8,
  kReportCount = 0x9,
  kPush = 0xA,
  kPop = 0xB
};
enum : int { kUsage = 0x0, kUsageMin = 0x1, kUsageMax = 0x2 };

struct Globals {
  std::uint16_t page = 0;
  std::int32_t logical_min = 0;
  std::int32_t logical_max = 0;
  std::uint32_t logical_max_raw = 0;
  int logical_max_bytes = 0;
  std::uint32_t report_size = 0;
  std::uint32_t report_count = 0;
  int report_id = -1;
};

struct Locals {
  std::vector<std::uint32_t> usages;  // extended: page << 16 | usage
  bool has_min = false, has_max = false;
  std::uint32_t usage_min = 0, usage_max = 0;
};

std::int32_t sign_extend(std::uint32_t v, int bytes) {
  if (bytes == 1) return static_cast<std::int8_t>(v);
  if (bytes == 2) return static_cast<std::int16_t>(v);
  return static_cast<std::int32_t>(v);
}

// A 1- or 2-byte usage is on the current page; a 4-byte one names its own
// (HID 1.11, 6.2.2.8).
std::uint32_t extended(std::uint32_t v, int bytes, std::uint16_t page) {
  return bytes == 4 ? v : (static_cast<std::uint32_t>(page) << 16) | (v & 0xFFFF);
}

class Parser {
 public:
  explicit Parser(std::span<const std::uint8_t> d) : d_(d) { offsets_.fill(0); }

  std::vector<HidInputField> run() {
    std::size_t i = 0;
    while (i < d_.size()) {
      at_ = i;
      const std::uint8_t prefix = d_[i];
      if (prefix == 0xFE) {  // long item: size, tag, data (6.2.2.3); none are defined
        if (i + 1 >= d_.size()) fail(prefix, "a long item's size byte");
        const std::size_t n = d_[i + 1];
        if (i + 3 + n > d_.size())
          fail(prefix, "a long item's " + std::to_string(n) + " data bytes");
        i += 3 + n;
        continue;
      }
      const int bytes = (prefix & 3) == 3 ? 4 : prefix & 3;
      if (i + 1 + static_cast<std::size_t>(bytes) > d_.size()) {
        fail(prefix,
             std::to_string(bytes) + " data bytes, " + std::to_string(d_.size() - i - 1) + " left");
      }
      std::uint32_t v = 0;
      for (int b = 0; b < bytes; ++b) v |= static_cast<std::uint32_t>(d_[i + 1 + b]) << (8 * b);
      item(prefix, (prefix >> 2) & 3, prefix >> 4, v, bytes);
      i += 1 + static_cast<std::size_t>(bytes);
    }
    at_ = d_.size();
    if (!collections_.empty()) fail(0, "an End Collection for each Collection before the end");
    return std::move(fields_);
  }

 private:
  [[noreturn]] void fail(std::uint8_t prefix, const std::string& expected) const {
    char item[8];
    std::snprintf(item, sizeof item, "0x%02X", prefix);
    throw std::invalid_argument("HID report descriptor: byte " + std::to_string(at_) +
                                (at_ < d_.size() ? std::string(", item ") + item : "") +
                                ": expected " + expected);
  }

  void item(std::uint8_t prefix, int type, int tag, std::uint32_t v, int bytes) {
    if (type == kMain) {
      main_item(prefix, tag, v);
      locals_ = Locals{};  // local items last until the next main item (6.2.2.8)
    } else if (type == kGlobal) {
      global_item(prefix, tag, v, bytes);
    } else if (type == kLocal) {
      local_item(prefix, tag, v, bytes);
    } else {
      fail(prefix, "a main, global or local item (type 3 is reserved)");
    }
  }

  void global_item(std::uint8_t prefix, int tag, std::uint32_t v, int bytes) {
    switch (tag) {
      case kUsagePage:
        g_.page = static_cast<std::uint16_t>(v);
        break;
      case kLogicalMin:
        g_.logical_min = sign_extend(v, bytes);
        break;
      case kLogicalMax:
        g_.logical_max_raw = v;
        g_.logical_max_bytes = bytes;
        break;
      case kReportSize:
        if (v > kMaxReportSize) fail(prefix, "Report Size 0..256, got " + std::to_string(v));
        g_.report_size = v;
        break;
      case kReportId:
        if (v < 1 || v > 255) fail(prefix, "Report ID 1..255, got " + std::to_string(v));
        g_.report_id = static_cast<int>(v);
        break;
      case kReportCount:
        if (v > kMaxReportCount) fail(prefix, "Report Count 0..4096, got " + std::to_string(v));
        g_.report_count = v;
        break;
      case kPush:
        if (stack_.size() >= kMaxPushDepth) fail(prefix, "at most 16 nested Push");
        stack_.push_back(g_);
        break;
      case kPop:
        if (stack_.empty()) fail(prefix, "a Push before this Pop");
        g_ = stack_.back();
        stack_.pop_back();
        break;
      default:
        break;  // physical range, units: not needed to decode
    }
  }

  void local_item(std::uint8_t prefix, int tag, std::uint32_t v, int bytes) {
    if (tag == kUsage) {
      if (locals_.usages.size() >= kMaxUsages) fail(prefix, "at most 4096 usages per main item");
      locals_.usages.push_back(extended(v, bytes, g_.page));
    } else if (tag == kUsageMin) {
      locals_.has_min = true;
      locals_.usage_min = extended(v, bytes, g_.page);
    } else if (tag == kUsageMax) {
      locals_.has_max = true;
      locals_.usage_max = extended(v, bytes, g_.page);
    }
  }

  // Logical Maximum is signed too, but devices with a non-negative minimum
  // often write e.g. 0x25 0xFF for 255; like the Linux HID core
  // (drivers/hid/hid-core.c, hid_parser_global) it is read unsigned then.
  std::int32_t logical_max() const {
    if (g_.logical_min < 0) return sign_extend(g_.logical_max_raw, g_.logical_max_bytes);
    return static_cast<std::int32_t>(g_.logical_max_raw);
  }

  void main_item(std::uint8_t prefix, int tag, std::uint32_t v) {
    switch (tag) {
      case kCollection: {
        if (collections_.size() >= kMaxCollectionDepth)
          fail(prefix, "at most 32 nested Collections");
        const std::uint32_t usage = locals_.usages.empty() ? 0 : locals_.usages.front();
        if (collections_.empty()) application_ = usage;
        collections_.push_back(usage);
        (void)v;
        break;
      }
      case kEndCollection:
        if (collections_.empty()) fail(prefix, "a Collection before this End Collection");
        collections_.pop_back();
        break;
      case kInput:
        input(prefix, v);
        break;
      case kOutput:
      case kFeature:
        break;  // not in input reports
      default:
        fail(prefix, "Input, Output, Feature, Collection or End Collection");
    }
  }

  void expand_usage_range(std::uint8_t prefix) {
    if (!locals_.has_min && !locals_.has_max) return;
    if (!locals_.has_min || !locals_.has_max || locals_.usage_max < locals_.usage_min) {
      fail(prefix, "Usage Minimum and Usage Maximum, minimum <= maximum");
    }
    for (std::uint32_t u = locals_.usage_min;
         u <= locals_.usage_max && locals_.usages.size() < kMaxUsages; ++u) {
      locals_.usages.push_back(u);
      if (u == 0xFFFFFFFFu) break;
    }
  }

  void input(std::uint8_t prefix, std::uint32_t flags) {
    const int id = g_.report_id;
    const int slot = id < 0 ? 0 : id;
    const auto bits = static_cast<int>(g_.report_size * g_.report_count);
    if (offsets_[slot] + bits > kMaxReportBits) fail(prefix, "an input report of at most 8 KiB");
    const bool constant = (flags & 0x01) != 0;
    if (!constant && g_.report_size >= 1 && g_.report_size <= 32) {
      expand_usage_range(prefix);
      const std::int32_t lmax = logical_max();
      for (std::uint32_t k = 0; k < g_.report_count; ++k) {
        if (fields_.size() >= kMaxFields) fail(prefix, "at most 4096 input fields");
        HidInputField f;
        f.report_id = id;
        f.bit_offset = offsets_[slot] + static_cast<int>(k * g_.report_size);
        f.bit_size = static_cast<int>(g_.report_size);
        // Each field takes the next usage; the last one repeats (6.2.2.8).
        const std::uint32_t u =
            locals_.usages.empty()
                ? 0
                : locals_.usages[std::min<std::size_t>(k, locals_.usages.size() - 1)];
        f.page = static_cast<std::uint16_t>(u >> 16);
        f.usage = static_cast<std::uint16_t>(u & 0xFFFF);
        f.logical_min = g_.logical_min;
        f.logical_max = lmax;
        f.is_variable = (flags & 0x02) != 0;
        f.is_relative = (flags & 0x04) != 0;
        f.has_null_state = (flags & 0x40) != 0;
        f.application = application_;
        fields_.push_back(f);
      }
    }
    offsets_[slot] += bits;
  }

  std::span<const std::uint8_t> d_;
  std::size_t at_ = 0;
  Globals g_;
  Locals locals_;
  std::vector<Globals> stack_;
  std::vector<std::uint32_t> collections_;
  std::uint32_t application_ = 0;
  std::array<int, 256> offsets_{};  // next bit per report id (0: no id)
  std::vector<HidInputField> fields_;
};

}  // namespace

std::vector<HidInputField> parse_hid_descriptor(std::span<const std::uint8_t> descriptor) {
  return Parser(descriptor).run();
}

}  // namespace facectl
