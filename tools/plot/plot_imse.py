#!/usr/bin/python3
"""Plot the IMSE basis comparison written by `sphbasis imse --json PATH`.

    /usr/bin/python3 tools/plot/plot_imse.py [--check] out/imse.json out/imse.png

One panel per protocol (paper, hdri): the (relative) IMSE on a log axis against the evaluation
cost in ns per normal (one call at a time, float; log axis), one labelled marker per row, one
colour per basis. Rows that fit the signal exactly have no place on a log axis: SH 9/16/25
span the paper protocol's SH-9 irradiance, so their IMSE is 0. What the CLI computes is
rounding in double: at seed 1 with 10,000 signals the sample means are 1e-28 to 2e-25 (the
fit misses each signal by 1e-14 to 1e-12 rms) and the closed form tr(Q)/3 is 2.5e-17 (SH 9) and
-1.9e-15 (SH 16, 25; cancellation in Q = A (Y - C^T G^-1 C) A), measured with ops/imse.hpp
unclamped; the CLI reports |IMSE| <= 1e-13 as 0 (its JSON stderr of these rows, 1e-30 to
2e-27, shows the scale). They are drawn with a downward triangle and "(exact)" on a dotted
line at a quarter of the smallest non-zero IMSE of the panel (1.1e-5 in the paper panel,
below Zernike 15's 4.2e-5): that height is a place to draw them, not a value, and the legend
says so. It is neither
Monte Carlo nor quadrature error of a reference: the paper IMSE is the fit's residual
integrated by the rule, and for a basis that spans the signal that residual is zero on any
rule (the 1e-5 of an earlier plot was this drawing height, a quarter of Zernike 15's 4.2e-5).

Labels are placed without collisions: after the layout is fixed, each label tries a list of
positions around its marker (right, left, above, below, then farther out with a leader line)
and takes the first whose box overlaps no other label, no marker and stays inside the panel;
if none is free, the one with the least overlap. Rows at the same place (same IMSE, cost
within 30 %) share one label ("hbasis 6 = hbasis-mod 6"). With --check the script verifies
the result and exits 1 if any label box overlaps another label, covers a marker (its own
included) or leaves its panel, listing the collisions; the ctest cli_imse_plot_labels runs it.
Needs only Debian's python3-matplotlib (Agg backend, no display).
"""
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.text  # noqa: E402
import matplotlib.ticker  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.transforms import Bbox  # noqa: E402

FLOOR = 1e-13  # the CLI's rounding floor: values at or below it are exact fits
COLOURS = {
    "sh": "#1f77b4",
    "hsh": "#ff7f0e",
    "makhotkin": "#2ca02c",
    "zernike": "#d62728",
    "hbasis": "#9467bd",
    "hbasis-mod": "#8c564b",
    "hl2": "#e377c2",
    "ambient-cube": "#7f7f7f",
    "ambient-dice": "#bcbd22",
    "ambient-dice-bezier": "#8c6d31",
    "ambient-dice-linear": "#e7ba52",
    "ambient-dice-bezier-normalized": "#bd9e39",
    "ambient-dice-linear-normalized": "#e7cb94",
    "sg": "#17becf",
    "sh-l1-nonlinear": "#000000",
    "zh3-hallucinate": "#aec7e8",
    "zh3": "#393b79",
}


def protocols(doc):
    """The per-protocol objects of a single- or all-protocol JSON document."""
    if doc.get("protocol") == "all":
        return doc["protocols"]
    return [doc]


def groups(rows):
    """Rows drawn at the same place (same IMSE to 1e-6, evaluation cost within 30 %, e.g. the
    H-basis and the modified H-basis, which span the same space) share one label."""
    out = []
    for r in rows:
        if r["imse"] is None or r["imse"] <= FLOOR:
            out.append([r])  # exact fits are labelled one by one
            continue
        for g in out:
            a = g[0]
            if a["imse"] is None or a["imse"] <= FLOOR:
                continue
            same_y = abs(a["imse"] - r["imse"]) <= 1e-6 * abs(a["imse"])
            if same_y and max(a["eval_ns"], r["eval_ns"]) <= 1.3 * min(a["eval_ns"], r["eval_ns"]):
                g.append(r)
                break
        else:
            out.append([r])
    return out


def panel(ax, p):
    # The SG pipeline rows (sg-ls, sg-nnls, sg-ra, sg-ra-nn: BakingLab's radiance fit shaded by
    # Hill's approximation) are tabulated, not plotted: they are no basis fit of the irradiance.
    rows = [r for r in p["rows"] if not r["basis"].startswith("sg-")]
    hdri = p["protocol"] == "hdri"
    values = [r["imse"] for r in rows if r["imse"] is not None and r["imse"] > FLOOR]
    if not values:
        values = [1.0]
    bottom = min(values) / 4
    seen = set()
    labels = []  # (x, y, text, colour), placed by place_labels once the layout is fixed
    markers = []
    any_exact = False
    for g in groups(rows):
        for r in g:
            x, y = r["eval_ns"], r["imse"]
            exact = y is None or y <= FLOOR
            yy = bottom if exact else y
            colour = COLOURS.get(r["basis"], "black")
            label = r["basis"] if r["basis"] not in seen else None
            seen.add(r["basis"])
            ax.scatter([x], [yy], marker="v" if exact else "o", s=36, color=colour, label=label,
                       zorder=3)
            markers.append((x, yy))
            any_exact = any_exact or exact
            if not exact and r.get("stderr"):
                ax.errorbar([x], [y], yerr=[[min(r["stderr"], 0.999 * y)], [r["stderr"]]],
                            color=colour, capsize=2, lw=0.8, zorder=2)
        r = g[0]
        exact = r["imse"] is None or r["imse"] <= FLOOR
        text = " = ".join("%s %d" % (q["basis"], q["coeffs"]) for q in g)
        if exact:
            text += " (exact)"
        labels.append((r["eval_ns"], bottom if exact else r["imse"], text,
                       COLOURS.get(r["basis"], "black")))
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_ylim(bottom / 2, max(values) * 3)
    xs = [r["eval_ns"] for r in rows]
    ax.set_xlim(min(xs) / 1.25, max(xs) * 1.6)
    ticks = [t for t in (1, 2, 3, 4, 5, 7, 10, 15, 20, 30, 40, 50, 70, 100, 150, 200, 300)
             if min(xs) / 1.25 <= t <= max(xs) * 1.6]
    ax.set_xticks(ticks)
    ax.xaxis.set_major_formatter(matplotlib.ticker.ScalarFormatter())
    ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    ax.set_xlabel("evaluation cost per normal, ns (one call at a time, float)")
    if hdri:
        ax.set_ylabel("relative IMSE = IMSE / mean(E²) over the hemisphere")
        title = "hdri: 8 CC0 environment maps, %d random orientations" % p["signals"]
    else:
        ax.set_ylabel("IMSE (mean over signals)")
        title = "paper: %d random SH-9 radiance signals" % p["signals"]
    ax.set_title(title, fontsize=10)
    ax.grid(True, which="both", lw=0.3, alpha=0.5)
    handles, names = ax.get_legend_handles_labels()
    if any_exact:
        handles.append(Line2D([], [], marker="v", color="grey", linestyle="None", markersize=6))
        names.append("exact fit: the basis spans the SH-9 signal, so IMSE = 0 (computed: double "
                     "rounding, |IMSE| < %g).\nDrawn on the dotted line at %.1e, a quarter of the "
                     "smallest IMSE above: a place, not a value" % (FLOOR, bottom))
        ax.axhline(bottom, color="grey", lw=0.6, ls=":", zorder=1)
    ax.legend(handles, names, fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.12),
              ncol=5, frameon=False)
    if any_exact:
        # The legend's long entry does not fit beside the colours: it takes a row of its own.
        leg = ax.get_legend()
        leg.remove()
        first = ax.legend(handles[:-1], names[:-1], fontsize=7, loc="upper center",
                          bbox_to_anchor=(0.5, -0.12), ncol=5, frameon=False)
        ax.add_artist(first)
        ax.legend(handles[-1:], names[-1:], fontsize=7, loc="upper center",
                  bbox_to_anchor=(0.5, -0.24), frameon=False)
    return labels, markers


def overlap(a, b):
    """Area shared by two display-space boxes."""
    w = min(a.x1, b.x1) - max(a.x0, b.x0)
    h = min(a.y1, b.y1) - max(a.y0, b.y0)
    return w * h if w > 0 and h > 0 else 0.0


def place_labels(fig, ax, labels, markers):
    """Annotates each (x, y, text, colour) at the first free position (see the module doc)."""
    renderer = fig.canvas.get_renderer()
    frame = ax.get_window_extent(renderer)
    radius = 6 * fig.dpi / 72  # a marker of size 36 (6 pt across) and a margin
    blocked = []
    for x, y in markers:
        px, py = ax.transData.transform((x, y))
        blocked.append(Bbox([[px - radius, py - radius], [px + radius, py + radius]]))
    # Offsets in points and alignments; the first four touch the marker, the rest need a leader.
    near = [((6, 0), "left", "center"), ((-6, 0), "right", "center"),
            ((0, 6), "center", "bottom"), ((0, -7), "center", "top"),
            ((5, 5), "left", "bottom"), ((5, -5), "left", "top"),
            ((-5, 5), "right", "bottom"), ((-5, -5), "right", "top")]
    far = []
    for d in (14, 24, 36, 50):
        far += [((d, d * 0.6), "left", "bottom"), ((d, -d * 0.6), "left", "top"),
                ((-d, d * 0.6), "right", "bottom"), ((-d, -d * 0.6), "right", "top"),
                ((0, d), "center", "bottom"), ((0, -d), "center", "top")]
    placed = []
    texts = []
    # Labels in order of crowding (most markers nearby first), so the tight ones choose first.
    def crowding(item):
        px, py = ax.transData.transform((item[0], item[1]))
        return -sum(1 for b in blocked
                    if abs((b.x0 + b.x1) / 2 - px) < 80 and abs((b.y0 + b.y1) / 2 - py) < 30)
    for x, y, text, colour in sorted(labels, key=crowding):
        best = None
        for k, (off, ha, va) in enumerate(near + far):
            t = ax.annotate(text, (x, y), textcoords="offset points", xytext=off, fontsize=7,
                            color=colour, ha=ha, va=va, zorder=4)
            box = t.get_window_extent(renderer).expanded(1.04, 1.1)
            cost = sum(overlap(box, b) for b in placed + blocked)
            if not (frame.x0 <= box.x0 and box.x1 <= frame.x1 and frame.y0 <= box.y0
                    and box.y1 <= frame.y1):
                cost += 1e6
            if best is None or cost < best[0]:
                if best is not None:
                    best[1].remove()
                best = (cost, t, box, k >= len(near))
            else:
                t.remove()
            if cost == 0:
                break
        cost, t, box, leader = best
        if leader:
            t.remove()
            t = ax.annotate(text, (x, y), textcoords="offset points", xytext=t.xyann,
                            fontsize=7, color=colour, ha=t.get_ha(), va=t.get_va(), zorder=4,
                            arrowprops=dict(arrowstyle="-", color=colour, lw=0.5,
                                            shrinkA=0, shrinkB=4))
        placed.append(box)
        texts.append(t)
    return texts


def collisions(fig, ax, texts, markers):
    """What --check refuses: each label's drawn box (no margin) against every other label, every
    marker's disc (6 pt across, drawn at its data point) and the panel. Returns messages."""
    renderer = fig.canvas.get_renderer()
    frame = ax.get_window_extent(renderer)
    r = 3 * fig.dpi / 72
    dots = []
    for x, y in markers:
        px, py = ax.transData.transform((x, y))
        dots.append(((x, y), Bbox([[px - r, py - r], [px + r, py + r]])))
    # Text.get_window_extent: the text alone (an Annotation's own includes its leader line).
    boxes = []
    for t in texts:
        t.update_positions(renderer)  # places the text at its offset, as drawing does
        boxes.append((t.get_text(), matplotlib.text.Text.get_window_extent(t, renderer)))
    out = []
    for i, (a, box) in enumerate(boxes):
        for b, other in boxes[i + 1:]:
            if overlap(box, other) > 0:
                out.append("label '%s' overlaps label '%s'" % (a, b))
        for (x, y), dot in dots:
            if overlap(box, dot) > 0:
                out.append("label '%s' covers the marker at (%g, %g)" % (a, x, y))
        if not (frame.x0 <= box.x0 and box.x1 <= frame.x1 and frame.y0 <= box.y0
                and box.y1 <= frame.y1):
            out.append("label '%s' leaves its panel" % a)
    return out


def main(argv):
    check = "--check" in argv[1:]
    argv = [a for a in argv if a != "--check"]
    if len(argv) != 3:
        sys.stderr.write("usage: plot_imse.py [--check] IMSE.json OUT.png\n")
        return 2
    with open(argv[1]) as f:
        doc = json.load(f)
    ps = protocols(doc)
    fig, axes = plt.subplots(1, len(ps), figsize=(7.5 * len(ps), 6.8), squeeze=False, dpi=130)
    drawn = [(ax, panel(ax, p)) for ax, p in zip(axes[0], ps)]
    fig.suptitle("sphbasis IMSE basis comparison (seed %s): accuracy against evaluation cost"
                 % doc.get("seed"), fontsize=11)
    fig.tight_layout()  # fixes the axes, so label positions in display space are final
    problems = []
    count = 0
    for ax, (labels, markers) in drawn:
        texts = place_labels(fig, ax, labels, markers)
        count += len(texts)
        problems += collisions(fig, ax, texts, markers)
    fig.savefig(argv[2], dpi=130)
    if check:
        for p in problems:
            sys.stderr.write("plot_imse.py: %s\n" % p)
        if problems:
            return 1
        print("plot_imse.py: %d labels, none overlaps a label or a marker" % count)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
