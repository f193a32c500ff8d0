#pragma once

#include <modbus/modbus.h>

#include "drivers/modbus/modbus_timing.hpp"

namespace facectl {

// Sets both of libmodbus's timeouts from `timing`: the response timeout and
// the byte timeout. Left alone, either stays at libmodbus's 500 ms, and a
// peer that sends part of a reply then stalls holds a transaction that long.
void set_modbus_timeouts(modbus_t* ctx, const ModbusTiming& timing);

}  // namespace facectl
