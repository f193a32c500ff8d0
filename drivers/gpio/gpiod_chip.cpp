#include "drivers/gpio/gpiod_chip.hpp"

#include <fcntl.h>
#include <gpiod.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace facectl {

namespace {
[[noreturn]] void fail(const std::string& what) {
  throw std::runtime_error("GPIO " + what + ": " + std::strerror(errno));
}
}  // namespace

GpiodChip::GpiodChip(const std::string& chip) : name_(chip) {
  chip_ = gpiod_chip_open_lookup(chip.c_str());
  if (chip_ == nullptr) fail("chip '" + chip + "' cannot be opened");
}

GpiodChip::~GpiodChip() {
  for (gpiod_line* l : lines_) gpiod_line_release(l);
  if (chip_ != nullptr) gpiod_chip_close(chip_);
}

gpiod_line* GpiodChip::line(unsigned offset) {
  gpiod_line* l = gpiod_chip_get_line(chip_, offset);
  if (l == nullptr) fail(name_ + " line " + std::to_string(offset) + " does not exist");
  return l;
}

int GpiodChip::request_input(unsigned offset, bool active_low, const char* consumer) {
  gpiod_line* l = line(offset);
  const int flags = active_low ? GPIOD_LINE_REQUEST_FLAG_ACTIVE_LOW : 0;
  if (gpiod_line_request_both_edges_events_flags(l, consumer, flags) != 0) {
    fail(name_ + " line " + std::to_string(offset) + " cannot be requested for edge events");
  }
  const int fd = gpiod_line_event_get_fd(l);
  if (fd < 0 || fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) | O_NONBLOCK) != 0) {
    gpiod_line_release(l);
    fail(name_ + " line " + std::to_string(offset) + ": event fd");
  }
  lines_.push_back(l);
  return static_cast<int>(lines_.size() - 1);
}

int GpiodChip::request_output(unsigned offset, bool active_low, bool initial,
                              const char* consumer) {
  gpiod_line* l = line(offset);
  const int flags = active_low ? GPIOD_LINE_REQUEST_FLAG_ACTIVE_LOW : 0;
  if (gpiod_line_request_output_flags(l, consumer, flags, initial ? 1 : 0) != 0) {
    fail(name_ + " line " + std::to_string(offset) + " cannot be requested as an output");
  }
  lines_.push_back(l);
  return static_cast<int>(lines_.size() - 1);
}

int GpiodChip::read_edges(int handle, std::span<GpioEdge> out) {
  gpiod_line_event events[16];
  const auto want = static_cast<unsigned>(std::min<std::size_t>(out.size(), 16));
  const int n =
      gpiod_line_event_read_multiple(lines_[static_cast<std::size_t>(handle)], events, want);
  if (n < 0) return errno == EAGAIN ? 0 : -1;  // the fd is non-blocking: EAGAIN = nothing queued
  for (int i = 0; i < n; ++i) {
    // v1 reports edges of the logical value: rising = became active.
    out[static_cast<std::size_t>(i)].active = events[i].event_type == GPIOD_LINE_EVENT_RISING_EDGE;
  }
  return n;
}

int GpiodChip::get_value(int handle) {
  return gpiod_line_get_value(lines_[static_cast<std::size_t>(handle)]);
}

bool GpiodChip::set_value(int handle, bool active) {
  return gpiod_line_set_value(lines_[static_cast<std::size_t>(handle)], active ? 1 : 0) == 0;
}

}  // namespace facectl
