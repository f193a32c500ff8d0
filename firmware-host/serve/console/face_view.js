// The face, drawn in a canvas. Two sources:
// - the reduced model's control points: when GET /api/v1/rig names a
//   `face_geometry` endpoint, its neutral positions (mm) and edges, moved by
//   each telemetry frame's `landmarks_mm` displacements (the proposed API);
// - otherwise a schematic face drawn from the face signals alone.
"use strict";
window.FaceCtl = window.FaceCtl || {};

(function (ns) {
  class FaceView {
    constructor(canvas, modeLabel) {
      this.canvas = canvas;
      this.modeLabel = modeLabel;
      this.keys = new Map();  // signal key -> index in a frame's `face`
      this.neutral = [];
      this.geometry = null;
    }

    setSignals(signals) {
      this.keys = new Map(signals.map((s, i) => [s.key, i]));
      this.neutral = signals.map((s) => s.neutral);
    }

    // geometry: {landmarks: [{name, position_mm: [x, y, z]}], edges: [[i, j]]} or null.
    setGeometry(geometry) {
      this.geometry = geometry && Array.isArray(geometry.landmarks) ? geometry : null;
      this.modeLabel.textContent = this.geometry
        ? `(reduced model: ${this.geometry.landmarks.length} points)`
        : "(schematic from the signals)";
    }

    draw(frame) {
      const ctx = this.canvas.getContext("2d");
      ctx.clearRect(0, 0, this.canvas.width, this.canvas.height);
      const colours = palette();
      if (this.geometry) drawPoints(ctx, this.canvas, this.geometry, frame && frame.landmarks_mm, colours);
      else drawSchematic(ctx, this.canvas, this.signalReader(frame), colours);
    }

    signalReader(frame) {
      const face = frame && Array.isArray(frame.face) ? frame.face : this.neutral;
      return (key) => {
        const i = this.keys.get(key);
        const v = i === undefined ? undefined : face[i];
        return typeof v === "number" && isFinite(v) ? v : 0;
      };
    }
  }

  function palette() {
    const style = getComputedStyle(document.documentElement);
    const get = (name) => style.getPropertyValue(name).trim();
    return { line: get("--face-line"), skin: get("--face-skin"), eye: get("--face-eye"),
             point: get("--face-point"), dim: get("--text-dim") };
  }

  // Front view of the control points: +x (the head's left) to the right of
  // the picture, as one sees a face, +y up.
  function drawPoints(ctx, canvas, geometry, displacements, c) {
    const points = geometry.landmarks.map((l, i) => {
      const p = l.position_mm;
      const d = Array.isArray(displacements) ? displacements.slice(3 * i, 3 * i + 3) : [0, 0, 0];
      return [p[0] + (d[0] || 0), p[1] + (d[1] || 0)];
    });
    const xs = geometry.landmarks.map((l) => l.position_mm[0]);
    const ys = geometry.landmarks.map((l) => l.position_mm[1]);
    const cx = (Math.min(...xs) + Math.max(...xs)) / 2, cy = (Math.min(...ys) + Math.max(...ys)) / 2;
    const scale = 0.8 * Math.min(canvas.width / (Math.max(...xs) - Math.min(...xs) || 1),
                                 canvas.height / (Math.max(...ys) - Math.min(...ys) || 1));
    const sx = (p) => canvas.width / 2 + (p[0] - cx) * scale;
    const sy = (p) => canvas.height / 2 - (p[1] - cy) * scale;
    ctx.strokeStyle = c.line;
    ctx.lineWidth = 2;
    ctx.beginPath();
    for (const [a, b] of geometry.edges || []) {
      if (!points[a] || !points[b]) continue;
      ctx.moveTo(sx(points[a]), sy(points[a]));
      ctx.lineTo(sx(points[b]), sy(points[b]));
    }
    ctx.stroke();
    ctx.fillStyle = c.point;
    for (const p of points) {
      ctx.beginPath();
      ctx.arc(sx(p), sy(p), 3, 0, 2 * Math.PI);
      ctx.fill();
    }
  }

  // A schematic face: what each signal does, not the head's real shape.
  // Picture x is the head's left (signals ending in _l) on the right.
  function drawSchematic(ctx, canvas, v, c) {
    ctx.save();
    ctx.translate(canvas.width / 2 + v("neck_pan_deg"), 0.45 * canvas.height - v("neck_tilt_deg"));
    ctx.rotate(-v("neck_roll_deg") * Math.PI / 180);
    ctx.lineWidth = 2.5;
    ctx.strokeStyle = c.line;
    ctx.fillStyle = c.skin;

    const jawDrop = 2.5 * v("jaw_pitch_deg");
    const jawShift = 4 * v("jaw_yaw_deg");
    const jawForward = 1.5 * v("jaw_protrusion_mm");
    // Skull and jaw.
    ctx.beginPath();
    ctx.ellipse(0, -30, 120, 130, 0, Math.PI, 2 * Math.PI);
    ctx.bezierCurveTo(120, 60, 70 + jawShift, 150 + jawDrop, jawShift, 160 + jawDrop + jawForward);
    ctx.bezierCurveTo(-70 + jawShift, 150 + jawDrop, -120, 60, -120, -30);
    ctx.fill();
    ctx.stroke();

    for (const side of [1, -1]) drawEyeAndBrow(ctx, side, side > 0 ? "_l" : "_r", v, c);

    ctx.strokeStyle = c.line;
    ctx.beginPath();
    ctx.moveTo(0, -20);
    ctx.lineTo(-8, 30);
    ctx.lineTo(8, 32);
    ctx.stroke();
    drawMouth(ctx, v, jawDrop, jawShift, c);
    ctx.restore();
  }

  function drawEyeAndBrow(ctx, side, s, v, c) {
    const ex = 50 * side, ey = -40;
    ctx.fillStyle = c.eye;
    ctx.beginPath();
    ctx.ellipse(ex, ey, 26, 14, 0, 0, 2 * Math.PI);
    ctx.fill();
    ctx.stroke();
    ctx.fillStyle = c.line;
    ctx.beginPath();
    ctx.arc(ex + 0.5 * v("eye_yaw" + s + "_deg"), ey - 0.4 * v("eye_pitch" + s + "_deg"), 6, 0, 2 * Math.PI);
    ctx.fill();
    // Lid: closure 0 open .. 1 shut, squinting a little with orbicularis oculi.
    const closure = Math.min(1, v("eyelid_closure" + s) + 0.3 * v("orbicularis_oculi" + s));
    ctx.fillStyle = c.skin;
    ctx.beginPath();
    ctx.rect(ex - 28, ey - 16, 56, 2 + 30 * closure);
    ctx.fill();
    ctx.beginPath();
    ctx.moveTo(ex - 26, ey - 14 + 30 * closure);
    ctx.lineTo(ex + 26, ey - 14 + 30 * closure);
    ctx.stroke();

    const raiseInner = 14 * (v("frontalis" + s) + v("frontalis_inner" + s));
    const raiseOuter = 14 * (v("frontalis" + s) + v("frontalis_outer" + s));
    const lowerInner = 12 * (v("corrugator_supercilii" + s) + v("procerus" + s));
    const pullIn = 8 * v("corrugator_supercilii" + s);
    ctx.lineWidth = 5;
    ctx.beginPath();
    ctx.moveTo(side * (22 + 0 - pullIn), -68 - raiseInner + lowerInner);
    ctx.quadraticCurveTo(side * 50, -80 - (raiseInner + raiseOuter) / 2, side * 80, -66 - raiseOuter);
    ctx.stroke();
    ctx.lineWidth = 2.5;
  }

  function drawMouth(ctx, v, jawDrop, jawShift, c) {
    const corner = (s) => {
      const up = 16 * (v("zygomaticus_major" + s) + v("levator_anguli_oris" + s)) -
                 16 * v("depressor_anguli_oris" + s);
      const out = 12 * (v("risorius" + s) + 0.5 * v("zygomaticus_major" + s)) - 14 * v("orbicularis_oris");
      return [out, up];
    };
    const [outL, upL] = corner("_l"), [outR, upR] = corner("_r");
    const left = [45 + outL, 70 - upL + jawDrop / 3], right = [-45 - outR, 70 - upR + jawDrop / 3];
    const upperLift = 8 * (v("levator_labii_superioris_l") + v("levator_labii_superioris_r")) / 2;
    const lowerDrop = jawDrop + 8 * (v("depressor_labii_inferioris_l") + v("depressor_labii_inferioris_r")) / 2;
    ctx.fillStyle = c.line;
    ctx.beginPath();
    ctx.moveTo(right[0], right[1]);
    ctx.quadraticCurveTo(0, 62 - upperLift, left[0], left[1]);
    ctx.quadraticCurveTo(jawShift, 78 + lowerDrop, right[0], right[1]);
    ctx.fill();
  }

  ns.FaceView = FaceView;
})(window.FaceCtl);
