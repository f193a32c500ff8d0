#pragma once

namespace facectl::modbus_rtu {

// The characters one board's I/O cycle puts on an RTU wire (docs/PROTOCOLS.md):
// a write-multiple of CONTROL, HEARTBEAT and the `channels` targets (request
// 9 + 2·(2 + n) bytes, reply 8), then a read of the input registers (request
// 8, reply 5 + 2·(4 + n)). Every frame is followed by 3.5 characters of silence.
struct BoardCycleChars {
  static constexpr double kSilence = 3.5;
  double write_request = 0.0;
  double write_reply = 0.0;
  double read_request = 0.0;
  double read_reply = 0.0;

  explicit BoardCycleChars(int channels)
      : write_request(9 + 2 * (2 + channels)),
        write_reply(8),
        read_request(8),
        read_reply(5 + 2 * (4 + channels)) {}
  // Until the board has the whole write request (and its end-of-frame silence).
  double until_written() const { return write_request + kSilence; }
  double total() const {
    return write_request + write_reply + read_request + read_reply + 4 * kSilence;
  }
};

// 8N1 framing: start bit, 8 data bits, stop bit.
inline constexpr int kBitsPerChar = 10;

inline double chars_to_seconds(double chars, long baud) {
  return chars * kBitsPerChar / static_cast<double>(baud);
}

}  // namespace facectl::modbus_rtu
