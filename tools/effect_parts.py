#!/usr/bin/python3
"""Where a technique's object-effect error comes from (README Results "RTF", issue 14).

Reads a `bounce accuracy --effect-images --out DIR` folder (image-<row>.pfm, without-<row>.pfm,
reference-<kind>-with|without.pfm, mask-indirect-only.pfm) and prints, on the whole image and on the
indirect-only pixels (the mask bounce accuracy wrote), the reference effect's RMS and
mean, the technique's, their error (rel. RMSE, = accuracy.csv's) and the signed mean of the error.
With --parts A=DIR1 B=DIR2 the same row from other folders (e.g. renders with one term switched off) is
split into parts: part = that folder's effect, so a term's share of the error can be read off.

usage: tools/effect_parts.py DIR ROW [NAME=DIR2 ...]   (ROW e.g. rtf-bounces-2-ref-all)
"""
import sys
import numpy as np

from effect_noise import read_pfm as pfm  # one PFM reader for the tools (this folder is on sys.path)


def stats(name, et, er, mask):
    et, er = et[mask], er[mask]
    rms_r = np.sqrt((er ** 2).mean())
    err = np.sqrt(((et - er) ** 2).mean())
    print(f"  {name:28s} ref rms {rms_r:.5f} mean {er.mean():+.5f} | tech rms {np.sqrt((et**2).mean()):.5f} "
          f"mean {et.mean():+.5f} | rel err {err / rms_r:.4f} signed mean err {(et - er).mean() / rms_r:+.4f} (of ref rms)")


def main():
    d, row = sys.argv[1], sys.argv[2]
    kind = row.rsplit('ref-', 1)[1] if 'ref-' in row else 'all'  # the row's reference kind (its ref= setting)
    ref = pfm(f"{d}/reference-{kind}-with.pfm") - pfm(f"{d}/reference-{kind}-without.pfm")
    mask = pfm(f"{d}/mask-indirect-only.pfm")[:, :, 0] > 0.5
    whole = np.ones(mask.shape, bool)
    tech = pfm(f"{d}/image-{row}.pfm") - pfm(f"{d}/without-{row}.pfm")
    print(f"{row}: {mask.sum()} indirect-only pixels of {mask.size}")
    for label, m in (("whole image", whole), ("indirect-only", mask)):
        print(label)
        stats("technique", tech, ref, m)
        for arg in sys.argv[3:]:
            name, d2 = arg.split('=', 1)
            part = pfm(f"{d2}/image-{row}.pfm") - pfm(f"{d2}/without-{row}.pfm")
            stats(name + " alone", part, ref, m)
            stats("technique without " + name, tech - part, ref, m)


if __name__ == '__main__':
    main()
