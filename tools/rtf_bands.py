#!/usr/bin/python3
"""RTF's effect and its blocked term by distance from the nearest object, against the brute force (issue 14,
README "Sixth pass (session 10)").

Reads a `rtf_parts LEVEL W H N PARTS_DIR` folder and a `bounce accuracy --rows rtf --effect-images --out ACC_DIR`
folder of the same level and resolution. On the indirect-only pixels, by |q| (units of η: field.pfm × R_fade,
R_fade = (outer + Δr) in η, the argument R; cornell-5 4.7), prints the means of the reference effect, the GPU
row's effect, the GPU effect without RTF's two terms ("base": the relit probes' change, …), and of the
blocked term in each form rtf_parts writes (brute force ref-blocked; the probes' light with the exact
visibility and the exact clamped cosine, blocked-vis-exactcos; the order-4 OOF projected AT r with the exact
cosine, blocked-oofsh-exactcos; the same through the SH product and E_n, blocked-oof-at-r-nofade / with the
field's end, blocked-oof-at-r; Eq. 10's lookup, blocked-receiver; the GPU's, blocked-gpu). Then, per band,
the squared error of the GPU effect with its blocked term swapped for each form (Σ over RGB / indirect-only
pixels × 1e6): what each form would score.

usage: tools/rtf_bands.py PARTS_DIR ACC_DIR [R [RN [ROW]]]   (RN: the outermost sphere in η, default 4; ROW
default rtf-bounces-2-ref-all)
"""
import sys
import numpy as np

from effect_noise import read_pfm as pfm
from tool_input import run  # one line, exit 2 on bad input


def main():
    parts, acc = sys.argv[1], sys.argv[2]
    R = float(sys.argv[3]) if len(sys.argv) > 3 else 4.7
    rn = float(sys.argv[4]) if len(sys.argv) > 4 else 4.0
    row = sys.argv[5] if len(sys.argv) > 5 else "rtf-bounces-2-ref-all"
    g = lambda n: pfm(f"{parts}/{n}.pfm")
    mask = pfm(f"{acc}/mask-indirect-only.pfm")[:, :, 0] > 0.5
    q = g("field")[:, :, 0] * R
    ref = pfm(f"{acc}/reference-all-with.pfm") - pfm(f"{acc}/reference-all-without.pfm")
    gpu = pfm(f"{acc}/image-{row}.pfm") - pfm(f"{acc}/without-{row}.pfm")
    forms = ["ref-blocked", "blocked-vis-exactcos", "blocked-oofsh-exactcos", "blocked-oof-at-r-nofade",
             "blocked-oof-at-r", "blocked-receiver", "blocked-at-o", "blocked-gpu"]
    import os
    forms += [f for f in ("blocked-level", "blocked-eq3", "blocked-surface") if os.path.exists(f"{parts}/{f}.pfm")]  # seventh pass
    im = {n: g(n) for n in forms + ["rtf-interreflected", "ref-interreflected"]}
    base = gpu - (im["rtf-interreflected"] - im["blocked-gpu"])
    edges = sorted([e * R for e in (0, 0.15, 0.3, 0.45, 0.6, 0.75, 1.0, 1.2, 1.5, 3.0)] + [rn])
    edges = sorted(set(edges))
    n = mask.sum()
    print("|q|/eta  pixels  ref  gpu  base  ref-inter  rtf-inter | " + " ".join(forms))
    for a, b in zip(edges[:-1], edges[1:]):
        m = mask & (q >= a) & (q < b)
        if m.sum() == 0:
            continue
        print(f"{a:5.2f}-{b:5.2f} {int(m.sum()):5d} {ref[m].mean():+.4f} {gpu[m].mean():+.4f} {base[m].mean():+.4f} "
              f"{im['ref-interreflected'][m].mean():+.4f} {im['rtf-interreflected'][m].mean():+.4f} | "
              + " ".join(f"{im[f][m].mean():+.4f}" for f in forms))
    print("squared error with the GPU's blocked term swapped (sum over RGB / indirect-only pixels x 1e6)")
    print("|q|/eta       " + " ".join(f"{f[:14]:>14s}" for f in forms))
    total = dict.fromkeys(forms, 0.0)
    for a, b in zip(edges[:-1], edges[1:]):
        m = mask & (q >= a) & (q < b)
        if m.sum() == 0:
            continue
        line = []
        for f in forms:
            e = float((((base + im["rtf-interreflected"] - im[f]) - ref) ** 2)[m].sum()) / n * 1e6
            total[f] += e
            line.append(f"{e:14.1f}")
        print(f"{a:5.2f}-{b:5.2f}  " + " ".join(line))
    print("total        " + " ".join(f"{total[f]:14.1f}" for f in forms))


if __name__ == "__main__":
    run(main, "tools/rtf_bands.py PARTS_DIR ACC_DIR [R [RN [ROW]]]", args=(2, 5))
