#!/usr/bin/python3
"""Chart of `bounce accuracy`'s accuracy.csv: error (log scale) against GPU milliseconds.

    /usr/bin/python3 tools/plot_accuracy.py accuracy.csv accuracy.png [heatmaps.csv]

One column of panels per reference kind a row is scored against (its setting's "ref=direct",
"ref=1bounce" or "ref=all"; errors against different references are not comparable): top,
rel_rmse (whole image vs that reference); bottom, effect_rel_rmse (the dynamic objects' effect vs
the reference's; 1 = as wrong as leaving it out). The table also lists indirect_effect_rel_rmse (the
effect error on the pixels the objects neither cover nor shadow; empty in the CSV where a row has
none). Each technique has one colour; each point is
numbered, and the table beside the panels gives each number's technique, setting, GPU ms and
errors. The Pareto front of each panel (no other row of that reference is both cheaper and more
accurate) is drawn as a step line through its rows, which are ringed and starred in the table.
The x axis is logarithmic when the GPU times span more than 10x. Rows with NaN are left out of
that panel.

With heatmaps.csv (columns file,technique,setting,scale, written by `bounce accuracy`), each heat
map PNG (reference | technique | error panels) is redrawn with a title naming the technique and
setting, panel labels and a colour bar labelled with the error scale.

Exit codes: 0 drawn, 2 bad input (one line on stderr), 3 matplotlib missing (Debian
python3-matplotlib), so the caller can tell "cannot plot here" from "plotting failed".
"""
import csv
import math
import os
import sys

# The chart reads the first six; the noise columns after them (game/accuracy.hpp) are checked by name only.
HEADER = ["technique", "setting", "gpu_ms", "rel_rmse", "effect_rel_rmse", "indirect_effect_rel_rmse",
          "effect_noise_floor", "effect_rel_rmse_corrected", "indirect_noise_floor", "indirect_effect_rel_rmse_corrected"]
HEATMAP_HEADER = ["file", "technique", "setting", "scale"]
LOG_X_SPAN = 10.0  # max/min GPU ms above which a log axis keeps the cheap rows apart
REF_ORDER = ["direct", "1bounce", "all"]
REF_TITLE = {"direct": "vs the direct-only reference", "1bounce": "vs the one-bounce reference",
             "all": "vs the full (all-bounce) reference"}



def save_atomic(fig, path, **kwargs):
    """Writes the figure to a temporary file beside `path`, then renames it over `path`, so a reader
    (another process of the same test, or a person's viewer) never sees a half-written PNG."""
    tmp = f"{path}.tmp-{os.getpid()}.png"
    fig.savefig(tmp, **kwargs)
    os.replace(tmp, path)

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
                # indirect_effect_rel_rmse is empty where a row has none: NaN, left out like "nan".
                numbers = [float(v) for v in fields[2:5]] + [float(fields[5]) if fields[5] != "" else math.nan]
            except ValueError:
                raise ValueError(f"{path}: line {line}: a value is not a number "
                                 "(expected gpu_ms,rel_rmse,effect_rel_rmse[,indirect_effect_rel_rmse])")
            rows.append((fields[0], fields[1], *numbers))
        return rows


def reference_kind(setting):
    for item in setting.split(";"):
        if item.startswith("ref="):
            return item[4:]
    return "all"


def setting_without_ref(setting):
    return ";".join(i for i in setting.split(";") if not i.startswith("ref=")) or "-"


def pareto(points):
    """Indices of the points (ms, error) that no other point beats on both: sorted by ms, each
    strictly more accurate than every cheaper one."""
    order = sorted(range(len(points)), key=lambda i: (points[i][0], points[i][1]))
    front, best = [], math.inf
    for i in order:
        if points[i][1] < best:
            front.append(i)
            best = points[i][1]
    return front


def plot_chart(rows, png, plt):
    from matplotlib import gridspec
    kinds = [k for k in REF_ORDER if any(reference_kind(r[1]) == k for r in rows)]
    kinds += sorted({reference_kind(r[1]) for r in rows} - set(kinds))
    techniques = sorted({r[0] for r in rows})
    colours = {t: plt.cm.tab10(i % 10) for i, t in enumerate(techniques)}
    times = [r[2] for r in rows if r[2] > 0 and math.isfinite(r[2])]
    log_x = bool(times) and max(times) / min(times) > LOG_X_SPAN

    ncols = max(1, len(kinds))
    fig = plt.figure(figsize=(4.2 * ncols + 8.5, 8.5))
    grid = gridspec.GridSpec(2, ncols + 1, figure=fig, width_ratios=[1] * ncols + [2.1], wspace=0.35, hspace=0.35,
                             left=0.06, right=0.99, top=0.92, bottom=0.08)
    on_front = set()
    for col, kind in enumerate(kinds):
        idx = [i for i, r in enumerate(rows) if reference_kind(r[1]) == kind]
        for rowpos, column, label in ((0, 3, "image rel. RMSE"), (1, 4, "object-effect rel. RMSE (1 = effect missing)")):
            ax = fig.add_subplot(grid[rowpos, col])
            pts = [i for i in idx if math.isfinite(rows[i][column]) and rows[i][column] > 0 and math.isfinite(rows[i][2])]
            for t in techniques:
                mine = [i for i in pts if rows[i][0] == t]
                if mine:
                    ax.scatter([rows[i][2] for i in mine], [rows[i][column] for i in mine], color=colours[t], zorder=3, s=28)
            for i in pts:
                ax.annotate(str(i + 1), (rows[i][2], rows[i][column]), textcoords="offset points", xytext=(3, 3),
                            fontsize=7, color="0.25")
            front = [pts[j] for j in pareto([(rows[i][2], rows[i][column]) for i in pts])]
            if column == 3:
                on_front.update(front)
            if front:
                xs = [rows[i][2] for i in front]
                ys = [rows[i][column] for i in front]
                ax.step(xs, ys, where="post", color="black", linewidth=1.0, alpha=0.7, zorder=2, label="Pareto front")
                ax.scatter(xs, ys, facecolors="none", edgecolors="black", s=90, linewidths=1.0, zorder=4)
            if log_x:
                ax.set_xscale("log")
            ax.set_yscale("log")
            ax.grid(True, which="both", alpha=0.25)
            ax.set_xlabel("GPU ms (median of the row's passes)")
            ax.set_ylabel(label, fontsize=9)
            if rowpos == 0:
                ax.set_title(REF_TITLE.get(kind, "vs reference " + kind), fontsize=10)
            if not pts:
                ax.text(0.5, 0.5, "no finite values", transform=ax.transAxes, ha="center", color="0.5")
    # The technique colours, once, above the panels.
    handles = [plt.Line2D([], [], marker="o", linestyle="", color=colours[t], label=t) for t in techniques]
    handles.append(plt.Line2D([], [], color="black", label="Pareto front (image error)"))
    fig.legend(handles=handles, loc="upper left", ncol=len(handles), fontsize=8, frameon=False,
               bbox_to_anchor=(0.05, 0.995))
    # The settings table.
    tab = fig.add_subplot(grid[:, ncols])
    tab.axis("off")
    lines = [f"{'#':>3} {'technique':<9} {'setting':<48} {'ms':>7} {'rel rmse':>8} {'effect':>6} {'ind.':>6}"]
    for i, r in enumerate(rows):
        star = "*" if i in on_front else " "
        setting = setting_without_ref(r[1])
        setting = setting.replace("anti_radiance=", "anti=").replace("intrusion=", "intr=")
        if len(setting) > 48:
            setting = setting[:47] + "~"
        indirect = f"{r[5]:>6.3f}" if math.isfinite(r[5]) else f"{'-':>6}"
        lines.append(f"{i + 1:>3}{star}{r[0]:<9} {setting:<48} {r[2]:>7.2f} {r[3]:>8.4f} {r[4]:>6.3f} {indirect}")
    lines.append("")
    lines.append("* on the Pareto front of its reference's image error")
    lines.append("(intr = intrusion, anti = anti_radiance; ind. = effect error on the")
    lines.append(" pixels the objects neither cover nor shadow, - = none)")
    tab.text(0.0, 1.0, "\n".join(lines), family="monospace", fontsize=8.5 if len(rows) < 30 else 7, va="top",
             transform=tab.transAxes)
    save_atomic(fig, png, dpi=110)
    plt.close(fig)


def read_heatmaps(path):
    with open(path, newline="") as f:
        reader = csv.reader(f)
        header = next(reader, None)
        if header != HEATMAP_HEADER:
            raise ValueError(f"{path}: line 1: header is {header} (expected {','.join(HEATMAP_HEADER)})")
        out = []
        for line, fields in enumerate(reader, start=2):
            if len(fields) != len(HEATMAP_HEADER):
                raise ValueError(f"{path}: line {line}: {len(fields)} fields (expected {len(HEATMAP_HEADER)})")
            try:
                out.append((fields[0], fields[1], fields[2], float(fields[3])))
            except ValueError:
                raise ValueError(f"{path}: line {line}: scale is not a number")
        return out


def title_heatmap(file, technique, setting, scale, plt):
    """Redraws a comparison PNG (reference | technique | error, equal widths, 4-pixel gaps, an
    8-row colour bar under the error panel) with a title, panel labels and a labelled colour bar."""
    import matplotlib
    image = plt.imread(file)
    h, w = image.shape[0], image.shape[1]
    panel = (w - 8) // 3
    bar = 8 + 4  # colour bar and its gap, which the labelled bar below replaces
    fig = plt.figure(figsize=(max(6.0, w / 80.0), (h - bar) / 80.0 + 1.6), dpi=100)
    ax = fig.add_axes([0.02, 0.2, 0.96, 0.56])
    ax.imshow(image[: h - bar], interpolation="nearest")
    ax.set_xticks([panel / 2, panel + 4 + panel / 2, 2 * (panel + 4) + panel / 2])
    ax.set_xticklabels(["reference", technique, "error |image - reference|"], fontsize=8)
    ax.xaxis.tick_top()
    ax.set_yticks([])
    fig.suptitle(f"{technique}  {setting}", fontsize=10, y=0.98)
    cax = fig.add_axes([0.55, 0.1, 0.43, 0.05])
    mappable = matplotlib.cm.ScalarMappable(norm=matplotlib.colors.Normalize(0.0, scale), cmap="viridis")
    cb = fig.colorbar(mappable, cax=cax, orientation="horizontal")
    cb.set_label("per-pixel mean abs. error (linear radiance)", fontsize=8)
    cb.ax.tick_params(labelsize=7)
    save_atomic(fig, file)
    plt.close(fig)


def main(argv):
    if len(argv) not in (3, 4):
        print("usage: plot_accuracy.py accuracy.csv accuracy.png [heatmaps.csv]", file=sys.stderr)
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
        heatmaps = read_heatmaps(argv[3]) if len(argv) == 4 else []
    except (OSError, ValueError) as e:
        print(str(e), file=sys.stderr)
        return 2
    plot_chart(rows, argv[2], plt)
    for file, technique, setting, scale in heatmaps:
        title_heatmap(file, technique, setting, scale, plt)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
