#!/usr/bin/python3
"""Every diagnostic tool in tools/ on bad input answers one line on stderr and exits 2, never a traceback
(the brief's bad-input rule; tools/tool_input.py). Cases per tool: too few arguments; folders that do not
exist; folders whose images are truncated, hostile (a size of 2^40 pixels) or not PFM at all. Also
read_pfm itself on each bad image (BadInput naming the file) and on a good one (the pixels back, rows
top-down).

  bad_input_test.py TOOLS_DIR       (ctest: tools.bad_input)
"""
import os
import struct
import subprocess
import sys
import tempfile

TOOLS = ["effect_noise", "effect_parts", "rtf_bands", "rtf_blocked", "rtf_bounce2", "rtf_parts", "rtf_second", "rtf_whatif",
         "sl_bounce_split", "sl_dnrt_split", "sl_near_bins", "sl_parts", "sl_relight_bound"]
# The images the tools open first (accuracy --effect-images and rtf_parts folders).
IMAGES = ["reference-all-with", "reference-all-without", "reference-all-half-with", "reference-all-half-without",
          "mask-indirect-only", "rtf-interreflected", "field", "image-rtf-bounces-2-ref-all",
          "without-rtf-bounces-2-ref-all"]
BAD = {
    "truncated": b"PF\n4 4\n-1.0\n" + b"\0" * 21,  # not even whole floats
    "hostile": b"PF\n1048576 1048576\n-1.0\n" + b"\0" * 48,
    "garbage": b"{ this is not an image }\n",
    "badsize": b"PF\nfour 4\n-1.0\n",
}
failures = []


def check(name, argv):
    r = subprocess.run([sys.executable] + argv, capture_output=True, text=True, timeout=120,
                       env={k: v for k, v in os.environ.items() if k != "BOUNCE_TOOL_TRACEBACK"})
    lines = [l for l in r.stderr.splitlines() if l.strip()]
    if r.returncode != 2 or len(lines) != 1 or "Traceback" in r.stderr:
        failures.append(f"{name}: exit {r.returncode}, stderr {r.stderr.strip()[:400]!r}")


def main():
    tools = sys.argv[1]
    sys.path.insert(0, tools)
    from effect_noise import read_pfm
    from tool_input import BadInput
    with tempfile.TemporaryDirectory() as tmp:
        folders = {}
        for kind, data in BAD.items():
            d = os.path.join(tmp, kind)
            os.mkdir(d)
            for img in IMAGES:
                with open(os.path.join(d, img + ".pfm"), "wb") as f:
                    f.write(data)
            folders[kind] = d
            try:
                read_pfm(os.path.join(d, "field.pfm"))
                failures.append(f"read_pfm accepted a {kind} image")
            except BadInput as e:
                if os.path.join(d, "field.pfm") not in str(e):
                    failures.append(f"read_pfm's {kind} error does not name the file: {e}")
        good = os.path.join(tmp, "good.pfm")
        with open(good, "wb") as f:  # 2x1 RGB, little-endian, bottom row first
            f.write(b"PF\n1 2\n-1.0\n" + struct.pack("<6f", 1, 2, 3, 4, 5, 6))
        img = read_pfm(good)
        if img.shape != (2, 1, 3) or list(img[0, 0]) != [4, 5, 6] or list(img[1, 0]) != [1, 2, 3]:
            failures.append(f"read_pfm of a good image: {img.tolist()}")
        missing = os.path.join(tmp, "no-such-folder")
        for t in TOOLS:
            path = os.path.join(tools, t + ".py")
            check(f"{t} (no arguments)", [path])
            one = t in ("effect_noise", "sl_parts")  # these read one folder
            extra = lambda d: ["--slsets", f"{d}/fox.slset", f"{d}/cesium.slset"] if t == "sl_relight_bound" else []
            check(f"{t} (missing folders)", [path, missing] + ([] if one else [missing]) + extra(missing))
            for kind in ("truncated", "garbage"):  # the rest of BAD is read_pfm's alone (above)
                d = folders[kind]
                check(f"{t} ({kind} images)", [path, d] + ([] if one else [d]) + extra(d))
        # The escape hatch for a tool's own bugs: BOUNCE_TOOL_TRACEBACK=1 lets the exception through
        # with its traceback (exit 1), so a ValueError in a tool's arithmetic is not read as bad input.
        r = subprocess.run([sys.executable, os.path.join(tools, "effect_noise.py"), folders["garbage"]],
                           capture_output=True, text=True, timeout=120,
                           env=dict(os.environ, BOUNCE_TOOL_TRACEBACK="1"))
        if r.returncode != 1 or "Traceback" not in r.stderr or "BadInput" not in r.stderr:
            failures.append(f"BOUNCE_TOOL_TRACEBACK=1: exit {r.returncode}, stderr {r.stderr.strip()[-300:]!r}")
    for f in failures:
        print("FAIL", f)
    print(f"{len(TOOLS)} tools, {len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
