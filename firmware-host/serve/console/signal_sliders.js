// The face signals as sliders in hold mode: moving one holds the sliders'
// pose (POST /api/v1/pose). Ranges, units and neutral values come from
// GET /api/v1/rig; nothing is sent until the operator moves a slider.
"use strict";
window.FaceCtl = window.FaceCtl || {};

(function (ns) {
  const { el, command, format } = ns.ui;
  const SEND_EVERY_MS = 100;

  class SignalSliders {
    constructor() {
      this.box = document.getElementById("sliders");
      this.signals = [];
      this.inputs = [];
      this.live = [];
      this.pending = null;
      this.neutral = document.getElementById("sliders-neutral");
      // In JOG the face input is ignored: a pose sent then would only show after the jog.
      this.jogNote = el("p", { class: "hint jog-note", hidden: "",
                               text: "Off in JOG: the face input is ignored. End jog to hold a pose again." });
      this.box.before(this.jogNote);
      this.neutral.onclick = () => {
        this.signals.forEach((s, i) => this.setValue(i, s.neutral));
        this.send();
      };
    }

    setSignals(signals) {
      this.signals = signals;
      this.inputs = [];
      this.live = [];
      this.box.replaceChildren(...signals.map((signal, i) => {
        const id = "signal-" + signal.key;
        const step = signal.unit === "" ? 0.01 : 0.1;
        const input = el("input", { type: "range", id, min: signal.min, max: signal.max, step,
                                    value: signal.neutral });
        const shown = el("output", { for: id });
        const live = el("span", { class: "live", title: "the signal now (telemetry)" });
        input.oninput = () => { shown.textContent = label(signal, Number(input.value)); this.schedule(); };
        shown.textContent = label(signal, signal.neutral);
        this.inputs.push(input);
        this.live.push(live);
        return el("div", { class: "slider" },
          el("label", { for: id, title: signal.key }, signal.key,
             el("small", { text: `${signal.min}..${signal.max}${signal.unit ? " " + signal.unit : ""}` })),
          input, shown, live);
      }));
    }

    setValue(index, value) {
      this.inputs[index].value = value;
      this.inputs[index].dispatchEvent(new Event("input"));
    }

    // At most one pose every SEND_EVERY_MS while a slider moves, and the last one always.
    schedule() {
      if (this.pending) return;
      this.pending = setTimeout(() => { this.pending = null; this.send(); }, SEND_EVERY_MS);
    }

    async send() {
      clearTimeout(this.pending);
      this.pending = null;
      const signals = {};
      this.signals.forEach((s, i) => { signals[s.key] = Number(this.inputs[i].value); });
      await command("/api/v1/pose", { signals });
    }

    // GET /api/v1/state's answer: the sliders are off while the head is in JOG.
    render(state) {
      const jogging = Boolean(state && state.state === "JOG");
      this.jogNote.hidden = !jogging;
      this.neutral.disabled = jogging;
      this.inputs.forEach((input) => { input.disabled = jogging; });
    }

    showLive(face) {
      if (!Array.isArray(face)) return;
      this.live.forEach((span, i) => { span.textContent = "now " + format(face[i], 2); });
    }
  }

  function label(signal, value) {
    return `${format(value, signal.unit === "" ? 2 : 1)}${signal.unit ? " " + signal.unit : ""}`;
  }

  ns.SignalSliders = SignalSliders;
})(window.FaceCtl);
