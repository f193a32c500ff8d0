#include "firmware-host/config/hardware_config.hpp"

#include <cmath>

#include "drivers/hid/gamepad_descriptor_layout.hpp"

namespace facectl {
namespace {

bool parse_level(const ConfigNode& node) {  // true = active low
  const std::string s = node.string();
  if (s == "high") return false;
  if (s == "low") return true;
  node.fail("high or low");
}

int find_name(const ConfigNode& at, const std::string& name, const std::vector<std::string>& names,
              const char* what) {
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i] == name) return static_cast<int>(i);
  }
  std::string list;
  for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
  at.fail(std::string("the name of one of the gamepad's ") + what + " (" + list + ")",
          "'" + name + "'");
}

}  // namespace

HardwareMode parse_hardware_mode(const ConfigNode& node) {
  const std::string s = node.string();
  if (s == "sim") return HardwareMode::kSim;
  if (s == "real") return HardwareMode::kReal;
  node.fail("sim or real");
}

SafetyIoConfig parse_safety_io(const ConfigNode& node) {
  node.expect_keys({"chip", "estop_line", "estop_active", "release_debounce_ms", "power_line",
                    "power_active", "led_line", "led_active"});
  SafetyIoConfig cfg;
  cfg.where = node.where();
  GpioSafetyConfig& g = cfg.gpio;
  if (auto n = node.get("chip")) cfg.chip = n->string();
  g.estop_line = static_cast<unsigned>(node["estop_line"].integer_in(0, 1023));
  if (auto n = node.get("estop_active")) g.estop_active_low = parse_level(*n);
  if (auto n = node.get("release_debounce_ms"))
    g.release_debounce_s = n->number_in(0.0, 1000.0) * 1e-3;
  g.power_line = static_cast<unsigned>(node["power_line"].integer_in(0, 1023));
  if (auto n = node.get("power_active")) g.power_active_low = parse_level(*n);
  if (auto n = node.get("led_line")) g.led_line = static_cast<int>(n->integer_in(0, 1023));
  if (auto n = node.get("led_active")) g.led_active_low = parse_level(*n);
  if (g.power_line == g.estop_line) {
    node["power_line"].fail("a line other than estop_line", node["power_line"].found());
  }
  if (g.led_line >= 0 && (static_cast<unsigned>(g.led_line) == g.estop_line ||
                          static_cast<unsigned>(g.led_line) == g.power_line)) {
    node["led_line"].fail("a line other than estop_line and power_line", node["led_line"].found());
  }
  return cfg;
}

GamepadConfig parse_gamepad(const ConfigNode& node) {
  node.expect_keys({"path", "vendor", "product", "report_id", "rate_hz", "axes", "buttons", "map"});
  GamepadConfig cfg;
  cfg.where = node.where();
  if (auto n = node.get("path")) cfg.selector.path = n->string();
  if (auto n = node.get("vendor"))
    cfg.selector.vendor = static_cast<std::uint16_t>(n->integer_in(1, 0xFFFF));
  if (auto n = node.get("product"))
    cfg.selector.product = static_cast<std::uint16_t>(n->integer_in(1, 0xFFFF));
  if (cfg.selector.path.empty() && (cfg.selector.vendor == 0 || cfg.selector.product == 0)) {
    node.fail("either path, or vendor and product", "neither");
  }
  if (auto n = node.get("report_id"))
    cfg.layout.report_id = static_cast<int>(n->integer_in(-1, 255));
  if (auto n = node.get("rate_hz")) cfg.rate_hz = n->number_in(10.0, 1000.0);

  std::vector<std::string> axis_names, button_names;
  // Without axes and buttons the device's report descriptor decides, at each
  // open, into slots whose names are known now.
  if (!node.has("axes") && !node.has("buttons")) {
    axis_names.assign(kDescriptorAxisNames.begin(), kDescriptorAxisNames.end());
    for (int b = 1; b <= kDescriptorButtons; ++b) button_names.push_back(descriptor_button_name(b));
  }
  if (auto axes = node.get("axes")) {
    const auto items = axes->items();
    if (items.size() > kMaxGamepadAxes) axes->fail("at most 16 axes");
    for (const ConfigNode& a : items) {
      a.expect_keys({"name", "byte", "bit", "bits", "signed", "min", "max"});
      GamepadLayout::Axis axis;
      axis.name = a["name"].string();
      axis.byte = static_cast<int>(a["byte"].integer_in(0, 63));
      if (auto n = a.get("bit")) axis.bit = static_cast<int>(n->integer_in(0, 7));
      if (auto n = a.get("bits")) axis.bits = static_cast<int>(n->integer_in(1, 32));
      if (axis.byte * 8 + axis.bit + axis.bits > 64 * 8) {
        a["byte"].fail("a field that ends within 64 bytes (byte * 8 + bit + bits <= 512)",
                       a["byte"].found());
      }
      if (auto n = a.get("signed")) axis.is_signed = n->boolean();
      // The full raw range: symmetric when signed (-127..127 for 8 bits).
      const double top = std::ldexp(1.0, axis.bits - (axis.is_signed ? 1 : 0)) - 1.0;
      axis.min = axis.is_signed ? -top : 0.0;
      axis.max = top;
      if (auto n = a.get("min")) axis.min = n->number();
      if (auto n = a.get("max")) axis.max = n->number();
      if (!(axis.min < axis.max)) a.fail("min < max");
      for (const auto& other : axis_names) {
        if (other == axis.name) a["name"].fail("a unique axis name", "'" + axis.name + "' again");
      }
      axis_names.push_back(axis.name);
      cfg.layout.axes.push_back(axis);
    }
  }
  if (auto buttons = node.get("buttons")) {
    const auto items = buttons->items();
    if (items.size() > 32) buttons->fail("at most 32 buttons");
    for (const ConfigNode& b : items) {
      b.expect_keys({"name", "byte", "bit"});
      GamepadLayout::Button button;
      button.name = b["name"].string();
      button.byte = static_cast<int>(b["byte"].integer_in(0, 63));
      button.bit = static_cast<int>(b["bit"].integer_in(0, 7));
      for (const auto& other : button_names) {
        if (other == button.name)
          b["name"].fail("a unique button name", "'" + button.name + "' again");
      }
      button_names.push_back(button.name);
      cfg.layout.buttons.push_back(button);
    }
  }
  const auto rows = node["map"].items();
  if (rows.empty()) node["map"].fail("at least one mapping entry", "an empty list");
  for (const ConfigNode& m : rows) {
    m.expect_keys({"axis", "button", "signal", "gain", "offset", "dead_zone"});
    GamepadConfig::PendingTerm p;
    if (m.has("axis") == m.has("button")) m.fail("exactly one of axis or button");
    if (auto n = m.get("axis")) {
      p.term.source = GamepadTerm::Source::kAxis;
      p.term.input = static_cast<std::size_t>(find_name(*n, n->string(), axis_names, "axes"));
      if (auto d = m.get("dead_zone")) p.term.dead_zone = d->number_in(0.0, 0.9);
    } else {
      const ConfigNode b = m["button"];
      p.term.source = GamepadTerm::Source::kButton;
      p.term.input = static_cast<std::size_t>(find_name(b, b.string(), button_names, "buttons"));
      if (m.has("dead_zone")) m["dead_zone"].fail("dead_zone only on an axis", "a button");
    }
    p.signal_node = m["signal"];
    p.signal_key = p.signal_node->string();
    p.term.gain = m.get("gain") ? m["gain"].number() : 1.0;
    p.term.offset = m.get("offset") ? m["offset"].number() : 0.0;
    cfg.pending.push_back(std::move(p));
  }
  return cfg;
}

void resolve_gamepad_terms(GamepadConfig& gamepad, const FaceLayout& layout) {
  gamepad.terms.clear();
  for (const auto& p : gamepad.pending) {
    const auto index = layout.find_yaml_key(p.signal_key);
    if (!index) {
      p.signal_node->fail(
          "a face signal of the head (muscle name, jaw_pitch_deg, eyelid_closure_l, ...)",
          "unknown signal '" + p.signal_key + "'");
    }
    GamepadTerm t = p.term;
    const double to_si = yaml_to_si(layout.signal(*index).kind);
    t.signal = *index;
    t.gain *= to_si;
    t.offset *= to_si;
    gamepad.terms.push_back(t);
  }
}

}  // namespace facectl
