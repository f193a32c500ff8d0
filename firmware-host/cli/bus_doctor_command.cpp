#include "firmware-host/cli/bus_doctor_command.hpp"

#include <cstdio>
#include <memory>
#include <stdexcept>
#include <vector>

#include "drivers/bus_doctor.hpp"
#include "drivers/can/socketcan_transport.hpp"
#include "drivers/i2c/i2c_dev_transport.hpp"
#include "drivers/i2c/pca9685_doctor.hpp"
#include "firmware-host/config/head_config.hpp"
#include "firmware-host/config/loaded_config.hpp"
#include "firmware-host/config/rig_config.hpp"
#include "firmware-host/config/runtime_config.hpp"
#include "firmware-host/model/bus_budget_check.hpp"

namespace facectl {
namespace {

using Level = DoctorFinding::Level;

DoctorReport with_wire_time(DoctorReport r, const BusBudgetResult& budget) {
  r.findings.insert(r.findings.begin(),
                    {budget.verdict == BusBudgetResult::Verdict::kOk ? Level::kOk : Level::kWarning,
                     "wire time: " + budget.text});
  return r;
}

DoctorReport diagnose(const BusConfig& bus, const std::vector<ActuatorModel>& actuators,
                      const BusBudgetResult& budget, const BusDoctorOptions& options,
                      double tick_hz) {
  if (bus.is_pca9685()) {
    DoctorReport r;
    try {
      I2cDevTransport transport(bus.endpoint);
      r = diagnose_pca9685(bus.name, transport, actuators, bus.pca9685, options.samples);
    } catch (const std::runtime_error& e) {
      r.bus = bus.name + " (PCA9685 on " + bus.endpoint + ")";
      r.findings.push_back({Level::kProblem, std::string("cannot open: ") + e.what()});
    }
    r.findings.insert(
        r.findings.begin(),
        {budget.verdict == BusBudgetResult::Verdict::kOk ? Level::kOk : Level::kWarning,
         "wire time: " + budget.text});
    return r;
  }
  if (bus.is_modbus()) {
    DoctorReport r =
        diagnose_modbus(bus.name, ModbusEndpoint::parse(bus.type, bus.endpoint, bus.bitrate),
                        actuators, bus.modbus, options.samples, bus.modbus_registers);
    if (bus.type == "modbus_rtu") {
      r.findings.insert(
          r.findings.begin(),
          {budget.verdict == BusBudgetResult::Verdict::kOk ? Level::kOk : Level::kWarning,
           "wire time: " + budget.text});
    }
    return r;
  }
  // The serial buses: their wire-time budget first.
  if (bus.is_dynamixel()) {
    return with_wire_time(diagnose_dynamixel(bus.name, bus.endpoint, bus.bitrate, actuators,
                                             bus.dynamixel, options.samples),
                          budget);
  }
  if (bus.is_feetech()) {
    return with_wire_time(diagnose_feetech(bus.name, bus.endpoint, bus.bitrate, actuators,
                                           bus.feetech, options.samples),
                          budget);
  }
  if (bus.is_maestro()) {
    return with_wire_time(diagnose_maestro(bus.name, bus.endpoint, bus.bitrate, actuators,
                                           bus.maestro, options.samples),
                          budget);
  }
  std::unique_ptr<SocketCanTransport> transport;
  try {
    transport = std::make_unique<SocketCanTransport>(bus.endpoint, bus.can.fd);
  } catch (const std::runtime_error& e) {
    DoctorReport r;
    r.bus =
        bus.name + " (CAN, " + bus.can_protocol + ", " + std::to_string(bus.bitrate) + " bit/s)";
    r.findings.push_back({budget.verdict == BusBudgetResult::Verdict::kRefused   ? Level::kProblem
                          : budget.verdict == BusBudgetResult::Verdict::kWarning ? Level::kWarning
                                                                                 : Level::kOk,
                          "load: " + budget.text});
    r.findings.push_back({Level::kProblem, std::string("cannot open: ") + e.what()});
    return r;
  }
  return diagnose_can(bus.name, *transport, bus.can_protocol, actuators, bus.can, tick_hz,
                      bus.bitrate, options.listen_s);
}

}  // namespace

int bus_doctor_command(const BusDoctorOptions& options) {
  RuntimeConfig runtime;
  RigConfig rig;
  std::vector<BusBudgetResult> budgets;
  try {
    if (options.samples < 1 || options.samples > 10000) {
      throw ConfigError("--samples: expected 1..10000, found " + std::to_string(options.samples));
    }
    if (!(options.listen_s > 0.0 && options.listen_s <= 60.0)) {
      throw ConfigError("--listen: expected seconds in (0, 60]");
    }
    runtime = load_runtime_config(options.config.empty() ? default_config_path() : options.config);
    const HeadConfig head = load_head_config(runtime.head_path);
    rig = load_rig_config(options.rig.empty() ? runtime.rig_path : options.rig, head.layout);
    budgets = check_bus_budgets(rig, runtime.rate_hz);
    if (!options.bus.empty()) {
      bool found = false;
      for (const auto& b : rig.buses) found = found || b.name == options.bus;
      if (!found) {
        throw ConfigError("--bus: expected a bus of rig '" + rig.name + "', found '" + options.bus +
                          "'");
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "facectl bus doctor: %s\n", e.what());
    return 2;
  }

  std::printf("facectl bus doctor: rig %s (%s), loop %g Hz\n", rig.name.c_str(), rig.file.c_str(),
              runtime.rate_hz);
  bool problems = false;
  for (std::size_t i = 0; i < rig.buses.size(); ++i) {
    const BusConfig& bus = rig.buses[i];
    if (!options.bus.empty() && bus.name != options.bus) continue;
    std::vector<ActuatorModel> actuators;
    for (const ActuatorConfig& a : rig.actuators) {
      if (a.model.bus == bus.name) actuators.push_back(a.model);
    }
    DoctorReport report;
    try {
      report = diagnose(bus, actuators, budgets[i], options, runtime.rate_hz);
    } catch (const std::invalid_argument& e) {
      std::fprintf(stderr, "facectl bus doctor: %s: bus %s: %s\n", bus.where.c_str(),
                   bus.name.c_str(), e.what());
      return 2;
    }
    std::fputs(report.to_text().c_str(), stdout);
    problems = problems || report.has_problems();
  }
  std::printf("%s\n", problems ? "problems found" : "no problems found");
  return problems ? 1 : 0;
}

}  // namespace facectl
