// The operator console: polls the state, keeps the lists and the telemetry
// stream current across server restarts, and draws. It never sends a command
// by itself; only the operator's clicks and slider moves do.
"use strict";
window.FaceCtl = window.FaceCtl || {};

(function (ns) {
  const STATE_EVERY_MS = 250;
  const EVENTS_EVERY_MS = 2000;
  const DRAW_EVERY_MS = 33;

  const connection = document.getElementById("connection");
  const telemetryStatus = document.getElementById("telemetry-status");
  const rateInput = document.getElementById("rate");

  const safety = new ns.SafetyPanel();
  const shows = new ns.ShowsPanel();
  const expressions = new ns.ExpressionsPanel();
  const sliders = new ns.SignalSliders();
  const jog = new ns.JogPanel();
  const events = new ns.EventsPanel();
  const face = new ns.FaceView(document.getElementById("face"), document.getElementById("face-mode"));
  const telemetry = new ns.Telemetry(
    (text, ok) => { ns.ui.setText(telemetryStatus, text); telemetryStatus.className = ok ? "ok" : "lost"; },
    (frame) => { sliders.showLive(frame.face); jog.showMeasured(frame); });
  const plots = new ns.ActuatorPlots(telemetry);

  let connected = false;
  let uptime = -1;
  let stateTimer = null;

  function setConnected(ok, why) {
    connected = ok;
    ns.ui.setText(connection, ok ? "connected" : `connection lost: ${why}. Retrying…`);
    connection.className = ok ? "ok" : "lost";
  }

  // What a (re)started server may have changed: the rig, the shows, the expressions.
  async function loadLists() {
    const [rig, showList, expressionList] = await Promise.all([
      ns.api.get("/api/v1/rig"), ns.api.get("/api/v1/shows"), ns.api.get("/api/v1/expressions")]);
    document.title = `facectl · ${rig.head} on ${rig.rig}`;
    plots.setActuators(rig.actuators || []);
    jog.setActuators(rig.actuators || []);
    sliders.setSignals(rig.signals || []);
    face.setSignals(rig.signals || []);
    face.setGeometry(await ns.api.getIfPresent("/api/v1/face/geometry"));
    shows.setShows(showList.shows || []);
    expressions.setExpressions(expressionList.expressions || []);
    telemetry.start(Number(rateInput.value));
  }

  // One poll at a time: asked for while one runs, the next follows it at once.
  let polling = false;
  let pollAgain = false;
  async function pollState() {
    if (polling) { pollAgain = true; return; }
    polling = true;
    clearTimeout(stateTimer);
    try {
      const state = await ns.api.get("/api/v1/state");
      const restarted = !connected || state.uptime_s < uptime;
      uptime = state.uptime_s;
      if (restarted) {
        await loadLists();
        setConnected(true);
        events.refresh().catch(() => {});
      }
      safety.render(state);
      shows.render(state);
      expressions.render(state);
      sliders.render(state);
      jog.render(state);
    } catch (error) {
      setConnected(false, ns.ui.describe(error));
      safety.render(null);
      shows.render(null);
      jog.render(null);
    }
    polling = false;
    stateTimer = setTimeout(pollState, pollAgain ? 0 : STATE_EVERY_MS);
    pollAgain = false;
  }

  // After a command: show its effect now rather than at the next poll.
  ns.onCommandDone = () => {
    pollState();
    events.refresh().catch(() => {});
  };

  rateInput.onchange = () => {
    const rate = Math.min(100, Math.max(10, Math.round(Number(rateInput.value)) || 20));
    rateInput.value = rate;
    telemetry.start(rate);
  };

  setInterval(() => { if (connected) events.refresh().catch(() => {}); }, EVENTS_EVERY_MS);
  setInterval(() => { plots.draw(); face.draw(telemetry.latest()); }, DRAW_EVERY_MS);
  face.setGeometry(null);
  pollState();
})(window.FaceCtl);
