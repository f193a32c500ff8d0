#include "firmware-host/inputs/midi_input.hpp"

#include <alsa/asoundlib.h>
#include <poll.h>

#include <cerrno>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "control/clock.hpp"
#include "firmware-host/inputs/alsa_messages.hpp"

namespace facectl {
namespace {

std::runtime_error alsa_error(const std::string& what, int err) {
  return std::runtime_error("MIDI: " + what + ": " + snd_strerror(err));
}

}  // namespace

MidiInput::MidiInput(const MidiFaceMap& map, const std::array<double, kMaxFaceSignals>& neutral,
                     const MidiConfig& config, LatestValueMailbox<FaceCommand>* mailbox,
                     ShowRecorder* recorder)
    : state_(map, neutral), mailbox_(mailbox), recorder_(recorder), rate_hz_(config.rate_hz) {
  quiet_alsa_lib();
  int err = snd_seq_open(&seq_, "default", SND_SEQ_OPEN_INPUT, SND_SEQ_NONBLOCK);
  if (err < 0) {
    seq_ = nullptr;
    std::runtime_error e = alsa_error("cannot open the ALSA sequencer", err);
    if (err != -ENOENT) throw e;
    throw std::runtime_error(std::string(e.what()) + " (no /dev/snd/seq: load the snd-seq module)");
  }
  try {
    if ((err = snd_seq_set_client_name(seq_, config.client.c_str())) < 0) {
      throw alsa_error("cannot name the client '" + config.client + "'", err);
    }
    client_ = snd_seq_client_id(seq_);
    port_ = snd_seq_create_simple_port(
        seq_, "face", SND_SEQ_PORT_CAP_WRITE | SND_SEQ_PORT_CAP_SUBS_WRITE,
        SND_SEQ_PORT_TYPE_MIDI_GENERIC | SND_SEQ_PORT_TYPE_APPLICATION);
    if (port_ < 0) throw alsa_error("cannot create the port", port_);
    for (const std::string& from : config.connect) {
      snd_seq_addr_t addr;
      if ((err = snd_seq_parse_address(seq_, &addr, from.c_str())) < 0) {
        throw alsa_error("midi.connect: no sequencer port '" + from + "'", err);
      }
      if ((err = snd_seq_connect_from(seq_, port_, addr.client, addr.port)) < 0) {
        throw alsa_error("midi.connect: cannot connect from '" + from + "'", err);
      }
    }
  } catch (...) {
    snd_seq_close(seq_);
    seq_ = nullptr;
    throw;
  }
  state_.pose(cmd_.values);
}

MidiInput::~MidiInput() {
  stop();
  if (seq_ != nullptr) snd_seq_close(seq_);
}

std::string MidiInput::address() const {
  return std::to_string(client_) + ":" + std::to_string(port_);
}

void MidiInput::start() {
  thread_ = std::thread([this] { run(); });
}

void MidiInput::stop() {
  stop_.store(true, std::memory_order_relaxed);
  if (thread_.joinable()) thread_.join();
}

MidiStats MidiInput::stats() const {
  std::lock_guard lock(mutex_);
  return stats_;
}

int MidiInput::senders() const {
  snd_seq_port_info_t* info = nullptr;
  snd_seq_port_info_alloca(&info);
  if (snd_seq_get_port_info(seq_, port_, info) < 0) return 0;
  return snd_seq_port_info_get_write_use(info);
}

void MidiInput::handle_pending(MidiStats& delta) {
  snd_seq_event_t* ev = nullptr;
  while (true) {
    const int got = snd_seq_event_input(seq_, &ev);
    if (got == -ENOSPC) {
      // The kernel's input pool overflowed and dropped events: a note off
      // may be among them, so no expression is left held on a guess.
      ++delta.overruns;
      delta.last_error = "events dropped: the sequencer's input pool overflowed";
      state_.release_notes();
      continue;
    }
    if (got < 0 || ev == nullptr) break;
    using Applied = MidiFaceState::Applied;
    Applied a = Applied::kUnmapped;
    bool midi = true;
    switch (ev->type) {
      case SND_SEQ_EVENT_CONTROLLER:
        a = state_.control(ev->data.control.channel, static_cast<int>(ev->data.control.param),
                           ev->data.control.value);
        break;
      case SND_SEQ_EVENT_NOTEON:
        a = state_.note_on(ev->data.note.channel, ev->data.note.note, ev->data.note.velocity);
        break;
      case SND_SEQ_EVENT_NOTEOFF:
        a = state_.note_off(ev->data.note.channel, ev->data.note.note);
        break;
      default:
        midi = false;  // clock, sysex, port announcements: not the face's
    }
    ++delta.events;
    if (!midi) continue;
    if (a == Applied::kControl) ++delta.controls;
    if (a == Applied::kNoteOn || a == Applied::kNoteOff) ++delta.notes;
    if (a == Applied::kUnmapped) ++delta.unmapped;
  }
}

void MidiInput::publish(std::int64_t now_ns) {
  state_.pose(cmd_.values);
  ++cmd_.sequence;
  cmd_.stamp_ns = now_ns;
  if (mailbox_ != nullptr) mailbox_->publish(cmd_);
  if (first_publish_ns_ < 0) first_publish_ns_ = now_ns;
  if (recorder_ != nullptr) {
    recorder_->add(static_cast<double>(now_ns - first_publish_ns_) * 1e-9, cmd_.values);
  }
}

void MidiInput::run() {
  std::vector<pollfd> fds(static_cast<std::size_t>(snd_seq_poll_descriptors_count(seq_, POLLIN)));
  snd_seq_poll_descriptors(seq_, fds.data(), static_cast<unsigned>(fds.size()), POLLIN);
  const auto period_ns = static_cast<std::int64_t>(std::llround(1e9 / rate_hz_));
  std::int64_t next = monotonic_ns();
  int before = 0;  // senders at the last look
  while (!stop_.load(std::memory_order_relaxed)) {
    const std::int64_t wait_ns = std::max<std::int64_t>(0, next - monotonic_ns());
    const int n = ::poll(fds.data(), fds.size(), static_cast<int>((wait_ns + 999'999) / 1'000'000));
    MidiStats delta;
    if (n > 0) handle_pending(delta);
    const int now_senders = senders();
    const std::int64_t now = monotonic_ns();
    // Events are played even from a sender already gone (aplaymidi exits
    // right after its last note); a held pose is repeated only while one is
    // connected.
    const bool published = delta.controls + delta.notes > 0 || (now_senders > 0 && now >= next);
    if (published) publish(now);
    if (now_senders == 0 && before > 0) state_.reset();  // the last sender left: start afresh
    before = now_senders;
    if (now >= next) next = now + period_ns;
    std::lock_guard lock(mutex_);
    stats_.events += delta.events;
    stats_.controls += delta.controls;
    stats_.notes += delta.notes;
    stats_.unmapped += delta.unmapped;
    stats_.overruns += delta.overruns;
    if (!delta.last_error.empty()) stats_.last_error = delta.last_error;
    stats_.published += published ? 1 : 0;
    stats_.senders = now_senders;
    stats_.most_senders = std::max(stats_.most_senders, now_senders);
  }
}

}  // namespace facectl
