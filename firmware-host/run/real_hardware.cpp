#include "firmware-host/run/real_hardware.hpp"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <thread>

#include "drivers/dynamixel/dynamixel_bus.hpp"
#include "drivers/feetech/feetech_bus.hpp"
#include "drivers/maestro/maestro_bus.hpp"
#include "drivers/modbus/modbus_bus.hpp"

namespace facectl {
namespace {

// Waits until every board of a Modbus bus has answered, or its fault timeout
// has passed twice; a bus whose boards stay silent cannot be driven.
void check_modbus_answers(const ModbusBus& bus, const ModbusTiming& timing) {
  const auto limit = std::chrono::steady_clock::now() +
                     std::chrono::duration<double>(2.0 * timing.board_timeout_s + 0.2);
  while (std::chrono::steady_clock::now() < limit) {
    if (bus.boards_answered() == bus.board_count() && !bus.status().fault) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  const BusStatus s = bus.status();
  // The fault reason names the bus and board already.
  throw std::runtime_error(s.fault ? std::string(s.reason)
                                   : std::string(bus.name()) + ": " +
                                         std::to_string(bus.board_count() - bus.boards_answered()) +
                                         " of its boards do not answer");
}

// Waits until a serial servo bus is ready (DYNAMIXEL, Feetech: every servo
// set up, without a hardware error; Maestro: a whole cycle answered with no
// error bits), or a fault names what is not; `not_ready` otherwise.
template <typename Bus>
void check_ready(const Bus& bus, double fault_after_s, const char* not_ready) {
  const auto limit =
      std::chrono::steady_clock::now() + std::chrono::duration<double>(2.0 * fault_after_s + 0.5);
  while (std::chrono::steady_clock::now() < limit) {
    if (bus.ready() && !bus.status().fault) return;
    if (bus.status().fault) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  const BusStatus s = bus.status();
  throw std::runtime_error(s.fault ? std::string(s.reason)
                                   : std::string(bus.name()) + ": " + not_ready);
}

}  // namespace

std::unique_ptr<RealHardware> make_real_hardware(const ControllerModel& model,
                                                 const LoadedConfig& config,
                                                 const GpioOpener& open_gpio) {
  if (!config.runtime.safety_io) {
    throw ConfigError(config.runtime.file +
                      ": hardware: real: expected a safety_io block (the e-stop input and the "
                      "power-enable output), found none; nothing is enabled without an e-stop");
  }
  auto hw = std::make_unique<RealHardware>();
  for (const BusModel& bm : model.buses) {
    const auto it = std::find_if(config.rig.buses.begin(), config.rig.buses.end(),
                                 [&](const BusConfig& b) { return b.name == bm.name; });
    if (it == config.rig.buses.end()) {
      throw std::logic_error("bus " + bm.name + " of the model is not in the rig");
    }
    const std::vector<ActuatorModel> actuators(
        model.actuators.begin() + static_cast<long>(bm.first),
        model.actuators.begin() + static_cast<long>(bm.first + bm.count));
    std::vector<double> initial;
    for (const ActuatorModel& a : actuators) initial.push_back(a.rest);
    try {
      hw->buses.push_back(make_bus(*it, actuators, initial, model.rate_hz));
    } catch (const std::invalid_argument& e) {
      throw ConfigError(it->where + ": rig.buses '" + it->name + "': " + e.what());
    } catch (const std::runtime_error& e) {
      throw std::runtime_error("bus " + it->name + ": " + e.what());
    }
    RealBus& rb = hw->buses.back();
    if (auto* mb = dynamic_cast<ModbusBus*>(rb.bus.get())) {
      check_modbus_answers(*mb, it->modbus);
      hw->notes.push_back(it->name + ": " + std::to_string(mb->board_count()) +
                          " Modbus boards answer at " + it->endpoint);
    } else if (auto* db = dynamic_cast<DynamixelBus*>(rb.bus.get())) {
      check_ready(*db, it->dynamixel.fault_after_s, "its servos are not all set up");
      hw->notes.push_back(it->name + ": " + std::to_string(actuators.size()) +
                          " DYNAMIXEL servos set up at " + it->endpoint);
    } else if (auto* ma = dynamic_cast<MaestroBus*>(rb.bus.get())) {
      check_ready(*ma, it->maestro.fault_after_s, "the Maestro does not answer");
      hw->notes.push_back(it->name + ": a Maestro with " + std::to_string(actuators.size()) +
                          " channels answers at " + it->endpoint);
    } else if (auto* fb = dynamic_cast<FeetechBus*>(rb.bus.get())) {
      check_ready(*fb, it->feetech.fault_after_s, "its servos are not all set up");
      hw->notes.push_back(it->name + ": " + std::to_string(actuators.size()) +
                          " Feetech servos set up at " + it->endpoint);
    } else {
      hw->notes.push_back(rb.budget + " on " + it->endpoint);
    }
    hw->seams.push_back(rb.bus.get());
  }
  const SafetyIoConfig& sio = *config.runtime.safety_io;
  hw->gpio = open_gpio(sio.chip, sio.gpio);
  // The e-stop reads pressed until its line has been released for the
  // debounce time; a run must not start (and latch ESTOP) inside that window.
  const auto settle = std::chrono::steady_clock::now() +
                      std::chrono::duration<double>(sio.gpio.release_debounce_s + 0.1);
  while (hw->gpio.io->estop_active() && std::chrono::steady_clock::now() < settle) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  if (hw->gpio.io->estop_active()) {
    throw std::runtime_error("safety I/O: the e-stop (" + sio.chip + " line " +
                             std::to_string(sio.gpio.estop_line) +
                             ") reads pressed: release it (or check estop_active) and start again");
  }
  hw->notes.push_back("safety I/O on " + sio.chip + ": e-stop line " +
                      std::to_string(sio.gpio.estop_line) + ", power-enable line " +
                      std::to_string(sio.gpio.power_line));
  return hw;
}

}  // namespace facectl
