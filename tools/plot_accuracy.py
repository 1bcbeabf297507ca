#!/usr/bin/python3
"""Chart of `bounce accuracy`'s accuracy.csv: error against GPU milliseconds, one marker per row.

    /usr/bin/python3 tools/plot_accuracy.py accuracy.csv accuracy.png

Left panel: rel_rmse (whole image vs the path-traced reference); right panel: effect_rel_rmse
(the dynamic objects' effect vs the reference's; 1 = as wrong as leaving it out). Each marker is
labelled "technique setting". The x axis is logarithmic when the GPU times span more than 10x
(cheap screen-space passes next to expensive GI nodes), linear otherwise. Rows with a NaN value
are left out of that panel.

Exit codes: 0 drawn, 2 bad input (one line on stderr), 3 matplotlib missing (Debian
python3-matplotlib), so the caller can tell "cannot plot here" from "plotting failed".
"""
import csv
import math
import sys

HEADER = ["technique", "setting", "gpu_ms", "rel_rmse", "effect_rel_rmse"]
LOG_X_SPAN = 10.0  # max/min GPU ms above which a log axis keeps the cheap rows apart


def read_rows(path):
    with open(path, newline="") as f:
        reader = csv.reader(f)
        header = next(reader, None)
        if header != HEADER:
            raise ValueError(f"{path}: line 1: header is {header} (expected {','.join(HEADER)})")
        rows = []
        for line, fields in enumerate(reader, start=2):
            if len(fields) != len(HEADER):
                raise ValueError(f"{path}: line {line}: {len(fields)} fields (expected {len(HEADER)})")
            try:
                numbers = [float(v) for v in fields[2:]]
            except ValueError:
                raise ValueError(f"{path}: line {line}: a value is not a number (expected gpu_ms,rel_rmse,effect_rel_rmse)")
            rows.append((fields[0], fields[1], *numbers))
        return rows


def main(argv):
    if len(argv) != 3:
        print("usage: plot_accuracy.py accuracy.csv accuracy.png", file=sys.stderr)
        return 2
    try:
        import matplotlib
        matplotlib.use("Agg")  # no display: write the file only
        import matplotlib.pyplot as plt
    except ImportError:
        print("plot_accuracy.py: matplotlib is missing (expected Debian python3-matplotlib)", file=sys.stderr)
        return 3
    try:
        rows = read_rows(argv[1])
    except (OSError, ValueError) as e:
        print(str(e), file=sys.stderr)
        return 2

    fig, axes = plt.subplots(1, 2, figsize=(12, 5), constrained_layout=True)
    techniques = sorted({r[0] for r in rows})
    colours = {t: plt.cm.tab10(i % 10) for i, t in enumerate(techniques)}
    times = [r[2] for r in rows if r[2] > 0 and math.isfinite(r[2])]
    log_x = bool(times) and max(times) / min(times) > LOG_X_SPAN
    for ax, column, title in ((axes[0], 3, "image rel. RMSE vs reference"),
                              (axes[1], 4, "object-effect rel. RMSE (1 = effect missing)")):
        for t in techniques:
            pts = [r for r in rows if r[0] == t and math.isfinite(r[column]) and math.isfinite(r[2])]
            ax.scatter([p[2] for p in pts], [p[column] for p in pts], color=colours[t], label=t, zorder=3)
            for p in pts:
                ax.annotate(f"{p[0]} {p[1]}", (p[2], p[column]), textcoords="offset points", xytext=(4, 4),
                            fontsize=7)
        if log_x:
            ax.set_xscale("log")
        ax.set_xlabel("GPU ms (median, the configuration's lighting passes)")
        ax.set_ylabel(HEADER[column])
        ax.set_title(title)
        ax.set_ylim(bottom=0)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
    fig.savefig(argv[2], dpi=120)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
