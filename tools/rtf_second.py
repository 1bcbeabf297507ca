#!/usr/bin/python3
"""Why RTF's 2-bounce row scores worse than its 1-bounce row (issue 14, README "RTF's second bounce in
8 bits and where it lands, session 20").

Reads a `bounce accuracy LEVEL --rows rtf --effect-images --out ACC_DIR` folder and a `rtf_parts LEVEL W H N
PARTS_DIR` folder of the same level and resolution. With R the reference effect (with − without), T1 and T2
the GPU rows' effects and D = T2 − T1 (the second bounce as rendered), the change of the squared error is
  |T2 − R|² − |T1 − R|² = 2 D·(T1 − R) + |D|²
so the second bounce helps only where the first order is too dark (T1 < R). Prints:
  1. that change split by pixel class (the pixels that see an object, the ones whose direct light the objects
     change, the indirect-only ones) and by a region (default the bottom-left quarter-by-0.39 box: cornell-5's
     red box and truck), and the first-order parts there (sum over RGB, mean per pixel): the reference's
     interreflected, blocked (negated) and room terms (rtf_parts' brute force) against shade()'s interreflected
     light at 1 bounce and the GPU's blocked light as rtf_parts models it (blocked-gpu);
  2. D against the reference's own bounce ≥ 2 between the objects (ref-via-other, O) on the receivers:
     |D|², D·O/|D|² (a second bounce of this shape helps against an exact first order only where it is
     > ½) and D's correlation with shade()'s smooth (2 − 1) (C): what the 8-bit X adds to D;
  3. the noise of the reference in the comparison: the standard deviation of 2 D·(R − R_true), from the
     half-sample references (R − R_half estimates R's per-pixel noise);
  4. the corrected effect error of both rows with the receivers' first-order terms swapped for the
     reference's (blocked, single-bounce interreflected, the rest = direct change + room), with D, with C
     and with O (the reference's own second bounce, exact up to rtf_parts' noise);
  5. the reference's own second bounce O added at a scale a to the 1-bounce row (and to the 1/|q|² tail's
     1-bounce row when the run has it): |T1 + a O − R|² − |T1 − R|² = 2a O·(T1 − R) + a²|O|², so where the
     cross term O·(T1 − R) is positive no second bounce of O's shape helps at any a > 0, however exact —
     only a change to the first order can make 2 bounces better than 1 (README "RTF: the nearer
     object's occlusion of the other's light, session 24").

usage: tools/rtf_second.py ACC_DIR PARTS_DIR [Y0 X1]   (region: rows ≥ Y0·H, columns < X1·W; default 0.75 0.39)
"""
import csv
import itertools
import sys

import numpy as np

from effect_noise import read_pfm
from tool_input import BadInput, run  # one line, exit 2 on bad input


def main():
    acc, parts = sys.argv[1], sys.argv[2]
    if len(sys.argv) == 4:  # Y0 without X1: the region needs both (run() counts 2 to 4)
        raise BadInput("tools/rtf_second.py", "Y0 without X1", "ACC_DIR PARTS_DIR, or both Y0 and X1")
    y0, x1 = (float(sys.argv[3]), float(sys.argv[4])) if len(sys.argv) > 4 else (0.75, 0.39)
    ref = lambda n: read_pfm(f"{acc}/{n}.pfm")
    R = ref("reference-all-with") - ref("reference-all-without")
    Rh = ref("reference-all-half-with") - ref("reference-all-half-without")
    T1 = ref("image-rtf-bounces-1-ref-all") - ref("without-rtf-bounces-1-ref-all")
    T2 = ref("image-rtf-bounces-2-ref-all") - ref("without-rtf-bounces-2-ref-all")
    mask = ref("mask-indirect-only")[:, :, 0] > 0.5
    p = lambda n: read_pfm(f"{parts}/{n}.pfm")
    field = p("field")[:, :, 0]
    if field.shape != R.shape[:2]:
        raise BadInput(f"{parts}/field.pfm", f"{field.shape[1]}x{field.shape[0]}", f"the accuracy run's {R.shape[1]}x{R.shape[0]}")
    rI, rB, rRoom, rO = p("ref-interreflected"), p("ref-blocked"), p("ref-room"), p("ref-via-other")
    cI1, cI2, gB = p("rtf-interreflected-b1"), p("rtf-interreflected"), p("blocked-gpu")
    floor = None
    with open(f"{acc}/accuracy.csv") as f:
        for r in csv.DictReader(f):
            if r["technique"] == "rtf" and r["setting"] == "bounces=1;ref=all":
                floor = float(r["effect_noise_floor"])
    if floor is None:
        raise BadInput(f"{acc}/accuracy.csv", "no row rtf bounces=1;ref=all", "a bounce accuracy --rows rtf run")
    rr = np.sqrt((R ** 2).mean())

    def score(t):  # accuracy.csv's effect_rel_rmse_corrected
        e = np.sqrt(((t - R) ** 2).mean()) / rr
        return np.sqrt(max(e * e - floor * floor, 0.0) / (1.0 - floor * floor))

    D, C = T2 - T1, cI2 - cI1
    sees = field == 0
    recv = ~sees
    H, W = field.shape
    region = np.zeros_like(mask)
    region[int(round(y0 * H)):, :int(round(x1 * W))] = True
    delta = ((T2 - R) ** 2 - (T1 - R) ** 2).sum(axis=2)
    cross = 2.0 * (D * (T1 - R)).sum(axis=2)
    print(f"rows: 1 bounce {score(T1):.5f}, 2 bounces {score(T2):.5f} (corrected effect error); "
          f"Σ|T2 − R|² − Σ|T1 − R|² = {delta.sum():+.4f} (cross {cross.sum():+.4f}, |D|² {(D ** 2).sum():.4f})")
    cols = {"R": R, "T1": T1, "D": D, "T1-R": T1 - R, "ref inter": rI, "ref -blocked": -rB, "ref room": rRoom,
            "ref b>=2": rO, "rtf inter 1": cI1, "gpu -blocked": -gB}
    print(f"{'pixels':28s} {'n':>5s} {'delta':>8s} {'cross':>8s} " + " ".join(f"{c:>12s}" for c in cols))
    classes = (("sees an object", sees), ("direct changed", recv & ~mask), ("indirect-only", recv & mask))
    for where, m0 in (("all", np.ones_like(mask)), ("region", region), ("outside region", ~region)):
        for name, m1 in classes:
            m = m0 & m1
            if not m.any():
                continue
            print(f"{where + ', ' + name:28s} {m.sum():5d} {delta[m].sum():+8.4f} {cross[m].sum():+8.4f} "
                  + " ".join(f"{v[m].sum(axis=-1).mean():+12.5f}" for v in cols.values()))
    for where, m in (("receivers", recv), ("region receivers", recv & region), ("other receivers", recv & ~region)):
        Dm, Om, Cm = D[m], rO[m], C[m]
        print(f"{where:18s} D: Σ {Dm.sum():.3f} |D|² {(Dm ** 2).sum():.5f} D·O/|D|² {(Dm * Om).sum() / max((Dm ** 2).sum(), 1e-30):.3f}"
              f" | C: Σ {Cm.sum():.3f} |C|² {(Cm ** 2).sum():.5f} C·O/|C|² {(Cm * Om).sum() / max((Cm ** 2).sum(), 1e-30):.3f}"
              f" | O: Σ {Om.sum():.3f} | corr(D, C) {np.corrcoef(Dm.ravel(), Cm.ravel())[0, 1]:.3f}")
    sd = 2.0 * np.sqrt((D ** 2 * (R - Rh) ** 2).sum())
    print(f"reference noise in the cross term: sd {sd:.4f} against the change {delta.sum():+.4f} ({delta.sum() / sd:+.1f} sd)")
    swaps = {"blocked": gB - rB, "inter1": (rI - rO) - cI1, "rest": (R - rI + rB) - (T1 - cI1 + gB)}
    for k in range(4):
        for combo in itertools.combinations(swaps, k):
            t1 = T1.copy()
            for c in combo:
                t1[recv] += swaps[c][recv]
            a, b, c2, o = score(t1), score(t1 + D), score(t1 + C * recv[..., None]), score(t1 + rO * recv[..., None])
            print(f"receivers' {'+'.join(combo) or 'nothing':24s} swapped for the reference's: 1 bounce {a:.5f}, "
                  f"+ D {b:.5f} ({b - a:+.5f}), + C {c2:.5f} ({c2 - a:+.5f}), + O {o:.5f} ({o - a:+.5f})")
    O = rO * recv[..., None]
    rows = [("as rendered", T1)]
    try:
        rows.append(("tail 1 bounce", ref("image-rtf-tail-0.01-bounces-1-ref-all") - ref("without-rtf-tail-0.01-bounces-1-ref-all")))
    except (OSError, BadInput):  # a run without the tail row (the shipped rows have none)
        pass
    for name, t1 in rows:
        cross_o = 2.0 * (O * (t1 - R)).sum()
        sd_o = 2.0 * np.sqrt((O ** 2 * (R - Rh) ** 2).sum())  # the reference's noise in that cross term
        print(f"{name}: 2 O·(T1 − R) {cross_o:+.4f} (reference noise sd {sd_o:.4f}, {cross_o / max(sd_o, 1e-30):+.1f} sd), "
              f"|O|² {(O ** 2).sum():.5f}; T1 {score(t1):.5f}, + a O at a = 0.25, 0.5, 1, 2: "
              + ", ".join(f"{score(t1 + a * O):.5f}" for a in (0.25, 0.5, 1.0, 2.0)))


if __name__ == "__main__":
    run(main, "tools/rtf_second.py ACC_DIR PARTS_DIR [Y0 X1]", args=(2, 4))
