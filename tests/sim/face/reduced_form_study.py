#!/usr/bin/env python3
"""Development aid (not a test): tries forms of the reduced face model offline.

Fits the reduced model's least squares on a cache of full-model steady states written by
`face_convergence_probe dump` and prints its errors on check-reduced's named sets, so a
form can be tried in seconds instead of a 15-minute `facectl face reduce`. Forms:
- `shipped` repeats point_features() in sim/face/src/reduced_model_fit.cpp and
  reproduces `face reduce`'s table (its 99th percentiles to 0.03 mm): per muscle c,
  c^2, c^3, c^4 and c times each jaw variable; the jaw's cubic; per pair of muscles
  c_a*c_b, c_a^2*c_b and c_a*c_b^2; the lids; and, at points the jaw moves by more than
  1 mm at a corner of its envelope, c^2 times each jaw variable and c times each product
  of two. (The C++ writes c^4 as the triple 1*q*q over a derived variable q = c^2; here a
  feature may simply have four factors.)
- `cubic` is `shipped` without c^4 (the form before the muscle volumes were corrected);
  `pair_cubes` is `cubic` without the jaw couplings, `plain` also without the pair
  cubes.

    face_convergence_probe dump /tmp/d0.csv 2000 0 2 &   # two shards side by side
    face_convergence_probe dump /tmp/d1.csv 2000 1 2
    python3 reduced_form_study.py '/tmp/d*.csv' [shipped|cubic|pair_cubes|plain ...]

Needs python3-numpy. Muscle and control-point counts come from the rows' widths
(the default head: 29 and 19).
"""
import glob
import sys

import numpy as np

SETS = ["in_distribution", "sparse_uniform", "dense_uniform", "single_muscle_full",
        "jaw_corners", "library"]
LIDS = 5  # pitch, yaw, protrusion and two lids follow the contractions
TRAIN_MIXES = 2000  # the dump's mixes; the one-signal sweeps after them
SWEEP_WEIGHT, RIDGE, RELEVANCE_MM, LID_POINT_MM, JAW_POINT_MM = 10.0, 1e-6, 0.3, 3.0, 1.0
FORMS = ["shipped", "cubic", "pair_cubes", "plain"]
MUSCLES = 29


def load(pattern):
    sets = {}
    for path in sorted(glob.glob(pattern)):
        for line in open(path):
            t = line.rstrip("\n").split(",")
            sets.setdefault(t[0], []).append(t)
    out = {}
    for name, rows in sets.items():
        rows.sort(key=lambda t: int(t[1]))
        x = np.array([[float(v) for v in t[4:4 + MUSCLES + LIDS]] for t in rows])
        y = np.array([[float(v) for v in t[4 + MUSCLES + LIDS:]] for t in rows])
        out[name] = dict(settled=np.array([int(t[2]) for t in rows]), x=x, y=y)
    return out


def variables(x):
    """fill_feature_variables(): the jaw in the fit's scaled units, then a constant 1."""
    v = np.ones((len(x), MUSCLES + 6))
    v[:, :MUSCLES + LIDS] = x
    v[:, MUSCLES:MUSCLES + 3] *= [10, 10, 100]
    return v


def features(v, factors):
    """One column per feature: the product of its factors' variables."""
    return np.stack([np.prod(v[:, list(f)], axis=1) for f in factors], 1)


def point_features(muscles, lids, lid_points, jaw_point, form):
    p, y, t, one = MUSCLES, MUSCLES + 1, MUSCLES + 2, MUSCLES + 5
    jaw = [p, y, t, one]
    f = [(jaw[a], jaw[b], jaw[c]) for a in range(4) for b in range(a, 4) for c in range(b, 4)
         if jaw[a] != one]
    for i in muscles:
        f += [(i, one, one), (i, i, one), (i, i, i), (i, p, one), (i, y, one), (i, t, one)]
        if jaw_point and form in ("shipped", "cubic"):
            f += [(i, i, j) for j in (p, y, t)]
            f += [(i, a, b) for k, a in enumerate((p, y, t)) for b in (p, y, t)[k:]]
        if form == "shipped":
            f.append((i, i, i, i))
    for k, a in enumerate(muscles):
        for b in muscles[k + 1:]:
            a, b = min(a, b), max(a, b)
            f.append((a, b, one))
            if form != "plain":
                f += [(a, a, b), (a, b, b)]
    f += [(lid, one, one) for lid in lids]
    for lid in lid_points:
        f += [(lid, lid, one), (lid, lid, lid)] + [(i, lid, one) for i in muscles]
    return sorted(set(tuple(sorted(x)) for x in f))


def movers(data, points):
    """The single-muscle probe and the lids alone at 1, as build_reduced_model()."""
    single = data["single_muscle_full"]["y"].reshape(-1, points, 3)
    mov = [[i for i in range(MUSCLES) if np.linalg.norm(single[i, q]) * 1e3 > RELEVANCE_MM]
           for q in range(points)]
    train = data["train"]
    lids, lid_points = [[] for _ in range(points)], [[] for _ in range(points)]
    for side in range(2):
        x = train["x"]
        row = np.where((x[:, :MUSCLES].sum(1) == 0) & (x[:, MUSCLES + 3 + side] == 1) &
                       (x[:, MUSCLES + 4 - side] == 0))[0][0]
        y = train["y"][row].reshape(points, 3)
        for q in range(points):
            mm = np.linalg.norm(y[q]) * 1e3
            if mm > RELEVANCE_MM:
                lids[q].append(MUSCLES + 3 + side)
            if mm > LID_POINT_MM:
                lid_points[q].append(MUSCLES + 3 + side)
    # The jaw probe: the first 8 of jaw_corners are the envelope's corners, relaxed.
    corners = data["jaw_corners"]["y"][:8].reshape(8, points, 3)
    jaw_points = [bool((np.linalg.norm(corners[:, q], axis=1) * 1e3 > JAW_POINT_MM).any())
                  for q in range(points)]
    return mov, lids, lid_points, jaw_points


def errors(e):
    """RMS, 99th percentile and max of the per-point 3-D errors, mm (as reduced_errors())."""
    d = np.sort(np.sqrt((e.reshape(len(e), -1, 3) ** 2).sum(2)).ravel()) * 1e3
    return np.sqrt((d ** 2).mean()), d[min(len(d) - 1, int(0.99 * len(d)))], d[-1]


def study(data, form):
    train = data["train"]
    points = train["y"].shape[1] // 3
    mov, lids, lid_points, jaw_points = movers(data, points)
    weight = np.ones(len(train["x"]))
    weight[TRAIN_MIXES:] = np.sqrt(SWEEP_WEIGHT)
    v = variables(train["x"])
    models, columns = [], set()
    for q in range(points):
        triples = point_features(mov[q], lids[q], lid_points[q], jaw_points[q], form)
        columns.update(triples)
        x = features(v, triples) * weight[:, None]
        y = train["y"][:, 3 * q:3 * q + 3] * weight[:, None]
        w = np.linalg.solve(x.T @ x + RIDGE * np.eye(len(triples)), x.T @ y)
        models.append((triples, w))
    print(f"{form}: {len(columns)} features")
    for name in SETS:
        s = data[name]
        vs = variables(s["x"])
        pred = np.concatenate([features(vs, t) @ w for t, w in models], 1)
        rms, p99, worst = errors(pred - s["y"])
        print(f"  {name:20s} {len(s['x']):4d} inputs, {int((s['settled'] == 0).sum()):3d} "
              f"unsettled: RMS {rms:.3f} p99 {p99:.2f} max {worst:.1f} mm")


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    data = load(sys.argv[1])
    for form in sys.argv[2:] or ["shipped", "cubic"]:
        if form not in FORMS:
            sys.exit(f"unknown form '{form}'; forms: {', '.join(FORMS)}")
        study(data, form)


if __name__ == "__main__":
    main()
