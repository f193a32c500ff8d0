// The telemetry stream (GET /api/v1/telemetry?rate_hz=N, server-sent events)
// kept open across server restarts, and the last few seconds of it.
"use strict";
window.FaceCtl = window.FaceCtl || {};

(function (ns) {
  const HISTORY_S = 6;

  class Telemetry {
    // onStatus(text, ok) reports the stream's health; onFrame(frame) each event.
    constructor(onStatus, onFrame) {
      this.onStatus = onStatus;
      this.onFrame = onFrame;
      this.frames = [];  // oldest first, at most HISTORY_S seconds
      this.rate = 20;
      this.source = null;
      this.retryTimer = null;
    }

    start(rateHz) {
      this.rate = Math.min(100, Math.max(10, Math.round(rateHz) || 20));
      this.stop();
      this.frames = [];
      const source = new EventSource(ns.api.urlWithToken(`/api/v1/telemetry?rate_hz=${this.rate}`));
      this.source = source;
      this.onStatus(`connecting at ${this.rate} Hz…`, true);
      source.onopen = () => this.onStatus(`live at ${this.rate} Hz`, true);
      source.onmessage = (event) => this.receive(event.data);
      source.onerror = () => {
        if (this.source !== source) return;
        // CONNECTING: the browser retries by itself. CLOSED (the server said
        // no, or answered something else): retry ourselves, it may be restarting.
        this.onStatus("telemetry connection lost, reconnecting…", false);
        if (source.readyState === EventSource.CLOSED) {
          this.source = null;
          this.retryTimer = setTimeout(() => this.start(this.rate), 2000);
        }
      };
    }

    stop() {
      clearTimeout(this.retryTimer);
      if (this.source) this.source.close();
      this.source = null;
    }

    receive(data) {
      let frame;
      try { frame = JSON.parse(data); } catch (e) { return; }
      if (typeof frame.time_s !== "number") return;
      const last = this.frames[this.frames.length - 1];
      if (last && frame.time_s < last.time_s) this.frames = [];  // the server restarted
      this.frames.push(frame);
      const oldest = frame.time_s - HISTORY_S;
      let drop = 0;
      while (drop < this.frames.length && this.frames[drop].time_s < oldest) drop++;
      if (drop) this.frames.splice(0, drop);
      this.onFrame(frame);
    }

    latest() { return this.frames[this.frames.length - 1] || null; }
  }

  ns.Telemetry = Telemetry;
  ns.Telemetry.HISTORY_S = HISTORY_S;
})(window.FaceCtl);
