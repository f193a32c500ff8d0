// JOG: one actuator at a time, by hand (docs/SAFETY.md, "Jog"). JOG enters it
// from RUNNING (POST /api/v1/jog/start), "End jog" leaves it (jog/stop); in
// JOG a picker, a slider and a number box move the chosen actuator within its
// jog range from GET /api/v1/rig (POST /api/v1/jog). The number box sends what
// is typed, even outside the range: the server's refusal is shown here.
"use strict";
window.FaceCtl = window.FaceCtl || {};

(function (ns) {
  const { el, format, setText } = ns.ui;
  const SEND_EVERY_MS = 100;  // at most 10 targets a second while dragging

  class JogPanel {
    constructor() {
      this.actuators = [];
      this.jogging = false;
      this.wanted = null;   // the newest target not yet sent
      this.sending = false;
      this.timer = null;
      this.mode = el("p", { id: "jog-mode", class: "mode" });
      this.start = el("button", { id: "jog-start", type: "button", disabled: "",
                                  title: "RUNNING → JOG: the face input is ignored, every actuator holds",
                                  text: "JOG" });
      this.stop = el("button", { id: "jog-stop", type: "button", hidden: "",
                                 title: "JOG → RUNNING through the bumpless ramp", text: "End jog" });
      this.start.onclick = () => this.post("/api/v1/jog/start");
      this.stop.onclick = () => this.post("/api/v1/jog/stop");
      this.picker = el("select", { id: "jog-actuator" });
      this.picker.onchange = () => this.pick();
      this.slider = el("input", { id: "jog-slider", type: "range", "aria-label": "jog target" });
      this.slider.oninput = () => { this.number.value = this.slider.value; this.want(Number(this.slider.value), false); };
      this.slider.onchange = () => this.want(Number(this.slider.value), true);
      this.number = el("input", { id: "jog-target", type: "number", "aria-label": "jog target, typed" });
      this.number.onchange = () => this.typed();
      this.unit = el("span", { id: "jog-unit" });
      this.range = el("small", { id: "jog-range" });
      this.measured = el("span", { id: "jog-measured", class: "live", title: "telemetry: command and measured position" });
      this.error = el("p", { id: "jog-error", class: "error", role: "alert", hidden: "" });
      this.controls = el("div", { id: "jog-controls", hidden: "" },
        el("label", {}, "actuator ", this.picker), this.range,
        el("div", { class: "jog-target" }, this.slider, this.number, this.unit), this.measured);
      document.getElementById("jog").replaceChildren(
        this.mode, el("div", { class: "buttons" }, this.start, this.stop), this.controls, this.error);
      this.render(null);
    }

    // GET /api/v1/rig's actuators. `jog` null: a mandible strut, refused by the
    // API (409); no `jog` at all (an older server): the soft range.
    setActuators(actuators) {
      const keep = this.chosen() ? this.chosen().name : null;  // across a server restart
      this.actuators = actuators;
      this.picker.replaceChildren(...actuators.map((a, i) => {
        const option = el("option", { value: String(i),
                                      text: a.jog === null ? `${a.name} (strut: moves only with the jaw)` : a.name });
        option.disabled = a.jog === null;
        return option;
      }));
      const again = actuators.findIndex((a) => a.name === keep && a.jog !== null);
      const first = actuators.findIndex((a) => a.jog !== null);
      this.picker.value = String(again >= 0 ? again : first);
      this.pick();
    }

    chosen() { return this.actuators[Number(this.picker.value)] || null; }

    static rangeOf(a) {
      return a.jog ? [a.jog.min, a.jog.max] : [a.soft_min, a.soft_max];
    }

    // A new actuator: its range, and the target where it is now; nothing is sent.
    pick() {
      const a = this.chosen();
      this.cancel();
      this.showError("");
      if (!a) return;
      const [lo, hi] = JogPanel.rangeOf(a);
      const step = a.unit === "mm" ? 0.1 : 0.5;
      for (const input of [this.slider, this.number]) {
        input.min = lo;
        input.max = hi;
        input.step = step;
      }
      setText(this.unit, a.unit);
      setText(this.range, `jog range ${format(lo, 1)}..${format(hi, 1)} ${a.unit}`);
      this.setTarget(this.measuredOf(a) ?? a.rest);
    }

    setTarget(value) {
      const a = this.chosen();
      if (!a || typeof value !== "number") return;
      const [lo, hi] = JogPanel.rangeOf(a);
      const v = Math.min(hi, Math.max(lo, value));
      this.slider.value = v;
      this.number.value = v.toFixed(1);
    }

    measuredOf(a) {
      const i = this.actuators.indexOf(a);
      const m = this.frame && Array.isArray(this.frame.measured) ? this.frame.measured[i] : undefined;
      return typeof m === "number" ? m : null;
    }

    // A typed target is sent as it is: outside the range the server says why (422).
    typed() {
      const value = Number(this.number.value);
      if (this.number.value === "" || !isFinite(value)) {
        this.showError("type a number");
        return;
      }
      if (value >= Number(this.slider.min) && value <= Number(this.slider.max)) this.slider.value = value;
      this.want(value, true);
    }

    // Dragging sends at most every SEND_EVERY_MS; a release or a typed value at once.
    want(position, now) {
      const a = this.chosen();
      if (!a || !this.jogging) return;
      this.wanted = { actuator: a.name, position };
      if (now) {
        this.cancel();
        this.flush();
      } else if (!this.timer) {
        this.timer = setTimeout(() => { this.timer = null; this.flush(); }, SEND_EVERY_MS);
      }
    }

    cancel() {
      clearTimeout(this.timer);
      this.timer = null;
    }

    // One jog request at a time, the newest target next.
    async flush() {
      if (this.sending || !this.wanted) return;
      const body = this.wanted;
      this.wanted = null;
      this.sending = true;
      try {
        await ns.api.post("/api/v1/jog", body);
        this.showError("");
      } catch (error) {
        this.showError(ns.ui.describe(error));
      }
      this.sending = false;
      this.flush();
    }

    async post(path) {
      try {
        await ns.api.post(path);
        this.showError("");
      } catch (error) {
        this.showError(ns.ui.describe(error));
      }
      if (ns.onCommandDone) ns.onCommandDone();
    }

    // A refusal stays until the next request that is answered 200.
    showError(text) {
      setText(this.error, text);
      this.error.hidden = text === "";
    }

    // GET /api/v1/state's answer, or null when the server is unreachable.
    render(state) {
      const name = state ? state.state : "";
      const jogging = name === "JOG";
      this.start.disabled = name !== "RUNNING";
      this.start.hidden = jogging;
      this.stop.hidden = !jogging;
      this.controls.hidden = !jogging;
      setText(this.mode, jogging
        ? "JOG: the face input is ignored; the chosen actuator follows its target, the others hold."
        : "Hold mode: the face signals drive the head. JOG (from RUNNING) moves one actuator by hand.");
      this.mode.className = "mode " + (jogging ? "mode-jog" : "mode-hold");
      if (jogging && !this.jogging) this.setTarget(this.measuredOf(this.chosen()));  // start where it is
      if (!jogging) { this.cancel(); this.wanted = null; }
      this.jogging = jogging;
    }

    // A telemetry frame: the chosen actuator's command and measured position.
    showMeasured(frame) {
      this.frame = frame;
      const a = this.chosen();
      if (!a) return;
      const i = this.actuators.indexOf(a);
      const command = Array.isArray(frame.commands) ? frame.commands[i] : undefined;
      setText(this.measured, `command ${format(command, 1)} · measured ${format(this.measuredOf(a), 1)} ${a.unit}`);
    }
  }

  ns.JogPanel = JogPanel;
})(window.FaceCtl);
