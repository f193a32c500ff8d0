#pragma once

#include <string>
#include <vector>

#include "drivers/gpio/gpio_chip.hpp"

struct gpiod_chip;
struct gpiod_line;

namespace facectl {

// A GPIO chip through libgpiod's v1 API (Debian 12: libgpiod 1.6). Input
// lines are requested for both edges, with their event fd made non-blocking
// so that read_edges() never waits.
class GpiodChip final : public GpioChip {
 public:
  // `chip` is a name ("gpiochip0"), a number or a path, as gpiod_chip_open_lookup
  // takes it. Throws std::runtime_error naming it.
  explicit GpiodChip(const std::string& chip);
  ~GpiodChip() override;
  GpiodChip(const GpiodChip&) = delete;
  GpiodChip& operator=(const GpiodChip&) = delete;

  int request_input(unsigned offset, bool active_low, const char* consumer) override;
  int request_output(unsigned offset, bool active_low, bool initial, const char* consumer) override;
  int read_edges(int handle, std::span<GpioEdge> out) override;
  int get_value(int handle) override;
  bool set_value(int handle, bool active) override;

 private:
  gpiod_line* line(unsigned offset);

  std::string name_;
  gpiod_chip* chip_ = nullptr;
  std::vector<gpiod_line*> lines_;
};

}  // namespace facectl
