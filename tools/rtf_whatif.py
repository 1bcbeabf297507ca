#!/usr/bin/python3
"""What RTF's object-effect error would be with one of rtf_parts' what-if forms of the interreflected light
(issue 14, README "RTF's first order on cornell-5, session 17").

Reads a `rtf_parts LEVEL 128 128 16 PARTS_DIR` folder and a `bounce accuracy LEVEL --rows rtf --resolution 128x128
--effect-images --out ACC_DIR` folder of the same level. The GPU row's effect (image − without) has its
interreflected light swapped for a what-if: t' = t − rtf-interreflected + rtf-interreflected-NAME (both 2 bounces,
gi::rtf::shade() on the CPU, on the receiver pixels; the pixels that see an object keep the row's value), and for
the room's visibility t' = t − ref-interreflected-hidden (the light the room hides from r, which the field adds).
Prints e = ||t' − r|| / ||r|| over the whole image (accuracy.csv's effect_rel_rmse) and the noise-corrected
e* = sqrt((e² − f²) / (1 − f²)) with the row's effect_noise_floor f (its effect_rel_rmse_corrected), and the
squared error on the indirect-only pixels (Σ RGB / pixels × 1e6).

usage: tools/rtf_whatif.py PARTS_DIR ACC_DIR [ROW]   (ROW default rtf-bounces-2-ref-all; a bounces-1 row swaps
rtf-interreflected-b1 for the what-ifs written at 1 bounce, rtf-interreflected-NAME-b1, where rtf_parts writes one)
"""
import csv
import os
import sys

import numpy as np

from effect_noise import read_pfm
from tool_input import run  # one line, exit 2 on bad input

WHATIFS = ("albedo", "lampvis", "both", "shadowed", "shadowed-lampvis", "lampray", "shadowed-lampray")  # lampray*: -b1 only


def fail(path, what, expected):
    print(f"{path}: {what} (expected {expected})", file=sys.stderr)
    sys.exit(2)


def load(path):
    if not os.path.isfile(path):
        fail(path, "missing", "a PFM written by rtf_parts or bounce accuracy --effect-images")
    try:
        return read_pfm(path)
    except (OSError, ValueError) as e:
        fail(path, f"unreadable: {e}", "a PFM image")


def main():
    if len(sys.argv) not in (3, 4):
        fail("rtf_whatif.py", f"{len(sys.argv) - 1} arguments", "PARTS_DIR ACC_DIR [ROW]")
    parts, acc = sys.argv[1], sys.argv[2]
    row = sys.argv[3] if len(sys.argv) > 3 else "rtf-bounces-2-ref-all"
    ref = load(f"{acc}/reference-all-with.pfm") - load(f"{acc}/reference-all-without.pfm")
    gpu = load(f"{acc}/image-{row}.pfm") - load(f"{acc}/without-{row}.pfm")
    mask = load(f"{acc}/mask-indirect-only.pfm")[:, :, 0] > 0.5
    one = "bounces-1" in row  # a 1-bounce row: its CPU term and the what-ifs baked at 1 bounce (-b1)
    inter = load(f"{parts}/rtf-interreflected{'-b1' if one else ''}.pfm")
    if inter.shape != ref.shape:
        fail(f"{parts}/rtf-interreflected.pfm", f"{inter.shape[1]}x{inter.shape[0]}", f"the accuracy run's {ref.shape[1]}x{ref.shape[0]}")
    floor = None
    with open(f"{acc}/accuracy.csv") as f:
        for r in csv.DictReader(f):
            if r["technique"] == "rtf" and r["setting"].replace("=", "-").replace(";", "-") == row.replace("rtf-", "", 1):
                floor = float(r["effect_noise_floor"])
    if floor is None:
        fail(f"{acc}/accuracy.csv", f"no row {row}", "a row of the accuracy run named as its image files")
    rr = np.sqrt((ref ** 2).mean())

    def score(name, t):
        e = np.sqrt(((t - ref) ** 2).mean()) / rr
        c = np.sqrt(max(e * e - floor * floor, 0.0) / (1.0 - floor * floor))
        sq = ((t - ref)[mask] ** 2).sum(axis=-1).mean() * 1e6
        print(f"{name:36s} effect {e:.4f}  corrected {c:.4f}  indirect-only squared error {sq:8.1f}")

    score(f"{row} (as rendered)", gpu)
    for name in WHATIFS:
        path = f"{parts}/rtf-interreflected-{name}{'-b1' if one else ''}.pfm"
        if os.path.isfile(path):
            score(f"what-if {name}", gpu - inter + load(path))
    score("what-if room visibility", gpu - load(f"{parts}/ref-interreflected-hidden.pfm"))


if __name__ == "__main__":
    run(main, "tools/rtf_whatif.py PARTS_DIR ACC_DIR [ROW]", args=(2, 3))
