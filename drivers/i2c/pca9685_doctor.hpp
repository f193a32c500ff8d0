#pragma once

#include <string>
#include <vector>

#include "control/actuator_model.hpp"
#include "drivers/bus_doctor.hpp"
#include "drivers/i2c/i2c_transport.hpp"
#include "drivers/i2c/pca9685_options.hpp"

namespace facectl {

// PCA9685: reads each listed board's MODE1, MODE2 and PRE_SCALE `samples`
// times (reads only: a board is never woken or written) and reports whether
// it answers, the read time, its PWM frequency against the configured one,
// an external clock (EXTCLK) and boards listed with no actuator on them.
DoctorReport diagnose_pca9685(const std::string& bus, I2cTransport& transport,
                              const std::vector<ActuatorModel>& actuators,
                              const Pca9685Options& options, int samples = 20);

}  // namespace facectl
