#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>

#include "control/command/face_command.hpp"
#include "control/realtime/latest_value_mailbox.hpp"
#include "firmware-host/config/midi_config.hpp"
#include "firmware-host/inputs/midi_face.hpp"
#include "firmware-host/inputs/show_recorder.hpp"

typedef struct _snd_seq snd_seq_t;  // NOLINT: alsa/asoundlib.h's own declaration

namespace facectl {

struct MidiStats {
  std::uint64_t events = 0;    // MIDI events received (controls, notes, others)
  std::uint64_t controls = 0;  // control changes that moved a mapped signal
  std::uint64_t notes = 0;     // note ons and offs of mapped notes
  std::uint64_t unmapped = 0;  // controls and notes the map does not name
  std::uint64_t published = 0;
  std::uint64_t overruns = 0;  // times the kernel dropped events (input pool full)
  int senders = 0;             // subscribed to facectl's port now
  int most_senders = 0;
  std::string last_error;
};

// MIDI in through the ALSA sequencer (`facectl run --midi`, docs/INPUTS.md,
// "MIDI"): a client named by the runtime file with one writable port, which
// any sequencer client can connect to (aconnect, a DAW, a USB controller
// through snd-usb-audio, aplaymidi -p). Controls and notes move the face
// through MidiFaceState; while a sender is connected the held pose is
// published at rate_hz, so a fader left still keeps the face where it is.
// When the last sender disconnects, the face is forgotten and nothing more is
// published: the tick's input watchdog eases to neutral, as for a lost stream.
class MidiInput {
 public:
  // Opens the sequencer, makes the port and connects to config.connect;
  // std::runtime_error naming what failed (no /dev/snd/seq: snd-seq not loaded).
  MidiInput(const MidiFaceMap& map, const std::array<double, kMaxFaceSignals>& neutral,
            const MidiConfig& config, LatestValueMailbox<FaceCommand>* mailbox,
            ShowRecorder* recorder = nullptr);
  ~MidiInput();
  MidiInput(const MidiInput&) = delete;
  MidiInput& operator=(const MidiInput&) = delete;

  std::string address() const;  // "128:0", what senders connect to
  void start();
  void stop();
  MidiStats stats() const;

 private:
  void run();
  void handle_pending(MidiStats& delta);
  int senders() const;
  void publish(std::int64_t now_ns);

  MidiFaceState state_;
  LatestValueMailbox<FaceCommand>* mailbox_;
  ShowRecorder* recorder_;
  double rate_hz_;
  snd_seq_t* seq_ = nullptr;
  int client_ = -1;
  int port_ = -1;
  FaceCommand cmd_;
  std::int64_t first_publish_ns_ = -1;

  mutable std::mutex mutex_;  // guards stats_ between the thread and stats()
  MidiStats stats_;
  std::thread thread_;
  std::atomic<bool> stop_{false};
};

}  // namespace facectl
