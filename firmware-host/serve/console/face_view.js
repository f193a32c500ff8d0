// The face, drawn in a canvas. Two sources:
// - GET /api/v1/face/geometry: the skin mesh at rest, moved by each telemetry
//   frame's `landmarks_mm` (the reduced model's control-point displacements)
//   through the weights W, with the control points marked. Between the points
//   the skin is an interpolation, not the full face model (docs/API.md);
// - when the head has none (404): a schematic face drawn from the face signals.
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
      this.view = null;
      this.moved = null;  // the skin's vertices this frame, x y z per vertex
    }

    setSignals(signals) {
      this.keys = new Map(signals.map((s, i) => [s.key, i]));
      this.neutral = signals.map((s) => s.neutral);
    }

    // geometry: GET /api/v1/face/geometry's document, or null for the schematic.
    setGeometry(geometry) {
      this.geometry = isGeometry(geometry) ? geometry : null;
      this.view = this.geometry ? frontView(this.geometry.skin.vertices_mm, this.canvas) : null;
      this.moved = this.geometry ? new Float64Array(this.geometry.skin.vertices_mm.length) : null;
      this.modeLabel.textContent = this.geometry
        ? `(reduced model: ${this.geometry.landmarks.length} control points, skin interpolated)`
        : "(schematic from the signals)";
    }

    draw(frame) {
      const ctx = this.canvas.getContext("2d");
      ctx.clearRect(0, 0, this.canvas.width, this.canvas.height);
      const colours = palette();
      if (this.geometry) {
        const d = frame && Array.isArray(frame.landmarks_mm) ? frame.landmarks_mm : null;
        deform(this.geometry, d, this.moved);
        drawSkin(ctx, this.view, this.geometry.skin.triangles, this.moved, colours);
        drawPoints(ctx, this.view, this.geometry, d, colours);
      } else {
        drawSchematic(ctx, this.canvas, this.signalReader(frame), colours);
      }
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

  function isGeometry(g) {
    if (!g || !Array.isArray(g.landmarks) || !g.skin || !Array.isArray(g.weights)) return false;
    const vertices = g.skin.vertices_mm.length / 3;
    return vertices > 0 && g.weights.length === vertices * g.landmarks.length;
  }

  function palette() {
    const style = getComputedStyle(document.documentElement);
    const get = (name) => style.getPropertyValue(name).trim();
    return { line: get("--face-line"), skin: get("--face-skin"), eye: get("--face-eye"),
             point: get("--face-point"), dim: get("--text-dim") };
  }

  // Front view, fitted to the skin at rest: +x (the head's left) to the right
  // of the picture, as one sees a face, +y up.
  function frontView(vertices, canvas) {
    let x0 = Infinity, x1 = -Infinity, y0 = Infinity, y1 = -Infinity;
    for (let i = 0; i < vertices.length; i += 3) {
      x0 = Math.min(x0, vertices[i]); x1 = Math.max(x1, vertices[i]);
      y0 = Math.min(y0, vertices[i + 1]); y1 = Math.max(y1, vertices[i + 1]);
    }
    const scale = 0.9 * Math.min(canvas.width / (x1 - x0 || 1), canvas.height / (y1 - y0 || 1));
    const cx = (x0 + x1) / 2, cy = (y0 + y1) / 2;
    return { x: (x) => canvas.width / 2 + (x - cx) * scale,
             y: (y) => canvas.height / 2 - (y - cy) * scale };
  }

  // out = rest + W · d: each vertex moved by the weighted control-point displacements.
  function deform(g, d, out) {
    const rest = g.skin.vertices_mm, w = g.weights, points = g.landmarks.length;
    out.set(rest);
    if (!d || d.length !== 3 * points) return;
    for (let v = 0, row = 0; v < out.length; v += 3, row += points) {
      for (let p = 0; p < points; p++) {
        const k = w[row + p];
        out[v] += k * d[3 * p];
        out[v + 1] += k * d[3 * p + 1];
        out[v + 2] += k * d[3 * p + 2];
      }
    }
  }

  // Shaded triangles, farthest first; lit from the viewer, so a slope facing
  // away from the picture plane is darker.
  function drawSkin(ctx, view, triangles, v, c) {
    const order = [];
    for (let t = 0; t < triangles.length; t += 3) {
      const [a, b, d] = [3 * triangles[t], 3 * triangles[t + 1], 3 * triangles[t + 2]];
      order.push({ t, z: v[a + 2] + v[b + 2] + v[d + 2], light: facing(v, a, b, d) });
    }
    order.sort((p, q) => p.z - q.z);
    ctx.lineWidth = 0.5;
    ctx.strokeStyle = c.line;
    for (const { t, light } of order) {
      ctx.beginPath();
      for (let k = 0; k < 3; k++) {
        const i = 3 * triangles[t + k];
        ctx[k ? "lineTo" : "moveTo"](view.x(v[i]), view.y(v[i + 1]));
      }
      ctx.closePath();
      ctx.fillStyle = c.skin;
      ctx.globalAlpha = 1;
      ctx.fill();
      ctx.fillStyle = "#000";
      ctx.globalAlpha = 0.65 * (1 - light);
      ctx.fill();
      ctx.globalAlpha = 0.35;
      ctx.stroke();
    }
    ctx.globalAlpha = 1;
  }

  // |n_z| of the triangle's unit normal: 1 facing the viewer, 0 edge-on.
  function facing(v, a, b, d) {
    const ux = v[b] - v[a], uy = v[b + 1] - v[a + 1], uz = v[b + 2] - v[a + 2];
    const wx = v[d] - v[a], wy = v[d + 1] - v[a + 1], wz = v[d + 2] - v[a + 2];
    const nx = uy * wz - uz * wy, ny = uz * wx - ux * wz, nz = ux * wy - uy * wx;
    return Math.abs(nz) / (Math.hypot(nx, ny, nz) || 1);
  }

  // The control points where the model puts them, joined along the lips and brows.
  function drawPoints(ctx, view, g, d, c) {
    const points = g.landmarks.map((l, i) => {
      const p = l.position_mm;
      const o = d && d.length === 3 * g.landmarks.length ? d.slice(3 * i, 3 * i + 3) : [0, 0, 0];
      return [view.x(p[0] + o[0]), view.y(p[1] + o[1])];
    });
    ctx.strokeStyle = c.point;
    ctx.lineWidth = 1.5;
    ctx.beginPath();
    for (const [a, b] of g.edges || []) {
      if (!points[a] || !points[b]) continue;
      ctx.moveTo(points[a][0], points[a][1]);
      ctx.lineTo(points[b][0], points[b][1]);
    }
    ctx.stroke();
    ctx.fillStyle = c.point;
    for (const [x, y] of points) {
      ctx.beginPath();
      ctx.arc(x, y, 3, 0, 2 * Math.PI);
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
