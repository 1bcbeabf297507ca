#!/usr/bin/python3
"""SL's bounce and shadow on the characters, each against its own reference part (issue 13; README
"SL on the characters: the reference's bounce traced, session 12").

Session 11's decomposition (tools/sl_parts.py) compared each of SL's parts with the reference's NET
object effect only, so it could not say whether SL's bounce is wrong or merely outweighed by a
too-strong shadow. Here a second reference separates the net effect: the same level with the
characters black (every `sl` entity gets `"material": {"albedo": [0, 0, 0]}`; glTF base colour
factor 0 makes factor × texture 0, so the path tracer's characters reflect nothing but still block).
  r_occl   = ref_black_with − ref_without      what the characters take away (their blocking, every
                                               bounce of it, incl. the static surfaces' lost light)
  r_bounce = ref_with − ref_black_with         what they give back (their reflected light, every bounce)
  r        = r_occl + r_bounce                 the net effect `bounce accuracy` scores
Each part's noise is estimated as tools/effect_noise.py does, from the first-half references:
n_X = r_X − r_X(half); for r_bounce the two "with" renders' halves (correlated or not, the
difference of the two estimates is the right estimator). SL's parts are sl_parts.py's, from FULL's
decomposition rows at the cut F: relight (terms=none), bounce, shadow.
Printed per pixel group (indirect-only pixels; by distance from the nearer character; by character):
the reference parts' means and converged RMS, SL's parts against them (e* against the converged part,
the uncentred cosine, the least-squares scale of SL's part against the reference part — here a sound
figure, since each reference part is isolated), and the error of the net effect when one SL part is
replaced by the best scaling.

  bounce accuracy content/levels/characters.json --rows probes,sl --resolution 128x128 --spp 1024 \
      --frames 2 --effect-images --out FULL
  tools/sl_bounce_split.py --write-black content/levels/characters.json content/levels/characters-black.json
  bounce accuracy content/levels/characters-black.json --rows probes --resolution 128x128 \
      --spp 1024 --frames 2 --effect-images --out BLACK
  tools/sl_bounce_split.py FULL BLACK --influence 6
(the copy sits beside the level so its relative asset paths hold; delete it afterwards. Its name is
the level's with " (black)" added, so its static reference is rendered again under its own key: the
tool checks the two static references are equal.)

  tools/sl_bounce_split.py FULL BLACK --influence 0 --sl-bounce on
(uncut, session 16: FULL from `--rows sl`, whose rows "influence=0;terms=…;sl_bounce=off|on" hold the
uncut parts; README "SL's bounce on the characters, session 16")

usage: tools/sl_bounce_split.py FULL BLACK [--influence 6|12|0] [--sl-bounce off|on] [--level content/levels/characters.json]
       tools/sl_bounce_split.py --write-black LEVEL COPY
"""
import json
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from effect_noise import corrected, read_pfm as pfm  # noqa: E402
from tool_input import run  # one line, exit 2 on bad input
from sl_parts import arguments, pixel_groups, sl_parts  # noqa: E402


def ref(d, part):
    return pfm(f"{d}/reference-all-{part}.pfm")


def score(t, r, n):
    """(e*, cosine, scale) of t against the converged r* = r − n (noise n estimated, independent of t)."""
    r2, n2, t2 = float((r ** 2).sum()), float((n ** 2).sum()), float((t ** 2).sum())
    conv = r2 - n2
    floor = math.sqrt(n2 / r2) if r2 > 0 else float("nan")
    e = math.sqrt(float(((t - r) ** 2).sum()) / r2) if r2 > 0 else float("nan")
    es = corrected(e, floor) if floor < 1 else float("nan")
    cos = float((t * r).sum()) / math.sqrt(t2 * conv) if t2 > 0 and conv > 0 else float("nan")
    scale = float((t * r).sum()) / t2 if t2 > 0 else float("nan")
    return es, cos, scale, floor


def write_black(src, dst):
    level = json.load(open(src))
    level["name"] += " (black)"
    for e in level["entities"]:
        if "sl" in e:
            e["material"] = {"albedo": [0, 0, 0]}
    json.dump(level, open(dst, "w"), indent=1)


def main():
    if len(sys.argv) == 4 and sys.argv[1] == "--write-black":
        write_black(sys.argv[2], sys.argv[3])
        return 0
    a = arguments("full", "black")
    F, B = a.full, a.black
    without = ref(F, "without")
    if np.abs(ref(B, "without") - without).max() > 0:
        sys.exit("sl_bounce_split.py: the two folders' references without the characters differ (expected one static scene)")
    half_without = ref(F, "half-without")
    r = ref(F, "with") - without
    occl = ref(B, "with") - without
    bnc = r - occl
    n = r - (ref(F, "half-with") - half_without)
    n_occl = occl - (ref(B, "half-with") - half_without)
    n_bnc = n - n_occl
    mask = pfm(f"{F}/mask-indirect-only.pfm")[:, :, 0] > 0.5
    if (mask != (pfm(f"{B}/mask-indirect-only.pfm")[:, :, 0] > 0.5)).any():
        sys.exit("sl_bounce_split.py: the two folders' indirect-only masks differ (expected the same characters)")
    both, relight, sl_b, sl_s = sl_parts(F, a.influence, a.sl_bounce)
    groups = pixel_groups(json.load(open(a.level)), mask)
    print(f"{F} + {B}, influence {a.influence}, sl_bounce {a.sl_bounce}")
    for label, m in groups:
        if m.sum() < 16:
            continue
        m3 = np.repeat(m[:, :, None], 3, 2)
        rr, nn, ro, no, rb, nb = r[m3], n[m3], occl[m3], n_occl[m3], bnc[m3], n_bnc[m3]
        rms = lambda x, y: math.sqrt(max(float((x ** 2).sum() - (y ** 2).sum()), 0.0) / x.size)
        print(f"{label}: {int(m.sum())} px; reference mean / converged rms: net {rr.mean():+.5f} / {rms(rr, nn):.5f}, "
              f"occlusion {ro.mean():+.5f} / {rms(ro, no):.5f}, bounce {rb.mean():+.5f} / {rms(rb, nb):.5f}")
        rows = (("SL bounce vs ref bounce", sl_b[m3], rb, nb),
                ("SL shadow vs ref occlusion", sl_s[m3], ro, no),
                ("SL relight vs ref occlusion", relight[m3], ro, no),
                ("SL relight+shadow vs occl.", (relight + sl_s)[m3], ro, no),
                ("SL net vs ref net", both[m3], rr, nn))
        for name, t, x, y in rows:
            es, cos, scale, floor = score(t, x, y)
            print(f"  {name:28s} SL mean {t.mean():+.5f} | e* {es:.3f} cos {cos:+.3f} scale {scale:+.2f} (floor {floor:.3f})")
        # Joint fit of relight and shadow against the occlusion part alone (the bounce has its own reference).
        A = np.stack([relight[m3], sl_s[m3]], 1)
        c, *_ = np.linalg.lstsq(A, ro, rcond=None)
        es, *_ = score(A @ c, ro, no)
        print(f"  best {c[0]:.2f} relight + {c[1]:.2f} shadow vs ref occlusion: e* {es:.3f}")
        # The net effect with SL's bounce replaced by the converged reference bounce: its error is
        # (relight + shadow) − r_occl*, over ‖r*‖: e*² = (‖t − r_occl‖² − ‖n_occl‖²) / (‖r‖² − ‖n‖²).
        t = (relight + sl_s)[m3]
        conv = float((rr ** 2).sum() - (nn ** 2).sum())
        num = float(((t - ro) ** 2).sum() - (no ** 2).sum())
        print(f"  {'net, SL bounce -> ref bounce':28s} e* {math.sqrt(max(num, 0.0) / conv):.3f}")
        es, *_ = score(t, rr, nn)
        print(f"  {'net, SL bounce -> 0':28s} e* {es:.3f}")
    return 0


if __name__ == "__main__":
    run(main, "tools/sl_bounce_split.py FULL BLACK [--influence 6|12|0] [--sl-bounce off|on] [--level L] | --write-black IN OUT", args=(2, None))
