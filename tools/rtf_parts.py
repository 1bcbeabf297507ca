#!/usr/bin/python3
"""What the dynamic objects' effect is made of, against RTF's two terms (issue 14, README Results "RTF").

Reads a `rtf_parts LEVEL W H N PARTS_DIR` folder and a `bounce accuracy --effect-images --out ACC_DIR`
folder of the same level and resolution, and prints, on the indirect-only pixels inside and outside the
rtf fields (field.pfm < 1), the means of: the reference effect (with − without, 1024 spp), its brute-force
split (interreflected, blocked, room = the rest), blocked-probes (the blocked term with the probes' SH
light), RTF's CPU terms (shade()) and RTF's GPU effect (the row's image − without).

usage: tools/rtf_parts.py PARTS_DIR ACC_DIR [ROW]   (ROW default rtf-bounces-2-ref-all)
"""
import sys
import numpy as np

from effect_noise import read_pfm as pfm
from tool_input import run  # one line, exit 2 on bad input


def main():
    parts, acc = sys.argv[1], sys.argv[2]
    row = sys.argv[3] if len(sys.argv) > 3 else "rtf-bounces-2-ref-all"
    g = lambda n: pfm(f"{parts}/{n}.pfm")
    ref = pfm(f"{acc}/reference-all-with.pfm") - pfm(f"{acc}/reference-all-without.pfm")
    gpu = pfm(f"{acc}/image-{row}.pfm") - pfm(f"{acc}/without-{row}.pfm")
    mask = pfm(f"{acc}/mask-indirect-only.pfm")[:, :, 0] > 0.5
    field = g("field")[:, :, 0]
    inter, blocked, room, bprobe = g("ref-interreflected"), g("ref-blocked"), g("ref-room"), g("blocked-probes")
    rinter, rblocked = g("rtf-interreflected"), g("rtf-blocked")
    cols = [("ref effect", ref), ("ref inter", inter), ("ref -blocked", -blocked), ("ref room", room),
            ("sum of 3", inter - blocked + room), ("-blocked probes", -bprobe), ("rtf inter", rinter),
            ("rtf -blocked", -rblocked), ("rtf cpu net", rinter - rblocked), ("rtf gpu net", gpu)]
    sets = [("indirect-only, all", mask), ("inside fields (<1)", mask & (field < 1)),
            ("inside, <0.5", mask & (field < 0.5)), ("inside, 0.5-1", mask & (field >= 0.5) & (field < 1)),
            ("outside fields", mask & (field >= 1))]
    print(f"{'pixels (mean over RGB)':24s} {'n':>6s} " + " ".join(f"{c:>15s}" for c, _ in cols))
    for name, m in sets:
        print(f"{name:24s} {m.sum():6d} " + " ".join(f"{v[m].mean():+15.5f}" for _, v in cols))
    # rel. RMSE of the effect against the reference, on the indirect-only pixels, for RTF's CPU
    # terms and for what RTF would give with the reference's own first-order terms.
    rms = np.sqrt((ref[mask] ** 2).mean())
    for name, e in (("rtf gpu", gpu), ("rtf cpu", rinter - rblocked), ("ref inter-blocked", inter - blocked),
                    ("ref inter-blocked (probes)", inter - bprobe)):
        print(f"indirect-only rel. RMSE {name:28s} {np.sqrt(((e - ref)[mask] ** 2).mean()) / rms:.4f}")


def shares(parts, acc, row):
    """Where the GPU row's whole-image effect error lies: pixels that see an object, direct-changed, indirect-only."""
    ref = pfm(f"{acc}/reference-all-with.pfm") - pfm(f"{acc}/reference-all-without.pfm")
    gpu = pfm(f"{acc}/image-{row}.pfm") - pfm(f"{acc}/without-{row}.pfm")
    mask = pfm(f"{acc}/mask-indirect-only.pfm")[:, :, 0] > 0.5
    field = pfm(f"{parts}/field.pfm")[:, :, 0]
    sees = field == 0
    e2 = ((gpu - ref) ** 2).sum(axis=2)
    total = e2.sum()
    for name, m in (("sees an object", sees), ("direct changed (shadow)", ~sees & ~mask), ("indirect-only", mask & ~sees)):
        print(f"share of the whole-image squared error, {name:24s} {m.sum():6d} px {e2[m].sum() / total:6.1%}")


def parts_and_shares():
    main()
    shares(sys.argv[1], sys.argv[2], sys.argv[3] if len(sys.argv) > 3 else "rtf-bounces-2-ref-all")


if __name__ == "__main__":
    run(parts_and_shares, "tools/rtf_parts.py PARTS_DIR ACC_DIR [ROW]", args=(2, 3))
