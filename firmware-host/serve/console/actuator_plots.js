// Live plots of the actuators the operator picks: command and measured
// position over the last seconds, against the soft limits and hard limits of
// GET /api/v1/rig drawn as shaded bands.
"use strict";
window.FaceCtl = window.FaceCtl || {};

(function (ns) {
  const { el, format } = ns.ui;
  const WIDTH = 460, HEIGHT = 120, LEFT = 44, RIGHT = 8, TOP = 16, BOTTOM = 16;
  const PICKED_AT_START = 2;

  class ActuatorPlots {
    constructor(telemetry) {
      this.telemetry = telemetry;
      this.picks = document.getElementById("actuator-picks");
      this.plots = document.getElementById("plots");
      this.actuators = [];
      this.canvases = new Map();  // actuator index -> canvas
    }

    setActuators(actuators) {
      const before = this.actuators.map((a) => a.name);
      const kept = [...this.canvases.keys()].map((i) => before[i]);
      this.actuators = actuators;
      this.canvases.clear();
      this.plots.replaceChildren();
      this.picks.replaceChildren(...actuators.map((actuator, i) => {
        const box = el("input", { type: "checkbox", id: "pick-" + actuator.name });
        box.checked = kept.length ? kept.includes(actuator.name) : i < PICKED_AT_START;
        box.onchange = () => this.pick(i, box.checked);
        if (box.checked) this.pick(i, true);
        return el("label", { for: box.id }, box, ` ${actuator.name}`);
      }));
    }

    pick(index, on) {
      if (!on) {
        const canvas = this.canvases.get(index);
        if (canvas) canvas.parentElement.remove();
        this.canvases.delete(index);
        return;
      }
      const a = this.actuators[index];
      const canvas = el("canvas", { width: WIDTH, height: HEIGHT,
        "aria-label": `${a.name}: command and measured position in ${a.unit}, ` +
                      `soft limits ${a.soft_min}..${a.soft_max}, hard limits ${a.min}..${a.max}` });
      this.canvases.set(index, canvas);
      const figure = el("figure", {}, el("figcaption", { text: `${a.name} (${a.unit})` }), canvas);
      // Keep the plots in the rig's order.
      const next = [...this.canvases.keys()].filter((i) => i > index).sort((x, y) => x - y)[0];
      const anchor = next === undefined ? null : this.canvases.get(next).parentElement;
      this.plots.insertBefore(figure, anchor);
    }

    draw() {
      for (const [index, canvas] of this.canvases) drawPlot(canvas, this.actuators[index], index, this.telemetry.frames);
    }
  }

  function drawPlot(canvas, a, index, frames) {
    fitToLayout(canvas);
    const ctx = canvas.getContext("2d");
    const w = canvas.width, h = canvas.height;
    const margin = 0.08 * (a.max - a.min || 1);
    const lo = a.min - margin, hi = a.max + margin;
    const y = (v) => TOP + (h - TOP - BOTTOM) * (hi - v) / (hi - lo);
    const end = frames.length ? frames[frames.length - 1].time_s : 0;
    const span = ns.Telemetry.HISTORY_S - 1;
    const x = (t) => LEFT + (w - LEFT - RIGHT) * (1 - (end - t) / span);
    const style = getComputedStyle(document.documentElement);
    const colour = (name) => style.getPropertyValue(name).trim();

    ctx.clearRect(0, 0, w, h);
    ctx.fillStyle = colour("--plot-bg");
    ctx.fillRect(LEFT, TOP, w - LEFT - RIGHT, h - TOP - BOTTOM);
    band(ctx, colour("--hard-band"), y(hi), y(a.max), LEFT, w - RIGHT);
    band(ctx, colour("--hard-band"), y(a.min), y(lo), LEFT, w - RIGHT);
    band(ctx, colour("--soft-band"), y(a.max), y(a.soft_max), LEFT, w - RIGHT);
    band(ctx, colour("--soft-band"), y(a.soft_min), y(a.min), LEFT, w - RIGHT);

    ctx.fillStyle = colour("--text-dim");
    ctx.font = "10px sans-serif";
    ctx.textAlign = "right";
    ctx.textBaseline = "middle";
    const labelled = [];  // hard limits first; a label too close to one drawn is left out
    for (const v of [a.min, a.max, a.soft_min, a.soft_max, a.rest]) {
      if (labelled.some((other) => Math.abs(y(v) - other) < 11)) continue;
      ctx.fillText(format(v, 1), LEFT - 4, y(v));
      labelled.push(y(v));
    }
    ctx.textAlign = "left";
    ctx.textBaseline = "top";
    ctx.fillText(`${span} s`, LEFT, h - BOTTOM + 3);

    ctx.save();
    ctx.beginPath();
    ctx.rect(LEFT, TOP, w - LEFT - RIGHT, h - TOP - BOTTOM);
    ctx.clip();
    trace(ctx, frames, "commands", index, x, y, colour("--cmd"));
    trace(ctx, frames, "measured", index, x, y, colour("--meas"));
    ctx.restore();

    const last = frames[frames.length - 1];
    if (last) {
      ctx.fillStyle = colour("--text");
      ctx.textAlign = "right";
      ctx.fillText(`cmd ${format(value(last, "commands", index), 2)}  meas ${format(value(last, "measured", index), 2)}`,
                   w - RIGHT, 2);
    }
  }

  // Draws at the size the page lays the canvas out at, so text stays sharp.
  function fitToLayout(canvas) {
    const width = Math.round(canvas.clientWidth);
    if (width > 0 && canvas.width !== width) canvas.width = width;
  }

  function band(ctx, fill, yTop, yBottom, x0, x1) {
    if (yBottom <= yTop) return;
    ctx.fillStyle = fill;
    ctx.fillRect(x0, yTop, x1 - x0, yBottom - yTop);
  }

  function value(frame, key, index) {
    const list = frame[key];
    return Array.isArray(list) ? list[index] : undefined;
  }

  function trace(ctx, frames, key, index, x, y, stroke) {
    ctx.strokeStyle = stroke;
    ctx.lineWidth = 1.5;
    ctx.beginPath();
    let drawing = false;
    for (const frame of frames) {
      const v = value(frame, key, index);
      if (typeof v !== "number" || !isFinite(v)) { drawing = false; continue; }
      if (drawing) ctx.lineTo(x(frame.time_s), y(v));
      else ctx.moveTo(x(frame.time_s), y(v));
      drawing = true;
    }
    ctx.stroke();
  }

  ns.ActuatorPlots = ActuatorPlots;
})(window.FaceCtl);
