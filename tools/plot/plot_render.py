#!/usr/bin/python3
"""Plot error against render time from the report of `sphbasis render`.

    /usr/bin/python3 tools/plot/plot_render.py out/render/report.json out/render/error_vs_time.png

The relative MSE of each representation against its reference (over judged pixels; log axis)
against its render time per frame on one thread (ms; log axis): "what accuracy costs in time".
One labelled marker per representation, one colour per family (SH irradiance, AO and bent
normals, PRT, irradiance lightmaps, the irradiance volume, specular). Rows with a relative MSE
of zero cannot sit on a log axis: they are drawn on the bottom edge with a downward triangle
and "(exact)". Labels alternate above and below their marker to limit collisions. The title
gives the scene, the image size and the reference's samples per pixel.
Needs only Debian's python3-matplotlib (Agg backend, no display).
"""
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402

FAMILIES = [
    ("irradiance-sh9", "#1f77b4", "SH irradiance (no shadows)"),
    ("ao", "#ff7f0e", "AO / bent normal"),
    ("bent", "#ff7f0e", None),
    ("prt-", "#2ca02c", "PRT"),
    ("lightmap-", "#9467bd", "irradiance lightmaps"),
    ("volume", "#8c564b", "irradiance volume"),
    ("specular-", "#d62728", "specular (vs its own reference)"),
]


def family(name):
    for prefix, colour, label in FAMILIES:
        if name.startswith(prefix):
            return colour, label
    return "#7f7f7f", "other"


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: plot_render.py REPORT.json OUT.png")
    with open(sys.argv[1]) as f:
        doc = json.load(f)
    rows = [r for r in doc["representations"] if r["render_ms_1_thread"] > 0]
    if not rows:
        sys.exit("plot_render.py: no representation with a render time in " + sys.argv[1])
    positive = [r["rel_mse"] for r in rows if r["rel_mse"] > 0]
    floor = min(positive) / 4 if positive else 1e-6
    fig, ax = plt.subplots(figsize=(8, 5.5), dpi=120)
    legend = {}
    for i, r in enumerate(sorted(rows, key=lambda r: r["render_ms_1_thread"])):
        colour, label = family(r["name"])
        exact = r["rel_mse"] <= 0
        y = floor if exact else r["rel_mse"]
        ax.scatter([r["render_ms_1_thread"]], [y], color=colour, marker="v" if exact else "o",
                   s=40, zorder=3)
        if label:
            legend[label] = colour
        text = r["name"] + (" (exact)" if exact else "")
        ax.annotate(text, (r["render_ms_1_thread"], y), xytext=(6, 7 if i % 2 == 0 else -12),
                    textcoords="offset points", fontsize=7.5, color=colour)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("render time per frame, one thread (ms)")
    ax.set_ylabel("relative MSE against the reference (judged pixels)")
    ref = doc.get("reference", {})
    ax.set_title("%s: %dx%d, reference %s spp" % (doc.get("scene", "?"), doc.get("width", 0),
                                                  doc.get("height", 0), ref.get("spp", "?")),
                 fontsize=10)
    ax.grid(True, which="both", alpha=0.25)
    handles = [Line2D([], [], color=c, marker="o", linestyle="", label=l)
               for l, c in legend.items()]
    ax.legend(handles=handles, fontsize=8, loc="best")
    fig.tight_layout()
    fig.savefig(sys.argv[2])


if __name__ == "__main__":
    main()
