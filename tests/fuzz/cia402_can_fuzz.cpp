// CAN frames into the CiA 402 driver (Cia402Bus, docs/PROTOCOLS.md "CAN: CiA
// 402 drives"): TPDO1, EMCY, SDO replies and heartbeats (their COB-IDs are
// offered to the fuzzer), other traffic and error frames, while it maps PDOs,
// steps the drives' state machines and writes targets.
#include <stdexcept>

#include "drivers/can/cia402_bus.hpp"
#include "drivers/protocol/cia402_frames.hpp"
#include "tests/fuzz/can_fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace facectl;
  FuzzedDataProvider in(data, size);
  CanBusOptions options;
  options.map_pdos = in.ConsumeBool();
  options.cycle_divider = in.ConsumeIntegralInRange(1, 3);
  const std::vector<ActuatorModel> actuators = fuzz::consume_actuators(in, 127);
  fuzz::ScriptedCanTransport link;
  try {
    Cia402Bus bus("fuzz", link, actuators, std::vector<double>(actuators.size()), options);
    fuzz::run_bus(
        in, bus, link, actuators.size(),
        {cia402::kEmcyBase, cia402::kTpdo1Base, cia402::kSdoTxBase, cia402::kHeartbeatBase});
  } catch (const std::invalid_argument&) {  // addresses or encodings a rig file cannot pass
  }
  return 0;
}
