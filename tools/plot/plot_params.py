#!/usr/bin/python3
"""Plot the parameterization experiment (Iwanicki and Sloan, "Normal Mapping with Low-Frequency Precomputed Visibility", JGT 2009, appendix A) written by `sphbasis params`.

Usage: /usr/bin/python3 tools/plot/plot_params.py out/params.json out/params.png

Log-log MSE of the bilinearly reconstructed SH basis functions against the total number of
texels, one line per parameterization, one panel for 3 bands and one for 6 bands.
"""
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

STYLE = {
    "dual_orthographic": ("tab:gray", "v"),
    "dual_paraboloid": ("tab:green", "^"),
    "cube_dx9": ("tab:orange", "s"),
    "cube_dx10": ("tab:red", "D"),
    "octahedral_clamp": ("tab:cyan", "o"),
    "octahedral_seamless": ("tab:blue", "o"),
    "latlong": ("tab:purple", "x"),
}


def main(argv):
    if len(argv) != 3:
        sys.stderr.write(__doc__)
        return 2
    with open(argv[1]) as f:
        data = json.load(f)
    labels = {p["name"]: p["label"] for p in data.get("parameterizations", [])}
    names = []
    for r in data["results"]:
        if r["param"] not in names:
            names.append(r["param"])

    fig, axes = plt.subplots(1, 2, figsize=(12, 5), sharex=True)
    for ax, key, bands in ((axes[0], "mse_3bands", 3), (axes[1], "mse_6bands", 6)):
        for name in names:
            rows = sorted((r for r in data["results"] if r["param"] == name),
                          key=lambda r: r["texels"])
            xs = [r["texels"] for r in rows]
            ys = [r[key] for r in rows]
            color, marker = STYLE.get(name, (None, "."))
            dashed = name in ("cube_dx9", "octahedral_clamp")
            ax.loglog(xs, ys, marker=marker, markersize=4, color=color,
                      linestyle="--" if dashed else "-", label=labels.get(name, name))
        ax.set_title(f"{bands} bands ({bands * bands} SH functions)")
        ax.set_xlabel("total texels")
        ax.set_ylabel("MSE vs exact")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize=8)
    fig.suptitle(f"Bilinear reconstruction of SH basis functions, "
                 f"{data.get('points', '?')} random directions")
    fig.tight_layout()
    fig.savefig(argv[2], dpi=120)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
