#!/usr/bin/env python3
"""Writes cc_and_notes.mid, the MIDI file the QEMU guest test plays to
`facectl`'s ALSA sequencer port with aplaymidi (alsa-utils). Written by mido
(python3-mido), a MIDI library this project did not write, so the test
checks facectl against another reading of the Standard MIDI File format.

  channel 1 cc 1 = 127      the mapped fader at its top
  channel 2 cc 7 = 100      a control the map does not name
  channel 1 note 60 on 127  an expression at full weight
  channel 1 note 60 off
  channel 1 cc 1 = 64       the fader about halfway
  channel 1 note 62 on 64   another expression at 64/127, held to the end

Run from this folder: python3 make_cc_and_notes.py
"""
import mido

TICKS = 480  # per beat; at mido's default 120 bpm a beat is 0.5 s
mid = mido.MidiFile(ticks_per_beat=TICKS)
track = mido.MidiTrack()
mid.tracks.append(track)


def at(seconds):
    return int(round(seconds / 0.5 * TICKS))


events = [
    (0.00, mido.Message("control_change", channel=0, control=1, value=127)),
    (0.05, mido.Message("control_change", channel=1, control=7, value=100)),
    (0.10, mido.Message("note_on", channel=0, note=60, velocity=127)),
    (0.20, mido.Message("note_off", channel=0, note=60, velocity=0)),
    (0.25, mido.Message("control_change", channel=0, control=1, value=64)),
    (0.30, mido.Message("note_on", channel=0, note=62, velocity=64)),
]
now = 0
for t, msg in events:
    msg.time = at(t) - now
    now = at(t)
    track.append(msg)
track.append(mido.MetaMessage("end_of_track", time=at(0.40) - now))
mid.save("cc_and_notes.mid")
