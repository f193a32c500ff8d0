// CAN frames into the custom-board driver (CustomCanBus, docs/PROTOCOLS.md
// "CAN: custom boards"): feedback frames, other traffic and error frames, as
// its read() takes them from the transport each tick.
#include <stdexcept>

#include "drivers/can/custom_can_bus.hpp"
#include "tests/fuzz/can_fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace facectl;
  FuzzedDataProvider in(data, size);
  CanBusOptions options;
  options.fd = in.ConsumeBool();
  options.width = in.ConsumeBool() ? custom_can::Width::kInt16 : custom_can::Width::kInt32;
  options.cycle_divider = in.ConsumeIntegralInRange(1, 3);
  const std::vector<ActuatorModel> actuators = fuzz::consume_actuators(in, 64);
  fuzz::ScriptedCanTransport link;
  try {
    CustomCanBus bus("fuzz", link, actuators, std::vector<double>(actuators.size()), options);
    fuzz::run_bus(in, bus, link, actuators.size(), {custom_can::kFeedbackBase});
  } catch (const std::invalid_argument&) {  // addresses or encodings a rig file cannot pass
  }
  return 0;
}
