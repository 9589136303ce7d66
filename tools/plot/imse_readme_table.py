#!/usr/bin/env python3
"""The README's "Which basis?" table from one `sphbasis imse --protocol all --json` run.

    imse_readme_table.py RUN.json                 print the table
    imse_readme_table.py RUN.json --update FILE   rewrite FILE's block between
                                                  "<!-- imse_table -->" and "<!-- /imse_table -->"
    imse_readme_table.py RUN.json --check FILE    exit 1 if that block differs from the run's table

Rows: every basis of the hdri protocol (the bases scored on real light) and BakingLab's sg-ls 9
(paper protocol only), sorted by coefficient count (the run's order within a count), except the
16-function HSH and Makhotkin rows (the table stops at the sizes a texel stores). The H-basis and the
modified H-basis (one span) share a line where their printed IMSE agree ("hbasis = hbasis-mod",
the H-basis's ns). Columns: the paper
protocol's IMSE and its closed form ("exact" where both are 0, "no closed form" for the fitted
rows), the hdri protocol's relative IMSE, and the float evaluation ns (one call / batched) of the
paper protocol's run. Standard library only.
"""
import argparse
import json
import os
import sys

BEGIN, END = "<!-- imse_table -->", "<!-- /imse_table -->"
LEFT_OUT = {("hsh", 16), ("makhotkin", 16)}
PAPER_ONLY = {("sg-ls", 9)}
SAME_SPAN = {("hbasis", "hbasis-mod")}  # one span by construction: one line when the IMSE agree


class InputError(Exception):
    pass


def g3(x):
    """Three significant digits: decimals down to 1e-3, scientific below."""
    if x == 0:
        return "0"
    if abs(x) < 1e-3:
        return "%.2e" % x
    return "%.3g" % x


def rows_of(run):
    try:
        by = {p["protocol"]: p["rows"] for p in run["protocols"]}
        paper, hdri = by["paper"], by["hdri"]
    except (KeyError, TypeError) as e:
        raise InputError("not a `sphbasis imse --protocol all --json` run (%s)" % e)
    hd = {(r["basis"], r["coeffs"]): r for r in hdri}
    out = []
    for r in paper:
        key = (r["basis"], r["coeffs"])
        if key in LEFT_OUT or (key not in hd and key not in PAPER_ONLY):
            continue
        imse = r["imse"]
        exp = r.get("expected")
        if exp is None:
            paper_cell = "%s (no closed form)" % g3(imse)
        elif imse == 0 and exp == 0:
            paper_cell = "0 (exact)"
        else:
            paper_cell = "%s (%s)" % (g3(imse), g3(exp))
        h = hd.get(key)
        hdri_cell = g3(h["imse"]) if h else "-"
        ns = "%.2f / %.2f" % (r["eval_ns"], r["eval_batch_ns"])
        out.append([r["basis"], key[1], paper_cell, hdri_cell, ns])
    out.sort(key=lambda c: c[1])  # stable: the run's order within a count
    merged = []
    for c in out:
        same = [m for m in merged if (m[0], c[0]) in SAME_SPAN and m[1:4] == c[1:4]]
        if same:
            same[0][0] += " = " + c[0]
        else:
            merged.append(c)
    return merged


def table(run):
    lines = ["| basis | coeffs | paper IMSE (closed form) | hdri relative IMSE | "
             "eval ns (one call / batched, float) |",
             "|---|---:|---:|---:|---:|"]
    for c in rows_of(run):
        lines.append("| %s | %d | %s | %s | %s |" % tuple(c))
    return lines


def sync(path, made, write):
    try:
        with open(path) as f:
            lines = f.read().split("\n")
    except OSError as e:
        raise InputError("%s: cannot read (%s)" % (path, e))
    if lines.count(BEGIN) != 1 or lines.count(END) != 1:
        raise InputError("%s: needs exactly one %s ... %s block" % (path, BEGIN, END))
    i, j = lines.index(BEGIN) + 1, lines.index(END)
    if j < i:
        raise InputError("%s: %s before %s" % (path, END, BEGIN))
    if not write:
        if lines[i:j] != made:
            raise InputError("%s: the table differs from the run's (rerun with --update)" % path)
        return
    out = lines[:i] + made + lines[j:]
    with open(path + ".tmp", "w") as f:
        f.write("\n".join(out))
    os.replace(path + ".tmp", path)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("run", help="the JSON of `sphbasis imse --protocol all --json`")
    ap.add_argument("--update", metavar="FILE")
    ap.add_argument("--check", metavar="FILE")
    a = ap.parse_args()
    try:
        try:
            with open(a.run) as f:
                run = json.load(f)
        except (OSError, ValueError) as e:
            raise InputError("%s: cannot read (%s)" % (a.run, e))
        made = table(run)
        if a.update:
            sync(a.update, made, True)
        if a.check:
            sync(a.check, made, False)
            print("checked the table of %s against %s" % (a.check, a.run))
        if not a.update and not a.check:
            print("\n".join(made))
    except InputError as e:
        print("imse_readme_table.py: %s" % e, file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
