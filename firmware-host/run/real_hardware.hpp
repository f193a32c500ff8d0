#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "control/actuator_bus.hpp"
#include "control/controller_model.hpp"
#include "drivers/bus_factory.hpp"
#include "drivers/gpio/gpio_safety_io.hpp"
#include "firmware-host/config/loaded_config.hpp"

namespace facectl {

// The real hardware of a rig: one real bus per configured bus (make_bus:
// SocketCAN or libmodbus) and the GPIO safety I/O of the runtime file's
// `safety_io:` block. Nothing is enabled by building it.
struct RealHardware {
  GpioHardware gpio;
  std::vector<RealBus> buses;       // in the controller's bus order
  std::vector<ActuatorBus*> seams;  // the same buses, as the controller sees them
  std::vector<std::string> notes;   // one line per bus (its budget, its boards), to print

  SafetyIo& io() { return *gpio.io; }
};

// Opens a GPIO chip for the safety I/O; tests pass one that returns a simulated chip.
using GpioOpener = std::function<GpioHardware(const std::string& chip, const GpioSafetyConfig&)>;

// Builds and opens everything, then checks that each Modbus bus's boards
// answer (within a few fault_after_ms). Throws ConfigError when the
// configuration cannot drive real hardware (no safety_io block), and
// std::runtime_error naming the bus, device or chip that cannot be opened or
// does not answer. Actuators start at their rest positions until the hardware
// reports.
std::unique_ptr<RealHardware> make_real_hardware(const ControllerModel& model,
                                                 const LoadedConfig& config,
                                                 const GpioOpener& open_gpio = make_gpio_safety_io);

}  // namespace facectl
