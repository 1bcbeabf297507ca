#!/usr/bin/python3
"""SL's shadow on the probes' light against the black-character reference's occlusion, in fine distance
bins per character and per surface (floor / walls), and the fit occl − relight = a·shadow + c (c: a
room-wide constant) per character (issue 13; README "SL's near-field shadow, session 17").

  tools/sl_near_bins.py FULL BLACK [INFLUENCE]     (folders as for tools/sl_bounce_split.py; default 0)
"""
import json, os, sys, numpy as np
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from effect_noise import read_pfm as pfm
from sl_parts import sl_parts, room_positions, characters, segment_distance
from tool_input import run  # one line, exit 2 on bad input


def main():
  F, B = sys.argv[1], sys.argv[2]
  lvl = json.load(open(os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'content', 'levels', 'characters.json')))
  without = pfm(f"{F}/reference-all-without.pfm")
  occl = (pfm(f"{B}/reference-all-with.pfm") - without).mean(-1)
  net = (pfm(f"{F}/reference-all-with.pfm") - without).mean(-1)
  mask = pfm(f"{F}/mask-indirect-only.pfm")[:, :, 0] > 0.5
  both, relight, b, s = (x.mean(-1) for x in sl_parts(F, sys.argv[3] if len(sys.argv) > 3 else "0"))
  pos, wall = room_positions(lvl, *mask.shape, walls=True)
  chars = characters(lvl)
  dist = np.stack([segment_distance(pos, p, ht) for _, p, ht in chars], -1)
  near, dmin = dist.argmin(-1), dist.min(-1)
  for k,(name,_,_) in enumerate(chars):
    for wname, wm in (("floor", wall==2), ("walls", (wall!=2)&(wall!=3))):
      print(name, wname)
      for lo in np.arange(0, 2.0, 0.1 if wname=="floor" else 0.25):
        hi = lo + (0.1 if wname=="floor" else 0.25)
        m = mask & (near==k) & wm & (dmin>=lo) & (dmin<hi)
        if m.sum() < 8: continue
        print(f"  {lo:.2f}-{hi:.2f} {m.sum():5d}px occl {occl[m].mean():+.5f} SLshadow {s[m].mean():+.5f} relight {relight[m].mean():+.5f} ratio(shadow/occl) {s[m].mean()/occl[m].mean():.2f}  (shadow+relight)/occl {(s[m]+relight[m]).mean()/occl[m].mean():.2f}")
  print("fit occl = a*shadow + c (+ relight as is), indirect-only pixels per character")
  for k,(name,_,_) in enumerate(chars):
    for lbl, m in (("all", mask&(near==k)), ("floor", mask&(near==k)&(wall==2)), ("<1m", mask&(near==k)&(dmin<1)), (">1m", mask&(near==k)&(dmin>=1))):
      A = np.stack([s[m], np.ones(m.sum())],1)
      c,*_ = np.linalg.lstsq(A, occl[m]-relight[m], rcond=None)
      print(f"  {name} {lbl}: a {c[0]:.3f} c {c[1]:+.5f}")


if __name__ == "__main__":
  run(main, "tools/sl_near_bins.py FULL BLACK [INFLUENCE]", args=(2, 3))
