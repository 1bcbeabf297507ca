#!/usr/bin/python3
"""RTF's second inter-object bounce against the reference's (issue 14, README "Eighth pass (session 11)").

Reads a `rtf_parts LEVEL W H N PARTS_DIR` folder (ref-interreflected, ref-via-other: the part of it that came to
the first-hit object from ANOTHER object, i.e. the reference's bounces ≥ 2 between the objects; rtf-interreflected
at 2 bounces and rtf-interreflected-b1 at 1, from shade()) and a `bounce accuracy --rows rtf --effect-images --out
ACC_DIR` folder of the same level and resolution. On the indirect-only pixels, by |q| (η, as tools/rtf_bands.py),
prints the means of the reference's single-bounce interreflected light (ref-interreflected − ref-via-other), its
bounce ≥ 2 part, RTF's first bounce and its second (2 − 1), the reference effect, the GPU 1- and 2-bounce rows'
effects; then over all receivers the correlation of RTF's (2 − 1) with ref-via-other (per pixel and on 4×4
blocks, which average the reference's noise), and the squared error (Σ RGB / indirect-only pixels × 1e6) of the
GPU 1-bounce row with RTF's (2 − 1) added, with the reference's bounce ≥ 2 added instead, and scaled; the GPU rows
with the CPU's terms swapped for the exact-proxy-light what-if (rtf-interreflected-exact1/2) and for 3 and 4 bounces.

usage: tools/rtf_bounce2.py PARTS_DIR ACC_DIR [R]   (R: the field's end in η, default 4.7)
"""
import sys
import numpy as np

from effect_noise import read_pfm as pfm
from tool_input import run  # one line, exit 2 on bad input


def blocks(a, k=4):
    h, w = a.shape[0] // k * k, a.shape[1] // k * k
    return a[:h, :w].reshape(h // k, k, w // k, k, *a.shape[2:]).mean(axis=(1, 3))


def main():
    parts, acc = sys.argv[1], sys.argv[2]
    R = float(sys.argv[3]) if len(sys.argv) > 3 else 4.7
    g = lambda n: pfm(f"{parts}/{n}.pfm")
    mask = pfm(f"{acc}/mask-indirect-only.pfm")[:, :, 0] > 0.5
    q = g("field")[:, :, 0] * R
    ref = pfm(f"{acc}/reference-all-with.pfm") - pfm(f"{acc}/reference-all-without.pfm")
    eff = lambda row: pfm(f"{acc}/image-{row}.pfm") - pfm(f"{acc}/without-{row}.pfm")
    g1, g2 = eff("rtf-bounces-1-ref-all"), eff("rtf-bounces-2-ref-all")
    inter, other = g("ref-interreflected"), g("ref-via-other")
    r2, r1 = g("rtf-interreflected"), g("rtf-interreflected-b1")
    d = r2 - r1
    receivers = g("ref-interreflected").sum(axis=2) + g("ref-blocked").sum(axis=2) > 0  # pixels rtf_parts shaded
    n = mask.sum()
    print("|q|/eta     pixels  ref-single  ref-bounce>=2  rtf-b1  rtf-(2-1)  ref-effect  gpu-1  gpu-2   (means, RGB mean)")
    edges = [0, 1.4, 2.1, 2.8, 3.5, 4.0, 4.7, 6.0, 1e9]
    for a, b in zip(edges[:-1], edges[1:]):
        m = mask & (q >= a) & (q < b)
        if m.sum() == 0:
            continue
        f = lambda im: im[m].mean()
        print(f"{a:4.1f}-{min(b, 99):4.1f} {int(m.sum()):6d}  {f(inter - other):+.5f}  {f(other):+.5f}  {f(r1):+.5f}  {f(d):+.5f}  "
              f"{f(ref):+.5f}  {f(g1):+.5f}  {f(g2):+.5f}")
    m = mask
    f = lambda im: im[m].mean()
    print(f"all ind.  {int(m.sum()):6d}  {f(inter - other):+.5f}  {f(other):+.5f}  {f(r1):+.5f}  {f(d):+.5f}  {f(ref):+.5f}  {f(g1):+.5f}  {f(g2):+.5f}")
    for name, m in (("indirect-only", mask), ("all receivers", receivers)):
        a, b = d[m].sum(axis=-1), other[m].sum(axis=-1)
        mb = blocks(m.astype(float)) > 0.99
        ab, bb = blocks(d.sum(axis=2))[mb], blocks(other.sum(axis=2))[mb]
        print(f"{name}: sum rtf (2-1) {a.sum():.4f}, reference bounce>=2 {b.sum():.4f} (ratio {a.sum() / b.sum():.3f}); "
              f"correlation per pixel {np.corrcoef(a, b)[0, 1]:.3f}, 4x4 blocks {np.corrcoef(ab, bb)[0, 1]:.3f}")
    err = lambda im: float((((im - ref) ** 2)[mask]).sum()) / n * 1e6
    print("squared error on the indirect-only pixels (sum RGB / pixels x 1e6):")
    print(f"  gpu 1 bounce {err(g1):.1f}; gpu 2 bounces {err(g2):.1f}; gpu 1 + rtf (2-1) {err(g1 + d):.1f}; "
          f"gpu 1 + reference bounce>=2 {err(g1 + other):.1f}")
    for s in (2, 4):
        print(f"  gpu 1 + {s} x rtf (2-1) {err(g1 + s * d):.1f}")
    import os
    if os.path.exists(f"{parts}/rtf-interreflected-exact1.pfm"):  # the proxies' room light scaled to the traced one
        e1, e2 = g("rtf-interreflected-exact1"), g("rtf-interreflected-exact2")
        print(f"  exact proxy room light: 1 bounce {err(g1 + e1 - r1):.1f}, 2 bounces {err(g2 + e2 - r2):.1f}; its (2-1) "
              f"{(e2 - e1)[mask].sum():.4f} against the reference's {other[mask].sum():.4f}; single bounce mean "
              f"{e1[mask].mean():+.5f} against rtf-b1 {r1[mask].mean():+.5f} and the reference's {(inter - other)[mask].mean():+.5f}")
    for b in (3, 4):  # RTF at 3 and 4 bounces: the GPU 2-bounce row + the CPU's (b − 2)
        rb = g(f"rtf-interreflected-b{b}")
        print(f"  gpu 2 + rtf ({b}-2) = {b} bounces {err(g2 + rb - r2):.1f}; its extra bounces on the indirect-only pixels: "
              f"{(rb - r1)[mask].sum():.4f} against the reference's {other[mask].sum():.4f}")


if __name__ == "__main__":
    run(main, "tools/rtf_bounce2.py PARTS_DIR ACC_DIR [R]", args=(2, 3))
