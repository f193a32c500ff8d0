// The event log (GET /api/v1/events): newest first.
"use strict";
window.FaceCtl = window.FaceCtl || {};

(function (ns) {
  const { el } = ns.ui;
  const LIMIT = 50;

  class EventsPanel {
    constructor() { this.list = document.getElementById("events"); this.shown = ""; }

    async refresh() {
      const answer = await ns.api.get(`/api/v1/events?limit=${LIMIT}`);
      const events = (answer.events || []).slice().reverse();
      const key = JSON.stringify(events);
      if (key === this.shown) return;  // keep the operator's scroll position
      this.shown = key;
      this.list.replaceChildren(...events.map((event) => el("li", { class: "kind-" + event.kind },
        el("time", { datetime: event.time, text: shortTime(event.time) }),
        el("span", { class: "kind", text: event.kind }),
        el("span", { class: "src", text: event.source }),
        el("span", { class: "text", text: event.text, title: event.text }))));
    }
  }

  function shortTime(iso) {
    const date = new Date(iso);
    return isNaN(date) ? String(iso) : date.toLocaleTimeString([], { hour12: false });
  }

  ns.EventsPanel = EventsPanel;
})(window.FaceCtl);
