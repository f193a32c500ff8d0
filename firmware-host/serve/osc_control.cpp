#include "firmware-host/serve/osc_control.hpp"

#include <stdexcept>
#include <utility>
#include <variant>

#include "firmware-host/config/ipv4_cidr.hpp"
#include "firmware-host/serve/api_json.hpp"

namespace facectl {
namespace {

constexpr std::size_t kMaxDatagram = 8192;  // control messages are tens of bytes
constexpr std::string_view kSignal = "/facectl/signal/";
constexpr int kRefusalsLoggedPerSecond = 10;  // a runaway sender does not fill the log

// The argument list the address takes, as OSC type letters for the error.
void expect_args(const OscMessage& m, std::size_t min, std::size_t max, const char* what) {
  if (m.args.size() < min || m.args.size() > max) {
    throw std::invalid_argument(m.address + ": expected " + what + ", found " +
                                std::to_string(m.args.size()) + " arguments");
  }
}

// A sender's text as the event log and the API may show it: bytes outside
// printable ASCII as \xNN (liblo does not check UTF-8, and the API's JSON
// must stay valid; a terminal must not take escape sequences from the net).
std::string printable(std::string_view text) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out;
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (u >= 0x20 && u < 0x7f) {
      out.push_back(c);
    } else {
      out += "\\x";
      out.push_back(kHex[u >> 4]);
      out.push_back(kHex[u & 0xf]);
    }
  }
  return out;
}

bool known_address(std::string_view a) {
  return a == "/facectl/expression" || (a.starts_with(kSignal) && a.size() > kSignal.size()) ||
         a == "/facectl/neutral" || a == "/facectl/show/play" || a == "/facectl/show/queue" ||
         a == "/facectl/show/stop";
}

const std::string& string_arg(const OscMessage& m, std::size_t i, const char* what) {
  if (const auto* s = std::get_if<std::string>(&m.args[i])) return *s;
  throw std::invalid_argument(m.address + ": expected " + what + ", found a number");
}

double number_arg(const OscMessage& m, std::size_t i, const char* what) {
  if (const auto* v = std::get_if<double>(&m.args[i])) return *v;
  throw std::invalid_argument(m.address + ": expected " + what + ", found a string");
}

}  // namespace

OscControl::OscControl(HeadService& service, const UdpListenOptions& options)
    : service_(service),
      bounds_(face_bounds(service.head().model())),
      held_(service.head().model().neutral),
      listener_(options, "OSC control", "osc", kMaxDatagram,
                [this](const UdpDatagram& d, std::string_view bytes) { return handle(d, bytes); }) {
}

HeadService::Result OscControl::apply(const OscMessage& m, const std::string& who) {
  const std::string_view a = m.address;
  if (a == "/facectl/expression") {
    expect_args(m, 1, 2, "an expression name and an optional weight 0..1");
    const std::string& name = string_arg(m, 0, "an expression name");
    const double weight = m.args.size() > 1 ? number_arg(m, 1, "a weight 0..1") : 1.0;
    if (!(weight >= 0.0 && weight <= 1.0)) {
      return {422, m.address + ": weight: expected 0..1, found " + std::to_string(weight)};
    }
    HeadService::Result r = service_.hold_expression(who, name, weight);
    if (r.status < 300) held_ = service_.head().model().neutral;
    return r;
  }
  if (a.starts_with(kSignal)) {
    expect_args(m, 1, 1, "one number, the signal's value in its YAML unit");
    const std::string key(a.substr(kSignal.size()));
    const double v = number_arg(m, 0, "the signal's value in its YAML unit");
    std::pair<std::size_t, double> set;
    try {
      set = checked_signal_value(service_.head().model(), bounds_, key, v, m.address);
    } catch (const std::invalid_argument& e) {
      return {422, e.what()};
    }
    FaceDirector::Pose pose = held_;
    pose[set.first] = set.second;
    HeadService::Result r = service_.hold_pose(who, pose, key + "=" + std::to_string(v));
    if (r.status < 300) held_ = std::move(pose);
    return r;
  }
  if (a == "/facectl/neutral") {
    expect_args(m, 0, 0, "no arguments");
    // Whatever holds the face (a show and its queue, an expression, signals): neutral.
    HeadService::Result r = service_.stop_show(who);
    if (r.status < 300)
      r = service_.hold_pose(who, service_.head().model().neutral, "neutral (OSC)");
    if (r.status < 300) held_ = service_.head().model().neutral;
    return r;
  }
  if (a == "/facectl/show/stop") {
    expect_args(m, 0, 0, "no arguments");
    return service_.stop_show(who);  // ends a show; signals set over OSC stay held
  }
  if (a == "/facectl/show/play" || a == "/facectl/show/queue") {
    expect_args(m, 1, 1, "a show name");
    HeadService::Result r =
        service_.play(who, string_arg(m, 0, "a show name"), a == "/facectl/show/queue");
    if (r.status < 300) held_ = service_.head().model().neutral;
    return r;
  }
  throw std::logic_error("OscControl::apply: not an address of the address space");
}

void OscControl::log_refusal(const std::string& who, const std::string& why) {
  const auto now = std::chrono::steady_clock::now();
  if (now - refusal_window_ >= std::chrono::seconds(1)) {
    if (refusals_unlogged_ > 0) {
      service_.log().add("command", who,
                         std::to_string(refusals_unlogged_) + " more refused messages not logged");
    }
    refusal_window_ = now;
    refusals_in_window_ = 0;
    refusals_unlogged_ = 0;
  }
  if (refusals_in_window_ < kRefusalsLoggedPerSecond) {
    ++refusals_in_window_;
    service_.log().add("command", who, "refused: " + why);
  } else {
    ++refusals_unlogged_;
  }
}

std::size_t OscControl::handle(const UdpDatagram& d, std::string_view bytes) {
  const std::uint64_t drops = listener_.new_kernel_drops(d);
  OscStats delta;
  delta.datagrams = 1;
  delta.kernel_drops = drops;
  if (!listener_.allowed(d)) {
    delta.refused_senders = 1;
  } else {
    const std::string who = "osc " + ipv4_text(d.address) + ":" + std::to_string(d.port);
    std::vector<OscMessage> messages;
    try {
      if (bytes.size() > kMaxDatagram) {
        throw OscFormatError("expected a datagram of at most " + std::to_string(kMaxDatagram) +
                             " bytes, found a longer one");
      }
      messages = decode_osc_datagram(bytes);
    } catch (const OscFormatError& e) {
      delta.malformed = 1;
      delta.last_error = who + ": " + printable(e.what());
    }
    for (const OscMessage& m : messages) {
      ++delta.messages;
      if (!known_address(m.address)) {
        ++delta.unknown_address;
        const std::string why = printable(m.address) + ": no such address";
        delta.last_error = who + ": " + why + " (docs/INPUTS.md, \"OSC\")";
        log_refusal(who, why);
        continue;
      }
      HeadService::Result r;
      try {
        r = apply(m, who);
      } catch (const std::invalid_argument& e) {
        r = {400, e.what()};
      }
      if (r.status < 300) {
        ++delta.applied;
      } else {
        ++delta.refused;
        const std::string why = printable(r.error);
        delta.last_error = who + ": " + why;
        log_refusal(who, why);
      }
    }
  }
  std::lock_guard lock(mutex_);
  stats_.datagrams += delta.datagrams;
  stats_.messages += delta.messages;
  stats_.applied += delta.applied;
  stats_.refused += delta.refused;
  stats_.malformed += delta.malformed;
  stats_.unknown_address += delta.unknown_address;
  stats_.refused_senders += delta.refused_senders;
  stats_.kernel_drops += delta.kernel_drops;
  if (!delta.last_error.empty()) stats_.last_error = delta.last_error;
  return delta.applied;
}

std::string describe(const OscStats& s) {
  std::string out = std::to_string(s.datagrams) + " datagrams, " + std::to_string(s.messages) +
                    " messages, " + std::to_string(s.applied) + " applied, " +
                    std::to_string(s.refused) + " refused, " + std::to_string(s.malformed) +
                    " malformed, " + std::to_string(s.unknown_address) + " to unknown addresses, " +
                    std::to_string(s.refused_senders) + " from senders off the allow list, " +
                    std::to_string(s.kernel_drops) + " dropped by the kernel";
  if (!s.last_error.empty()) out += "; last error: " + s.last_error;
  return out;
}

OscStats OscControl::stats() const {
  std::lock_guard lock(mutex_);
  return stats_;
}

}  // namespace facectl
