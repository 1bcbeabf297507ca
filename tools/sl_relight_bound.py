#!/usr/bin/python3
"""Upper bound on what putting the characters into relight's transport could gain (issue 13; README
"SL on the characters: the room-wide part bounded, session 13").

The proposed change (session 12's "what is left"): a relight probe ray that passes through a posed SL
reads that SL's exitant radiance instead of the static surfel behind it, and SLs are seen only beyond
a receiver's influence ball, so `sl` / `sl.shadow` keep the near field. At best it makes the effect
exact where no SL's influence reaches and leaves SL as it is inside. This script scores that oracle
(and more generous ones) from the images of `bounce accuracy` (sl_bounce_split.py's two folders).

Influence weight of a receiver p (engine/gi/sl/evaluate.hpp rule 0, F = the level's influence):
  w(p) = max over spheres i of clamp((F − |c_i − p| / r_i) / (F/2), 0, 1)
(1 up to F/2 radii, 0 from F radii). Sphere centres c_i and radii r_i come from the level's baked
sphere sets (.slset, engine/gi/sl/sphere_set.cpp's layout) placed by the entity's transform and its
motion at t = 0 (orbit position from sl_parts.characters, rotation euler-y + spin phase about y, the
mesh scale): the bind pose, not the clip's first frame. CesiumMan's bind pose holds its arms out
(sphere centres up to 0.52 m from its axis; walking, they hang within ~0.25 m): --reach M clamps every
centre's horizontal offset from the entity's axis to M metres, to show how much the ball's extent matters.
Oracles, each scored as e* against the converged reference (the exact part is r* = r − n, so its
pixels carry no error and their noise leaves the numerator: e*² = (‖t − r‖²_in − ‖n‖²_in) / ‖r*‖²):
  A  hard:     SL's level row where w > 0, exact where w = 0
  B  blend:    exact weighted by 1 − w (SL today weighted by w): a continuous blend at the ball's edge
               (the transport would have to be exact, near field included, in the fade shell F/2..F)
  H  first order: like B, with SL's own uncut field (the influence-12 row) in place of exact: probes
               that reproduced only SL's first-order view of the spheres in the shell
  E  added:    SL today + (1 − w) × exact inside (the transport exact but seen with weight 1 − w on top
               of SL's own faded near field: the double counting the blend must avoid)
  C  + const:  A, plus inside the ball the least-squares constant (a room-wide level added everywhere
               inside, as the relit room's lost light would be)
  C2 + affine: A, plus inside the least-squares affine function of world position
  D  refit:    A, with inside the best joint scaling of SL's three parts (relight, bounce, shadow) and a
               constant (least squares on the inside pixels: generous, it sees the reference)
  G1–G3:       SL + the least-squares trilinear field on a grid of the level's probe spacing (what a
               probe grid can hold at best) fitted beyond the ball / everywhere, and the field alone
Also printed: the shares of the converged effect's energy and of SL's error energy at w = 0, 0 < w < 1
and w = 1. If A, C2 and D are above the goal, no transport that leaves the ball to `sl` can reach it.

  tools/sl_relight_bound.py FULL BLACK --slsets FOX.slset CESIUM.slset [--influence 6]
(FULL, BLACK: sl_bounce_split.py's folders; the .slset files in the level's sl-entity order, from
`bounce bake`'s log lines "sl NAME: ... -> PATH".)
"""
import json
import math
import os
import struct
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from effect_noise import read_pfm as pfm  # noqa: E402
from tool_input import Arguments, run  # one line, exit 2 on bad input
from sl_parts import characters, effect, room_positions  # noqa: E402


def read_spheres(path):
    """(centre, radius) in mesh units from a version-2 .slset (sphere_set.cpp serialize)."""
    b = open(path, "rb").read()
    if b[:8] != b"BSLSPSET" or struct.unpack_from("<I", b, 8)[0] != 2:
        sys.exit(f"{path}: header: not an SL sphere-set file (expected magic BSLSPSET version 2)")
    o = 12
    order = struct.unpack_from("<6i", b, o)[1]
    nc = order * order
    o += 24 + 24  # settings; boundCentre, boundRadius, coverageError, volumeOvershoot
    (n,) = struct.unpack_from("<I", b, o)
    o += 4
    out = []
    for _ in range(n):
        c = struct.unpack_from("<3f", b, o)
        (r,) = struct.unpack_from("<f", b, o + 12)
        o += 16 + 8  # centre, radius, intersects
        (nv,) = struct.unpack_from("<I", b, o)
        o += 4 + 4 * nv
        (nj,) = struct.unpack_from("<I", b, o)
        o += 4 + 2 * nj
        (ns,) = struct.unpack_from("<I", b, o)
        o += 4 + ns * (28 + 4 * nc) + 4 * nc * 3 + 8  # samples; albedo; bounce and shadow scales
        out.append((np.array(c, float), r))
    if o != len(b):
        sys.exit(f"{path}: end: {len(b) - o} bytes left over (expected a complete sphere-set file)")
    return out


def world_spheres(entity, foot, path, reach=None):
    t = entity["transform"]
    s = t.get("scale", [1, 1, 1])[0]
    yaw = math.radians(t.get("rotation_euler_deg", [0, 0, 0])[1])
    spin = entity.get("motion", {}).get("spin")
    if spin:
        yaw += 2 * math.pi * spin.get("phase", 0.0)
    c, sn = math.cos(yaw), math.sin(yaw)
    rot = np.array([[c, 0, sn], [0, 1, 0], [-sn, 0, c]])
    out = []
    for ctr, r in read_spheres(path):
        d = rot @ (s * ctr)
        h = math.hypot(d[0], d[2])
        if reach is not None and h > reach:  # --reach: the arms of the bind pose brought in (see the usage)
            d[0], d[2] = d[0] * reach / h, d[2] * reach / h
        out.append((foot + d, s * r))
    return out


def main():
    ap = Arguments()
    ap.add_argument("full")
    ap.add_argument("black")
    ap.add_argument("--slsets", nargs="+", required=True)
    ap.add_argument("--influence", default="6", choices=["12", "6", "4"])
    ap.add_argument("--level", default="content/levels/characters.json")
    ap.add_argument("--spacing", type=float, default=None, help="G1/G2's grid spacing in metres (default the level's probes)")
    ap.add_argument("--reach", type=float, default=None, help="metres: clamp each centre's horizontal offset from the entity's axis")
    a = ap.parse_args()
    F, B = a.full, a.black
    ref = lambda d, p: pfm(f"{d}/reference-all-{p}.pfm")  # noqa: E731
    without = ref(F, "without")
    r = ref(F, "with") - without
    n = r - (ref(F, "half-with") - ref(F, "half-without"))
    occl = ref(B, "with") - without
    mask = pfm(f"{F}/mask-indirect-only.pfm")[:, :, 0] > 0.5
    base = f"sl-spheres-level-order-4-influence-{a.influence}"
    sl = effect(F, f"{base}-hierarchy-off-ref-all")
    terms = os.path.exists(f"{F}/image-{base}-terms-none-ref-all.pfm")  # the decomposition rows (F = 6, 12)
    if terms:
        rel = effect(F, f"{base}-terms-none-ref-all")
        sb = effect(F, f"{base}-terms-bounce-ref-all") - rel
        ss = effect(F, f"{base}-terms-shadow-ref-all") - rel
    level = json.load(open(a.level))
    ents = [e for e in level["entities"] if "sl" in e]
    if len(ents) != len(a.slsets):
        sys.exit(f"{a.level}: entities: {len(ents)} with sl (expected one .slset each, got {len(a.slsets)})")
    h, wd = mask.shape
    pos = room_positions(level, h, wd)
    Fv = float(a.influence)
    w = np.zeros((h, wd))
    for e, (_, foot, _), path in zip(ents, characters(level), a.slsets):
        for c, rad in world_spheres(e, foot, path, a.reach):
            t = np.linalg.norm(pos - c, axis=-1) / rad
            w = np.maximum(w, np.clip((Fv - t) / (Fv / 2), 0.0, 1.0))
    m3 = np.repeat(mask[:, :, None], 3, 2)
    w3 = np.repeat(w[:, :, None], 3, 2)
    ins = m3 & (w3 > 0)
    conv = float((r[m3] ** 2).sum() - (n[m3] ** 2).sum())

    def es(t, inside):
        """e* with t on `inside` and the converged reference elsewhere on the mask."""
        num = float(((t - r)[inside] ** 2).sum() - (n[inside] ** 2).sum())
        return math.sqrt(max(num, 0.0) / conv)

    def es_all(t):
        return es(t, m3)

    rr, nn = r[ins], n[ins]
    print(f"{F} + {B}, influence {a.influence}: {int(mask.sum())} indirect-only px, {int(ins.sum()) // 3} inside some "
          f"SL's influence (w > 0), {int((m3 & (w3 >= 1)).sum()) // 3} at w = 1")
    print(f"  share of ||r*||^2 inside: {(float((rr ** 2).sum() - (nn ** 2).sum())) / conv:.3f}; "
          f"SL's error energy inside / all: {float(((sl - r)[ins] ** 2).sum() - (nn ** 2).sum()) / float(((sl - r)[m3] ** 2).sum() - (n[m3] ** 2).sum()):.3f}")
    print(f"  reference inside: net mean {rr.mean():+.5f}, occlusion {occl[ins].mean():+.5f}; outside: net "
          f"{r[m3 & ~ins].mean():+.5f}, occlusion {occl[m3 & ~ins].mean():+.5f}")
    print(f"  SL as is (level row)                 e* {es_all(sl):.3f}")
    print(f"  A exact beyond the ball              e* {es(sl, ins):.3f}")
    blend = w3 * sl + (1 - w3) * (r - n)  # r − n = r*: only the w-weighted SL part carries error
    print(f"  B blended by w                       e* {es(blend, ins):.3f}")
    k = float((r - sl)[ins].mean())
    print(f"  C A + best constant inside ({k:+.5f}) e* {es(sl + k, ins):.3f}")
    # A smooth room-wide field inside instead of a constant: one affine function of world position over
    # every inside pixel and channel, fitted to r − SL (generous: it sees the reference).
    t = sl.copy()
    P = np.repeat(pos[:, :, None, :], 3, 2)[ins]
    X = np.concatenate([P, np.ones((P.shape[0], 1))], 1)
    c, *_ = np.linalg.lstsq(X, (r - sl)[ins], rcond=None)
    t[ins] += X @ c
    print(f"  C2 A + best affine field inside      e* {es(t, ins):.3f}")
    for name, g in (("w = 0", m3 & (w3 <= 0)), ("0 < w < 1", m3 & (w3 > 0) & (w3 < 1)), ("w = 1", m3 & (w3 >= 1))):
        err = float(((sl - r)[g] ** 2).sum() - (n[g] ** 2).sum()) / conv
        rc = float((r[g] ** 2).sum() - (n[g] ** 2).sum()) / conv
        print(f"    {name:10s} {int(g.sum()) // 3:6d} px: share of ||r*||^2 {rc:.3f}, SL's error energy / ||r*||^2 {err:.3f}")
    # What a probe grid can carry: the best trilinear field on a grid of the level's probe spacing
    # (least squares to r − SL, generous: fitted to the reference, not transported), G1 beyond the ball
    # only, G2 everywhere (SL's near field kept, the field added on top), G3 the field alone (how
    # smooth the whole effect is at that spacing).
    sp = a.spacing or level["probes"]["spacing"]
    g = (pos - pos[mask].min(0)) / sp
    i0 = np.floor(g).astype(int)
    f = g - i0
    dims = i0[mask].max(0) + 2
    rows, cols, vals = [], [], []
    idx = np.flatnonzero(mask.ravel())
    for corner in range(8):
        o = np.array([(corner >> k) & 1 for k in range(3)])
        wt = np.prod(np.where(o, f, 1 - f), -1).ravel()[idx]
        node = np.ravel_multi_index(tuple((i0 + o).reshape(-1, 3)[idx].T), dims)
        rows.append(np.arange(idx.size)), cols.append(node), vals.append(wt)
    used, col = np.unique(np.concatenate(cols), return_inverse=True)
    M = np.zeros((idx.size, used.size))
    np.add.at(M, (np.concatenate(rows), col), np.concatenate(vals))
    win = (w.ravel()[idx] > 0)
    # A least-squares fit of k values to N noisy pixels also fits k/N of their noise energy (white
    # noise), so the fitted pixels' noise term is (1 − k/N)‖n‖² there, not ‖n‖².
    every = np.ones_like(win)
    for name, base_t, fit_on in (("G1 SL + grid field beyond the ball", sl, ~win), ("G2 SL + grid field everywhere", sl, every),
                                 ("G3 grid field alone, no SL", np.zeros_like(sl), every)):
        t = base_t.copy()
        for ch in range(3):
            y = (r - base_t)[:, :, ch].ravel()[idx]
            c, *_ = np.linalg.lstsq(M[fit_on], y[fit_on], rcond=None)
            tc = t[:, :, ch].ravel()
            tc[idx[fit_on]] += M[fit_on] @ c
            t[:, :, ch] = tc.reshape(h, wd)
        fit3 = np.zeros_like(m3)
        fit3[mask] = np.repeat(fit_on[:, None], 3, 1)
        k = int((np.abs(M[fit_on]).sum(0) > 0).sum())
        num = float(((t - r)[m3] ** 2).sum() - (n[m3 & ~fit3] ** 2).sum() - (1 - k / fit_on.sum()) * (n[fit3] ** 2).sum())
        print(f"  {name:36s} e* {math.sqrt(max(num, 0.0) / conv):.3f}  ({sp:g} m grid, {k} nodes, {int(fit_on.sum())} px fitted)")
    # H: the shell given SL's own first-order field, uncut (the influence-12 row, ~ unfaded at F ≤ 6's
    # shell), instead of the exact one: what probes that only reproduced SL's view of the spheres would add.
    wide = "sl-spheres-level-order-4-influence-12-hierarchy-off-ref-all"
    if a.influence != "12" and os.path.exists(f"{F}/image-{wide}.pfm"):
        t = w3 * sl + (1 - w3) * effect(F, wide)
        print(f"  H w·SL + (1 − w)·SL uncut (12) inside  e* {es(t, ins):.3f}")
    print(f"  E SL + (1 - w) exact inside          e* {es(sl + (1 - w3) * (r - n), ins):.3f}")
    if not terms:
        return 0
    A = np.stack([rel[ins], sb[ins], ss[ins], np.ones(int(ins.sum()))], 1)
    c, *_ = np.linalg.lstsq(A, r[ins], rcond=None)
    t = np.zeros_like(r)
    t[ins] = A @ c
    print(f"  D A + inside refit {np.round(c, 3)} (relight, bounce, shadow, const) e* {es(t, ins):.3f}")
    for cut in (0.25, 0.5, 0.75):  # a smaller ball: more of the near field left to the transport
        i2 = m3 & (w3 > cut)
        print(f"  A with the ball shrunk to w > {cut:4.2f} ({int(i2.sum()) // 3} px inside)  e* {es(sl, i2):.3f}")
    return 0


if __name__ == "__main__":
    run(main, "tools/sl_relight_bound.py FULL BLACK --slsets FOX.slset CESIUM.slset [--influence 6]", args=(2, None))
