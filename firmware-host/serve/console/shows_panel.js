// The shows folder (GET /api/v1/shows) with play / queue / stop, and the
// playing show's progress from GET /api/v1/state.
"use strict";
window.FaceCtl = window.FaceCtl || {};

(function (ns) {
  const { el, command, format } = ns.ui;

  class ShowsPanel {
    constructor() {
      this.list = document.getElementById("show-list");
      this.bar = document.getElementById("show-progress-bar");
      this.barText = document.getElementById("show-progress-text");
      this.progress = this.bar.parentElement;
      this.queue = document.getElementById("queue");
      document.getElementById("show-stop").onclick = () => command("/api/v1/show/stop");
    }

    setShows(shows) {
      this.list.replaceChildren(...shows.map((show) => el("li", {},
        el("span", { class: "name", text: show.name }),
        el("span", { class: "duration", text: `${format(show.duration_s, 1)} s` }),
        el("button", { type: "button", "aria-label": `play ${show.name}`, text: "▶ play",
                       onclick: () => command("/api/v1/show/play", { name: show.name }) }),
        el("button", { type: "button", "aria-label": `queue ${show.name}`, text: "+ queue",
                       onclick: () => command("/api/v1/show/queue", { name: show.name }) }))));
      if (shows.length === 0) this.list.append(el("li", { text: "no shows in the shows folder" }));
    }

    render(state) {
      const show = state && state.show;
      let percent = 0;
      if (show && show.duration_s > 0) percent = Math.min(100, Math.max(0, 100 * show.position_s / show.duration_s));
      this.bar.style.width = percent + "%";
      this.progress.setAttribute("aria-valuenow", percent.toFixed(0));
      this.barText.textContent = show
        ? `${show.name}: ${format(show.position_s, 1)} / ${format(show.duration_s, 1)} s`
        : "no show playing";
      const queued = (state && state.queue) || [];
      this.queue.textContent = queued.length ? "queued: " + queued.join(", ") : "";
    }
  }

  ns.ShowsPanel = ShowsPanel;
})(window.FaceCtl);
