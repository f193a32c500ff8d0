// The safety state, the active faults, and DISABLE / ENABLE / RESET.
"use strict";
window.FaceCtl = window.FaceCtl || {};

(function (ns) {
  const { el, command, setText } = ns.ui;
  const ENABLE_FROM = ["IDLE"];
  const RESET_FROM = ["FAULT", "ESTOP"];

  class SafetyPanel {
    constructor() {
      this.stateText = document.getElementById("state");
      this.stateBox = document.getElementById("state-box");
      this.sourceText = document.getElementById("source");
      this.faults = document.getElementById("faults");
      this.enable = document.getElementById("enable");
      this.reset = document.getElementById("reset");
      this.loopInfo = document.getElementById("loop-info");
      // DISABLE is never greyed out: it is sent even when the page believes it
      // cannot help, and says so if the server cannot be reached.
      document.getElementById("disable").onclick = () => command("/api/v1/disable");
      this.enable.onclick = () => command("/api/v1/enable");
      this.reset.onclick = () => command("/api/v1/reset");
    }

    // `state` is GET /api/v1/state's answer, or null when the server is unreachable.
    render(state) {
      const name = state ? state.state : "NO CONNECTION";
      setText(this.stateText, name);
      this.stateBox.className = "state-" + (state ? name.toLowerCase() : "unknown");
      this.enable.disabled = !state || !ENABLE_FROM.includes(name);
      this.reset.disabled = !state || !RESET_FROM.includes(name);
      if (!state) return;
      const source = state.source || {};
      setText(this.sourceText, source.kind ? `source: ${source.kind}${source.name ? " " + source.name : ""}` : "");
      const loop = state.loop || {};
      this.loopInfo.textContent = `up ${ns.ui.format(state.uptime_s, 0)} s · ticks ${loop.ticks ?? "–"} · ` +
        `overruns ${loop.overruns ?? "–"} · faults seen ${state.faults_seen ?? 0}`;
      this.renderFaults(state.faults || []);
    }

    renderFaults(faults) {
      const key = JSON.stringify(faults);
      if (key === this.shownFaults) return;  // the alert is announced on each change
      this.shownFaults = key;
      this.faults.hidden = faults.length === 0;
      this.faults.replaceChildren(...faults.map((f) => el("div", { class: "fault" },
        el("strong", { text: f.reason || "fault" }),
        ` ${f.detail || ""} `,
        el("span", { class: "time", text: `at ${ns.ui.format(f.time_s, 3)} s` }))));
    }
  }

  ns.SafetyPanel = SafetyPanel;
})(window.FaceCtl);
