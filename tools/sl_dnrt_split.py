#!/usr/bin/python3
"""SL's and DNRT's object effects term by term, on the same frames and references (issue 13, goal
"indirect-only error, cornell-1 < DNRT's best"; README "SL against DNRT term by term on cornell-1,
session 14").

Both techniques model the same two local terms on top of the same relit probes:
  bounce  the prop's reflected light (SL: pass 1 + Eq. 12-14; DNRT: c_j t_j, Eq. 8)
  shadow  the prop blocking the probes' light (SL: Eq. 3/6 on the probes, sl.shadow; DNRT: the
          anti-radiance -c_j k_j, Eq. 12-13, without the lamp: "lights_in_anti_radiance": false)
The level's black copy (tools/sl_bounce_split.py --write-black: the prop reflects nothing, blocks
the same) separates them for BOTH techniques and for the reference, with no engine switch:
  term        reference               SL (row ROW_SL)                 DNRT (row ROW_DNRT)
  bounce      ref_with - ref_black    SL(full) - SL(black)            DNRT(full) - DNRT(black)
  shadow      ref_black - ref_without SL(black) - relight             DNRT(black) - relight
(relight = SL's terms=none row: the relit probes' own change, the same in both folders; the tool
checks that). Printed per pixel group (indirect-only pixels; on a Cornell-box level also by the
wall of the room's box each pixel's ray meets, sl_parts.room_positions): the reference parts' means,
each technique's terms against the reference part (e*, cosine, least-squares scale) and SL's term
against DNRT's (sum ratio, cosine); then the net effect's e* with one of SL's terms swapped for
DNRT's, which says which term holds the gap between the two techniques.

  bounce accuracy content/levels/cornell-1.json --rows dnrt,sl --resolution 128x128 --spp 512 \\
      --frames 3 --effect-images --out FULL
  tools/sl_bounce_split.py --write-black content/levels/cornell-1.json content/levels/cornell-1-black.json
  bounce accuracy content/levels/cornell-1-black.json --rows dnrt,sl (same options) --out BLACK
  tools/sl_dnrt_split.py FULL BLACK --level content/levels/cornell-1.json

usage: tools/sl_dnrt_split.py FULL BLACK [--level L] [--sl-row ROW] [--dnrt-row ROW]
"""
import json
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from effect_noise import read_pfm as pfm  # noqa: E402
from tool_input import Arguments, run  # one line, exit 2 on bad input
from sl_bounce_split import ref, score  # noqa: E402
from sl_parts import effect, room_positions  # noqa: E402

WALLS = ("left wall", "right wall", "floor", "ceiling", "back wall", "front wall")


def cosine(a, b):
    d = math.sqrt(float((a * a).sum()) * float((b * b).sum()))
    return float((a * b).sum()) / d if d > 0 else float("nan")


def main():
    ap = Arguments()
    ap.add_argument("full")
    ap.add_argument("black")
    ap.add_argument("--level", default="content/levels/cornell-1.json")
    ap.add_argument("--sl-row", default="sl-spheres-level-order-4-influence-12-hierarchy-off-ref-all")
    ap.add_argument("--relight-row", default="sl-spheres-level-order-4-influence-12-terms-none-ref-all")
    ap.add_argument("--dnrt-row", default="dnrt-sh-9-grid-32-intrusion-off-anti_radiance-improved-ref-all")
    a = ap.parse_args()
    F, B = a.full, a.black
    without = ref(F, "without")
    if np.abs(ref(B, "without") - without).max() > 0:
        sys.exit("sl_dnrt_split.py: the two folders' references without the prop differ (expected one static scene)")
    mask = pfm(f"{F}/mask-indirect-only.pfm")[:, :, 0] > 0.5
    if (mask != (pfm(f"{B}/mask-indirect-only.pfm")[:, :, 0] > 0.5)).any():
        sys.exit("sl_dnrt_split.py: the two folders' indirect-only masks differ (expected the same prop)")
    half_without = ref(F, "half-without")
    r = ref(F, "with") - without
    occl = ref(B, "with") - without
    bnc = r - occl
    n = r - (ref(F, "half-with") - half_without)
    n_o = occl - (ref(B, "half-with") - half_without)
    n_b = n - n_o
    relight = effect(F, a.relight_row)
    if np.abs(effect(B, a.relight_row) - relight)[mask].max() > 0:
        sys.exit("sl_dnrt_split.py: relight differs between the folders (expected the prop's albedo not to enter it)")
    sl, sl_black = effect(F, a.sl_row), effect(B, a.sl_row)
    dn, dn_black = effect(F, a.dnrt_row), effect(B, a.dnrt_row)
    terms = {"SL": (sl - sl_black, sl_black - relight, sl), "DNRT": (dn - dn_black, dn_black - relight, dn)}

    level = json.load(open(a.level))
    groups = [("indirect-only", mask)]
    if any(e["id"] == "cornell-box" for e in level["entities"]):
        _, wall = room_positions(level, *mask.shape, walls=True)
        groups += [(f"  {name} (room box)", mask & (wall == k)) for k, name in enumerate(WALLS)]
    print(f"{F} + {B}: SL {a.sl_row}, DNRT {a.dnrt_row}")
    for label, m in groups:
        if m.sum() < 16:
            continue
        m3 = np.repeat(m[:, :, None], 3, 2)
        print(f"{label}: {int(m.sum())} px; reference mean net {r[m3].mean():+.5f}, shadow {occl[m3].mean():+.5f}, "
              f"bounce {bnc[m3].mean():+.5f}; relight {relight[m3].mean():+.5f}")
        for name, (tb, ts, tn) in terms.items():
            eb, cb, sb, _ = score(tb[m3], bnc[m3], n_b[m3])
            es, cs, ss, _ = score(ts[m3], occl[m3], n_o[m3])
            en, cn, _, _ = score(tn[m3], r[m3], n[m3])
            print(f"  {name:4s} bounce {tb[m3].mean():+.5f} (e* {eb:.3f} cos {cb:+.2f} scale {sb:.2f}) | shadow "
                  f"{ts[m3].mean():+.5f} (e* {es:.3f} cos {cs:+.2f} scale {ss:.2f}) | net e* {en:.3f} cos {cn:+.2f}")
        (sb_, ss_, _), (db_, ds_, _) = terms["SL"], terms["DNRT"]
        print(f"  SL / DNRT: bounce {sb_[m3].sum() / db_[m3].sum():.2f}x (cos {cosine(sb_[m3], db_[m3]):+.2f}), "
              f"shadow {ss_[m3].sum() / ds_[m3].sum():.2f}x (cos {cosine(ss_[m3], ds_[m3]):+.2f})")
    m3 = np.repeat(mask[:, :, None], 3, 2)

    def es(t):
        return score(t[m3], r[m3], n[m3])[0]
    (sb_, ss_, _), (db_, ds_, _) = terms["SL"], terms["DNRT"]
    print("net e* on the indirect-only pixels, one term swapped:")
    print(f"  SL {es(relight + sb_ + ss_):.3f} | SL, bounce -> DNRT's {es(relight + db_ + ss_):.3f} | "
          f"SL, shadow -> DNRT's {es(relight + sb_ + ds_):.3f} | DNRT {es(relight + db_ + ds_):.3f} | "
          f"relight alone {es(relight):.3f} | relight + SL bounce {es(relight + sb_):.3f} | "
          f"relight + DNRT bounce {es(relight + db_):.3f} | relight + SL shadow {es(relight + ss_):.3f} | "
          f"relight + DNRT shadow {es(relight + ds_):.3f}")
    for name, (tb, ts, _) in terms.items():
        A = np.stack([relight[m3], tb[m3], ts[m3]], 1)
        c, *_ = np.linalg.lstsq(A, r[m3], rcond=None)
        print(f"  {name} best {c[0]:.2f} relight + {c[1]:.2f} bounce + {c[2]:.2f} shadow: "
              f"{es(c[0] * relight + c[1] * tb + c[2] * ts):.3f}")
    return 0


if __name__ == "__main__":
    run(main, "tools/sl_dnrt_split.py FULL BLACK [--level L] [--sl-row ROW] [--dnrt-row ROW]", args=(2, None))
