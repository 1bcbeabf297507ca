#!/usr/bin/python3
"""The blocked term's light four ways and the second inter-object bounce, against the brute force (issue 14,
README Results "RTF", "Fifth pass").

Reads a `rtf_parts LEVEL W H N PARTS_DIR` folder and a `bounce accuracy --rows rtf --effect-images --out ACC_DIR`
folder of the same level and resolution. On the indirect-only pixels:
1. by distance band (field.pfm: < 0.5, 0.5–1, inside, outside the fields) the means of the brute-force
   blocked light (ref-blocked), blocked-probes (the probes' SH light with the exact visibility), shade()'s
   blocked term and rtf_parts' four variants (blocked-receiver, blocked-shape-o, blocked-at-o, blocked-gpu),
   then each blocked term's RMSE against ref-blocked and against blocked-probes inside the fields, and the
   RMSE of (rtf-interreflected − that term) against the reference effect;
2. where the `bounces=2` row differs from `bounces=1`: both rows' RMSE against the reference effect and
   against the brute-force first order (ref-interreflected − ref-blocked: the objects' terms without the
   room's own bounces, which RTF does not model).

usage: tools/rtf_blocked.py PARTS_DIR ACC_DIR
"""
import sys
import numpy as np

from effect_noise import read_pfm as pfm
from tool_input import run  # one line, exit 2 on bad input


def rms(x):
    return float(np.sqrt((x ** 2).mean()))


def main():
    parts, acc = sys.argv[1], sys.argv[2]
    g = lambda n: pfm(f"{parts}/{n}.pfm")
    mask = pfm(f"{acc}/mask-indirect-only.pfm")[:, :, 0] > 0.5
    field = g("field")[:, :, 0]
    ref = pfm(f"{acc}/reference-all-with.pfm") - pfm(f"{acc}/reference-all-without.pfm")
    row = lambda r: pfm(f"{acc}/image-{r}.pfm") - pfm(f"{acc}/without-{r}.pfm")
    terms = ["ref-blocked", "blocked-probes", "rtf-blocked", "blocked-receiver", "blocked-shape-o", "blocked-at-o", "blocked-gpu"]
    im = {n: g(n) for n in terms + ["rtf-interreflected", "ref-interreflected"]}
    print("band n " + " ".join(terms))
    for name, m in [("<0.5", field < 0.5), ("0.5-1", (field >= 0.5) & (field < 1)), ("inside", field < 1), ("outside", field >= 1)]:
        m = m & mask
        print(name, int(m.sum()), " ".join(f"{im[n][m].mean():+.4f}" for n in terms))
    inside = mask & (field < 1)
    print("inside the fields: RMSE against ref-blocked / blocked-probes; net (rtf-interreflected - term) against the reference effect")
    for n in terms[1:]:
        net = im["rtf-interreflected"] - im[n]
        print(f"  {n:18s} {rms((im[n] - im['ref-blocked'])[inside]):.5f} / {rms((im[n] - im['blocked-probes'])[inside]):.5f}"
              f"   net {rms((net - ref)[mask]):.5f}")
    e1, e2 = row("rtf-bounces-1-ref-all"), row("rtf-bounces-2-ref-all")
    first = im["ref-interreflected"] - im["ref-blocked"]
    m = mask & (np.abs(e2 - e1).max(axis=2) > 0.0)
    print(f"{int(m.sum())} indirect-only pixels where 2 bounces differ from 1 (mean difference {(e2 - e1)[m].mean():+.6f}, RMS {rms((e2 - e1)[m]):.6f}):")
    for name, t in [("reference effect", ref), ("brute-force first order", first)]:
        r1, r2 = rms((e1 - t)[m]), rms((e2 - t)[m])
        print(f"  vs {name:24s} 1 bounce {r1:.5f}, 2 bounces {r2:.5f} ({r2 - r1:+.6f}); mean target {t[m].mean():+.5f}, 1 bounce {e1[m].mean():+.5f}")


if __name__ == "__main__":
    run(main, "tools/rtf_blocked.py PARTS_DIR ACC_DIR", args=(2, 2))
