#!/usr/bin/python3
"""Where a technique's object-effect error comes from (README Results "RTF", issue 14).

Reads a `bounce accuracy --effect-images --out DIR` folder (image-<row>.pfm, without-<row>.pfm,
reference-<kind>-with|without.pfm, mask-indirect-only.pfm) and prints, on the whole image and on the
indirect-only pixels (the mask bounce accuracy wrote), the reference effect's RMS and
mean, the technique's, their error (rel. RMSE, = accuracy.csv's) and the signed mean of the error.
With --parts A=DIR1 B=DIR2 the same row from other folders (e.g. renders with one term switched off) is
split into parts: part = that folder's effect, so a term's share of the error can be read off.
Where DIR holds the first-half references (bounce accuracy --effect-images writes them), every line also
gives the error against the converged effect (e*, = accuracy.csv's *_corrected for the technique's
line) and the correlation <t, r> / (|t| |r*|) with it (the noise is independent of t, so <t, r>
estimates <t, r*>), and with parts the best least-squares a*part1 + b*part2 ... and its e*.

usage: tools/effect_parts.py DIR ROW [NAME=DIR2 ...]   (ROW e.g. rtf-bounces-2-ref-all)
"""
import sys
import numpy as np

from effect_noise import corrected, read_pfm as pfm  # one PFM reader and e* for the tools (this folder is on sys.path)
from tool_input import run  # one line, exit 2 on bad input
import os


def stats(name, et, er, mask, noise=None):
    et, er = et[mask], er[mask]
    rms_r = np.sqrt((er ** 2).mean())
    err = np.sqrt(((et - er) ** 2).mean())
    line = (f"  {name:28s} ref rms {rms_r:.5f} mean {er.mean():+.5f} | tech rms {np.sqrt((et**2).mean()):.5f} "
            f"mean {et.mean():+.5f} | rel err {err / rms_r:.4f} signed mean err {(et - er).mean() / rms_r:+.4f} (of ref rms)")
    if noise is not None:
        n2, r2 = float((noise[mask] ** 2).sum()), float((er ** 2).sum())
        floor = np.sqrt(n2 / r2)
        t2 = float((et ** 2).sum())
        corr = float((et * er).sum()) / np.sqrt(t2 * (r2 - n2)) if t2 > 0 and r2 > n2 else float("nan")
        line += f" | e* {corrected(err / rms_r, floor):.4f} corr {corr:+.3f}"
    print(line)


def best_fit(parts, er, mask):
    """Least-squares a_i over the parts' effects against the reference effect, and its e*."""
    a = np.stack([p[mask].ravel() for p in parts], 1)
    coef, *_ = np.linalg.lstsq(a, er[mask].ravel(), rcond=None)
    fit = np.zeros_like(er)
    for c, p in zip(coef, parts):
        fit = fit + c * p
    return coef, fit


def main():
    d, row = sys.argv[1], sys.argv[2]
    kind = row.rsplit('ref-', 1)[1] if 'ref-' in row else 'all'  # the row's reference kind (its ref= setting)
    ref = pfm(f"{d}/reference-{kind}-with.pfm") - pfm(f"{d}/reference-{kind}-without.pfm")
    noise = None
    if os.path.exists(f"{d}/reference-{kind}-half-with.pfm"):  # r_N - r_{N/2}: a sample of r_N's noise
        noise = ref - (pfm(f"{d}/reference-{kind}-half-with.pfm") - pfm(f"{d}/reference-{kind}-half-without.pfm"))
    mask = pfm(f"{d}/mask-indirect-only.pfm")[:, :, 0] > 0.5
    whole = np.ones(mask.shape, bool)
    tech = pfm(f"{d}/image-{row}.pfm") - pfm(f"{d}/without-{row}.pfm")
    print(f"{row}: {mask.sum()} indirect-only pixels of {mask.size}")
    parts = []
    for arg in sys.argv[3:]:
        name, d2 = arg.split('=', 1)
        parts.append((name, pfm(f"{d2}/image-{row}.pfm") - pfm(f"{d2}/without-{row}.pfm")))
    for label, m in (("whole image", whole), ("indirect-only", mask)):
        print(label)
        stats("technique", tech, ref, m, noise)
        for name, part in parts:
            stats(name + " alone", part, ref, m, noise)
            stats("technique without " + name, tech - part, ref, m, noise)
        if parts:
            coef, fit = best_fit([p for _, p in parts], ref, m)
            stats("best " + " + ".join(f"{c:.2f}*{n}" for c, (n, _) in zip(coef, parts)), fit, ref, m, noise)


if __name__ == "__main__":
    run(main, "tools/effect_parts.py DIR ROW [NAME=DIR2 ...]", args=(2, None))
