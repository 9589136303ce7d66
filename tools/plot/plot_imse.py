#!/usr/bin/python3
"""Plot the IMSE basis comparison written by `sphbasis imse --json PATH`.

    /usr/bin/python3 tools/plot/plot_imse.py out/imse.json out/imse.png

One panel per protocol (paper, hdri): the (relative) IMSE on a log axis against the evaluation
cost in ns per normal (one call at a time, float; log axis), one labelled marker per row, one
colour per basis. Rows that fit the signal exactly (IMSE at the rounding level, SH 9/16/25 in
the paper protocol) are drawn at the bottom edge with a downward triangle and "(exact)".
Needs only Debian's python3-matplotlib (Agg backend, no display).
"""
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402

FLOOR = 1e-13  # the CLI's rounding floor: values at or below it are exact fits
COLOURS = {
    "sh": "#1f77b4",
    "hsh": "#ff7f0e",
    "makhotkin": "#2ca02c",
    "zernike": "#d62728",
    "hbasis": "#9467bd",
    "hbasis-mod": "#8c564b",
    "hl2": "#e377c2",
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
    rows = p["rows"]
    hdri = p["protocol"] == "hdri"
    values = [r["imse"] for r in rows if r["imse"] is not None and r["imse"] > FLOOR]
    if not values:
        values = [1.0]
    bottom = min(values) / 4
    seen = set()
    exact_count = 0
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
            if not exact and r.get("stderr"):
                ax.errorbar([x], [y], yerr=[[min(r["stderr"], 0.999 * y)], [r["stderr"]]],
                            color=colour, capsize=2, lw=0.8, zorder=2)
        r = g[0]
        exact = r["imse"] is None or r["imse"] <= FLOOR
        text = " = ".join("%s %d" % (q["basis"], q["coeffs"]) for q in g)
        if exact:
            text += " (exact)"
            offset = (4, 3 + 9 * (exact_count % 3))  # stagger the labels along the bottom
            exact_count += 1
        else:
            offset = (5, 3)
        ax.annotate(text, (r["eval_ns"], bottom if exact else r["imse"]),
                    textcoords="offset points", xytext=offset, fontsize=7,
                    color=COLOURS.get(r["basis"], "black"))
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
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.12), ncol=7,
              frameon=False)


def main(argv):
    if len(argv) != 3:
        sys.stderr.write("usage: plot_imse.py IMSE.json OUT.png\n")
        return 2
    with open(argv[1]) as f:
        doc = json.load(f)
    ps = protocols(doc)
    fig, axes = plt.subplots(1, len(ps), figsize=(7.5 * len(ps), 6.4), squeeze=False)
    for ax, p in zip(axes[0], ps):
        panel(ax, p)
    fig.suptitle("sphbasis IMSE basis comparison (seed %s): accuracy against evaluation cost"
                 % doc.get("seed"), fontsize=11)
    fig.tight_layout()
    fig.savefig(argv[2], dpi=130)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
