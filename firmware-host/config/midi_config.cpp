#include "firmware-host/config/midi_config.hpp"

#include <set>
#include <tuple>
#include <utility>

namespace facectl {

MidiConfig parse_midi_config(const ConfigNode& node) {
  node.expect_keys({"client", "connect", "rate_hz", "controls", "notes"});
  MidiConfig c;
  if (auto n = node.get("client")) {
    c.client = n->string();
    if (c.client.empty() || c.client.size() > 63) n->fail("a client name of 1 to 63 characters");
  }
  if (auto n = node.get("connect")) c.connect = n->string_list();
  if (auto n = node.get("rate_hz")) c.rate_hz = n->number_in(10.0, 1000.0);
  std::set<std::tuple<int, int, std::string>> moved;  // a control may move several signals
  if (auto list = node.get("controls")) {
    for (const ConfigNode& item : list->items()) {
      item.expect_keys({"channel", "cc", "signal", "min", "max"});
      MidiControlRule r;
      r.channel = static_cast<int>(item["channel"].integer_in(1, 16));
      r.cc = static_cast<int>(item["cc"].integer_in(0, 119));
      r.signal = item["signal"].string();
      r.min = item["min"].number();
      r.max = item["max"].number();
      r.where = item.where() + ": " + item.path();
      if (!moved.emplace(r.channel, r.cc, r.signal).second) {
        item["signal"].fail("each signal mapped once per channel and cc");
      }
      c.controls.push_back(std::move(r));
    }
  }
  std::set<std::pair<int, int>> seen;
  if (auto list = node.get("notes")) {
    for (const ConfigNode& item : list->items()) {
      item.expect_keys({"channel", "note", "expression"});
      MidiNoteRule r;
      r.channel = static_cast<int>(item["channel"].integer_in(1, 16));
      r.note = static_cast<int>(item["note"].integer_in(0, 127));
      r.expression = item["expression"].string();
      r.where = item.where() + ": " + item.path();
      if (!seen.emplace(r.channel, r.note).second) {
        item["note"].fail("each channel and note mapped once");
      }
      c.notes.push_back(std::move(r));
    }
  }
  if (c.controls.empty() && c.notes.empty()) {
    node.fail("controls or notes mapped to the face", "neither");
  }
  return c;
}

}  // namespace facectl
