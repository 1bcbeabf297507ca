#!/usr/bin/python3
"""What SL's indirect-only object-effect error on a level is made of (issue 13; README "SL on the
characters: what the error is made of, session 11").

Reads a `bounce accuracy LEVEL --rows probes,sl --effect-images --out DIR` folder. SL's decomposition
rows (engine/gi/sl/technique.cpp, "terms=none|bounce|shadow", one fused pass with one term switched
off by a specialization constant) give, at the cut F of the command line, three parts of the row
"spheres=level;order=4;influence=F;hierarchy=off" (both terms):
  relight = effect(terms=none)              the probes' own change (relit: the objects' shadow on the
                                            static surfaces' bounce), SL's passes adding nothing
  bounce  = effect(terms=bounce) - relight  Eq. 12-14: the SLs' reflected light
  shadow  = effect(terms=shadow) - relight  Eq. 3/6 + 23: the SLs' shadow on the probes' light
(the shadow on the direct light is the shadow map's and lies outside the indirect-only mask).
For every part and their sum: mean and RMS on the indirect-only pixels, the error against the
reference effect corrected for the reference's noise (e*, = accuracy.csv's *_corrected), its
cosine with the converged effect (the uncentred correlation <t, r> / (|t| |r*|)), and the
least-squares scale of each part alone against the whole effect r (not against that part's own
share of r, which no reference isolates: it absorbs what the other parts miss, so read the joint fit
of the three parts, the last line, for how far each part is off). The same
split by world distance from the nearest character (pixels are ray-cast into the room's box from the
level camera; the characters are vertical segments at their t = 0 orbit positions) and by which
character is nearest (only for a level whose room is the "room-floor" … entities, characters.json;
other levels get the indirect-only line alone).

usage: tools/sl_parts.py DIR [--influence 12|6|0] [--sl-bounce off|on] [--level content/levels/characters.json]
"""
import json
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from effect_noise import corrected, read_pfm as pfm  # noqa: E402  one PFM reader and e* for the tools
from tool_input import Arguments, run  # one line, exit 2 on bad input


def effect(d, row):
    return pfm(f"{d}/image-{row}.pfm") - pfm(f"{d}/without-{row}.pfm")


def room_positions(level, h, w, walls=False):
    """World position of every pixel's first hit on the room's box (the static level is that box; the
    characters are not in the indirect-only mask), from the level's camera (glTF: looks down −Z); with
    walls=True also the index of the wall hit (below)."""
    cam = next(e for e in level["entities"] if "camera" in e)
    t = cam["transform"]
    eye = np.array(t["translation"], float)
    pitch, yaw, roll = (math.radians(a) for a in t.get("rotation_euler_deg", [0, 0, 0]))
    if abs(yaw) > 1e-9 or abs(roll) > 1e-9:
        sys.exit("sl_parts.py: camera with yaw or roll (expected a pitch only)")
    tan = math.tan(0.5 * math.radians(cam["camera"]["yfov_deg"]))
    jj, ii = np.meshgrid(np.arange(w), np.arange(h))
    x = (2.0 * (jj + 0.5) / w - 1.0) * tan * (w / h)
    y = (1.0 - 2.0 * (ii + 0.5) / h) * tan
    z = -np.ones_like(x)
    c, s = math.cos(pitch), math.sin(pitch)
    d = np.stack([x, c * y - s * z, s * y + c * z], -1)
    # The room's box: cornell.gltf's walls (x ±0.278, y 0…0.5488, z ±0.2796) × the entities' scale
    # (characters.json's "room-floor" …; cornell-1's "cornell-box", unscaled). Its inner blocks are
    # not in it: a pixel on a block gets the wall behind it.
    room = next(e for e in level["entities"] if e["id"] in ("room-floor", "cornell-box"))
    scale = room.get("transform", {}).get("scale", [1.0])[0]
    lo, hi = scale * np.array([-0.278, 0.0, -0.2796]), scale * np.array([0.278, 0.5488, 0.2796])
    with np.errstate(divide="ignore", invalid="ignore"):
        tx = np.where(d > 0, (hi - eye) / d, (lo - eye) / d)  # exit distance per axis (eye inside)
    tx = np.where(np.isfinite(tx), tx, np.inf)
    tt = tx.min(-1)
    if walls:  # which wall: 0/1 left/right (x), 2/3 floor/ceiling (y), 4/5 back/front (z)
        axis = tx.argmin(-1)
        return eye + tt[..., None] * d, 2 * axis + (np.take_along_axis(d, axis[..., None], -1)[..., 0] > 0)
    return eye + tt[..., None] * d


def characters(level):
    """(name, foot position at t = 0, height) per entity with an sl component: its orbit at t = 0
    (engine/scene/motion.cpp: centre + r(cos θ u + sin θ v), u = x, v = −z for the y axis)."""
    out = []
    for e in level["entities"]:
        if "sl" not in e:
            continue
        o = e.get("motion", {}).get("orbit")
        p = np.array(e["transform"].get("translation", [0, 0, 0]), float)
        if o:
            th = 2 * math.pi * o.get("phase", 0.0)
            centre = np.array(o["center"], float) if "center" in o else p  # motion.cpp: default the translation
            p = centre + o["radius"] * np.array([math.cos(th), 0.0, -math.sin(th)])
        height = 0.5 if "fox" in e["id"] else 1.5  # the Fox's back ≈ 0.5 m, CesiumMan ≈ 1.5 m (from the meshes)
        out.append((e["id"], p, height))
    return out


def segment_distance(q, foot, height):
    y = np.clip(q[..., 1], foot[1], foot[1] + height)
    return np.sqrt((q[..., 0] - foot[0]) ** 2 + (q[..., 1] - y) ** 2 + (q[..., 2] - foot[2]) ** 2)


def line(name, t, r, n, m, total_err2):
    t, r, n = t[m], r[m], n[m]
    r2, n2, t2 = float((r ** 2).sum()), float((n ** 2).sum()), float((t ** 2).sum())
    err = math.sqrt(float(((t - r) ** 2).sum()) / max(r2, 1e-300))
    floor = math.sqrt(n2 / max(r2, 1e-300))
    conv = r2 - n2  # ||r*||^2
    # Uncentred (no means removed): a cosine, not Pearson's correlation. ⟨t, r⟩ estimates ⟨t, r*⟩ (n ⟂ t).
    cos = float((t * r).sum()) / math.sqrt(t2 * conv) if t2 > 0 and conv > 0 else float("nan")
    scale = float((t * r).sum()) / t2 if t2 > 0 else float("nan")  # least-squares a in a*t ≈ r (the whole r)
    share = float(((t - r) ** 2).sum() - n2) / total_err2 if total_err2 else float("nan")
    es = corrected(err, floor) if floor < 1 else float("nan")
    print(f"  {name:26s} mean {t.mean():+.5f} rms {math.sqrt((t ** 2).mean()):.5f} | e* {es:.3f} "
          f"cos {cos:+.3f} scale alone {scale:+.2f} | err² / SL's {share:5.2f}")


def table(label, parts, r, n, m):
    rr, nn = r[m], n[m]
    if m.sum() < 16:
        return
    conv = float((rr ** 2).sum() - (nn ** 2).sum())
    floor = math.sqrt(float((nn ** 2).sum()) / float((rr ** 2).sum()))
    print(f"{label}: {int(m.sum()) // 3} px, reference mean {rr.mean():+.5f} rms {math.sqrt((rr ** 2).mean()):.5f} "
          f"(converged rms {math.sqrt(max(conv, 0) / m.sum()):.5f}, floor {floor:.3f})")
    return conv


def arguments(*folders):
    """The command line both SL tools take: the folders, then --influence and --level."""
    ap = Arguments()
    for name in folders:
        ap.add_argument(name)
    ap.add_argument("--influence", default="6", choices=["12", "6", "0"])  # the decomposition rows' cuts (0: uncut)
    # uncut only: the bounce part with the relit probes carrying SL's bounce ("probes": {"sl_bounce": true})
    ap.add_argument("--sl-bounce", default="off", choices=["off", "on"])
    ap.add_argument("--level", default="content/levels/characters.json")
    return ap.parse_args()


def sl_parts(d, influence, sl_bounce="off"):
    """SL's row with both terms and its parts (module docstring): both, relight, bounce, shadow. Uncut
    (influence "0") from the rows "influence=0;[terms=…;]sl_bounce=off|on" (engine/gi/sl/technique.cpp):
    only the bounce part changes with sl_bounce (the relit probes then carry it on)."""
    base = f"sl-spheres-level-order-4-influence-{influence}"
    if influence == "0":
        both = effect(d, f"{base}-sl_bounce-{sl_bounce}-ref-all")
        relight = effect(d, f"{base}-terms-none-sl_bounce-off-ref-all")
        bounce = effect(d, f"{base}-terms-bounce-sl_bounce-{sl_bounce}-ref-all") - relight
        shadow = effect(d, f"{base}-terms-shadow-sl_bounce-off-ref-all") - relight
        return both, relight, bounce, shadow
    if sl_bounce != "off":
        sys.exit("sl_parts.py: --sl-bounce on needs --influence 0 (the only rows with it)")
    both = effect(d, f"{base}-hierarchy-off-ref-all")
    relight = effect(d, f"{base}-terms-none-ref-all")
    bounce = effect(d, f"{base}-terms-bounce-ref-all") - relight
    shadow = effect(d, f"{base}-terms-shadow-ref-all") - relight
    return both, relight, bounce, shadow


def pixel_groups(level, mask, indent=""):
    """(label, pixel mask) pairs: the indirect-only pixels, and on the characters' room (the
    "room-floor" … entities) the same split by distance from the nearer character and by character."""
    groups = [("indirect-only", mask)]
    if any(e["id"] == "room-floor" for e in level["entities"]):
        pos = room_positions(level, *mask.shape)
        chars = characters(level)
        dist = np.stack([segment_distance(pos, p, ht) for _, p, ht in chars], -1)
        nearest, dmin = dist.argmin(-1), dist.min(-1)
        for lo, hi in ((0.0, 0.5), (0.5, 1.0), (1.0, 2.0), (2.0, 99.0)):
            groups.append((f"{indent}{lo:g}-{hi:g} m from a character", mask & (dmin >= lo) & (dmin < hi)))
        for k, (name, _, _) in enumerate(chars):
            groups.append((f"{indent}nearest {name}", mask & (nearest == k)))
    return groups


def main():
    a = arguments("dir")
    d, f = a.dir, a.influence
    level = json.load(open(a.level))
    r = pfm(f"{d}/reference-all-with.pfm") - pfm(f"{d}/reference-all-without.pfm")
    n = r - (pfm(f"{d}/reference-all-half-with.pfm") - pfm(f"{d}/reference-all-half-without.pfm"))
    mask = pfm(f"{d}/mask-indirect-only.pfm")[:, :, 0] > 0.5
    both, relight, bounce, shadow = sl_parts(d, f, a.sl_bounce)
    mask3 = np.repeat(mask[:, :, None], 3, 2)
    print(f"{d}, influence {f}: parts of the row with both terms; sum − both: max "
          f"{np.abs(relight + bounce + shadow - both)[mask3].max():.2e}")
    groups = pixel_groups(level, mask, "  ")
    total = None
    for label, m in groups:
        m3 = np.repeat(m[:, :, None], 3, 2)
        conv = table(label, None, r, n, m3)
        if conv is None:
            continue
        err2 = float(((both - r)[m3] ** 2).sum() - (n[m3] ** 2).sum())
        if total is None:
            total = err2
        print(f"  share of the level's squared error (noise removed): {err2 / total:.2f}")
        for name, t in (("SL (both terms + relight)", both), ("relight alone", relight), ("bounce", bounce),
                        ("shadow on probes' light", shadow), ("relight + shadow", relight + shadow),
                        ("nothing (0)", np.zeros_like(r))):
            line(name, t, r, n, m3, err2)
        A = np.stack([relight[m3], bounce[m3], shadow[m3]], 1)
        coef, *_ = np.linalg.lstsq(A, r[m3], rcond=None)
        fit = coef[0] * relight + coef[1] * bounce + coef[2] * shadow
        line(f"best {coef[0]:.2f}r+{coef[1]:.2f}b+{coef[2]:.2f}s", fit, r, n, m3, err2)


if __name__ == "__main__":
    run(main, "tools/sl_parts.py DIR [--influence 12|6|0] [--sl-bounce off|on] [--level L]", args=(1, None))
