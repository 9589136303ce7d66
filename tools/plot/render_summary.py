#!/usr/bin/python3
"""The committed scenes' verdict: tables of the reports of `sphbasis render` on several scenes.

    tools/plot/render_summary.py out/render/*/report.json    # the tables, markdown on stdout
    tools/plot/render_summary.py --save RUN.json --md SUMMARY.md REPORT.json...
    tools/plot/render_summary.py --update README.md --update docs/rendering.md RUN.json
    tools/plot/render_summary.py --check README.md --check docs/rendering.md RUN.json

Inputs: the report.json of `sphbasis render`, one per scene, or a run saved by --save (the fields
these tables read, every scene in one small file: tests/data/render_readme_run.json is the run
behind README.md's "On the committed scenes"). A scene is named by its file's base name; the
scenes keep the order given.

Blocks (each printed under a "<!-- render_summary: NAME -->" line):
  irradiance   the irradiance representations: every name starting with "lightmap-" (bytes per
               texel), "volume-" or equal to "volume" (bytes per probe), found by that pattern (a
               representation added later appears by itself). Per scene "FLIP / rel. MSE": the
               report's headline metric, FLIP (LDR-FLIP of the tone-mapped images, mean over the
               covered pixels; the reports rank by it), and the floored relative MSE in linear
               radiance; the mean FLIP over the scenes the row ran on; the shading time per pixel
               sample on one thread (the median over the scenes; the camera rays the representations
               share are not in it); the bake seconds summed over the scenes. Rows: lightmaps, then
               volumes; in each, by bytes, then by mean FLIP. "best per": "byte" on the Pareto front
               of bytes against mean FLIP within its kind (texel or probe): no row has at most its
               bytes and a lower mean FLIP, or fewer bytes and at most its mean FLIP, compared as
               shown (FLIP to 3 decimals, whole ns: rows shown equal tie); "ns" likewise for the
               median shading ns.
  others       every other representation (SH irradiance, AO, PRT, L×H, specular), by mean FLIP.
  scene:NAME   one scene's whole table, ranked by FLIP as its report, with its run's settings.
--update FILE (repeatable) rewrites, in each file, the lines between
"<!-- render_summary: NAME -->" and "<!-- /render_summary -->" with block NAME; --check fails
(exit 1, one line naming the file and block) where they differ, so a document's table is the one
this tool makes of the committed run.
Standard library only. Bad input: one line on stderr and exit 1.
"""
import argparse
import json
import math
import os
import re
import statistics
import sys

TOOL = "render_summary.py"
# The fields of a report that the tables read (--save keeps only these).
RUN_KEYS = ("tool", "scene", "command", "width", "height", "threads", "seconds")
REFERENCE_KEYS = ("spp", "relative_noise", "seconds")
ROW_KEYS = ("name", "flip", "rel_mse_floored", "bake_seconds", "bakes_cached",
            "shade_ns_per_sample", "element", "bytes_per_element")
BEGIN = re.compile(r"^<!-- render_summary: (\S+) -->$")
END = "<!-- /render_summary -->"


class InputError(Exception):
    pass


def number(row, key, where):
    v = row.get(key)
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or v < 0:
        raise InputError("%s: representation %r: %s: expected a finite number >= 0, got %r"
                         % (where, row.get("name"), key, v))
    return v


def trim(doc, where):
    """The fields of one report these tables read, checked: a report.json with fewer keys."""
    if doc.get("tool") != "sphbasis render" or not isinstance(doc.get("representations"), list):
        raise InputError("%s: expected a report.json of `sphbasis render` (\"tool\": \"sphbasis "
                         "render\" and a list \"representations\")" % where)
    out = {k: doc.get(k) for k in RUN_KEYS}
    ref, sampling = doc.get("reference"), doc.get("sampling")
    if not isinstance(ref, dict) or not isinstance(sampling, dict):
        raise InputError("%s: expected the objects \"reference\" and \"sampling\"" % where)
    out["reference"] = {k: ref.get(k) for k in REFERENCE_KEYS}
    out["sampling"] = {"camera_ns_per_sample": sampling.get("camera_ns_per_sample")}
    rows = []
    for r in doc["representations"]:
        if not isinstance(r, dict) or not isinstance(r.get("name"), str):
            raise InputError("%s: a representation without a name" % where)
        for k in ("flip", "rel_mse_floored", "bake_seconds", "shade_ns_per_sample",
                  "bytes_per_element"):
            number(r, k, where)
        rows.append({k: r.get(k) for k in ROW_KEYS})
    if not rows:
        raise InputError("%s: no representations" % where)
    out["representations"] = rows
    return out


def save(path, scenes):
    """The trimmed reports in one file, one representation a line (small diffs on a rerun)."""
    text = '{"tool": "%s", "scenes": [\n' % TOOL
    for i, (_, t) in enumerate(scenes):
        head = {k: v for k, v in t.items() if k != "representations"}
        text += json.dumps(head)[:-1] + ', "representations": [\n'
        text += ",\n".join("  " + json.dumps(r) for r in t["representations"])
        text += "\n]}" + ("," if i + 1 < len(scenes) else "") + "\n"
    text += "]}\n"
    with open(path + ".tmp", "w") as f:
        f.write(text)
    os.replace(path + ".tmp", path)


def load(paths):
    """[(scene name, trimmed report)] in the order given."""
    scenes = []
    for p in paths:
        try:
            with open(p) as f:
                doc = json.load(f)
        except (OSError, ValueError) as e:
            raise InputError("%s: cannot read JSON (%s)" % (p, e))
        docs = doc.get("scenes") if isinstance(doc, dict) and doc.get("tool") == TOOL else [doc]
        if not isinstance(docs, list):
            raise InputError("%s: expected a list \"scenes\"" % p)
        for d in docs:
            if not isinstance(d, dict):
                raise InputError("%s: expected a JSON object per scene" % p)
            t = trim(d, p)
            name = os.path.splitext(os.path.basename(str(t["scene"])))[0]
            if any(name == n for n, _ in scenes):
                raise InputError("%s: scene %r given twice" % (p, name))
            scenes.append((name, t))
    if not scenes:
        raise InputError("no report given")
    return scenes


def is_irradiance(name):
    return name.startswith("lightmap-") or name == "volume" or name.startswith("volume-")


def g(x, digits=3):
    return "%.*f" % (digits, x)


def sci(x):
    return "%.1e" % x if x > 0 else "0"


def combine(scenes, select):
    """Per representation (in first-seen order): its rows by scene and the aggregates."""
    order, by_name = [], {}
    for scene, t in scenes:
        for r in t["representations"]:
            if not select(r["name"]):
                continue
            if r["name"] not in by_name:
                by_name[r["name"]] = {"name": r["name"], "rows": {}}
                order.append(r["name"])
            by_name[r["name"]]["rows"][scene] = r
    out = []
    for n in order:
        c = by_name[n]
        rows = list(c["rows"].values())
        c["element"] = rows[0]["element"]
        c["bytes"] = rows[0]["bytes_per_element"]
        c["mean_flip"] = statistics.fmean(r["flip"] for r in rows)
        c["ns"] = statistics.median(r["shade_ns_per_sample"] for r in rows)
        c["bake"] = sum(r["bake_seconds"] for r in rows)
        c["cached"] = any(r.get("bakes_cached") for r in rows)
        out.append(c)
    return out


def front(rows, cost):
    """Names on the Pareto front of cost against mean FLIP (lower is better in both), both as
    the table shows them: rows the table shows equal tie."""
    def key(c):
        return cost(c), round(c["mean_flip"], 3)
    best = set()
    for a in rows:
        ca, fa = key(a)
        if not any((cb <= ca and fb < fa) or (cb < ca and fb <= fa) for cb, fb in map(key, rows)):
            best.add(a["name"])
    return best


def scene_cells(c, names):
    cells = []
    for s in names:
        r = c["rows"].get(s)
        cells.append("—" if r is None else "%s / %s" % (g(r["flip"]), sci(r["rel_mse_floored"])))
    return cells


def table_head(names, last, text_last=False):
    head = ["representation"] + ["%s FLIP / rel. MSE" % s for s in names] + last
    align = ["---"] + ["---:"] * (len(head) - 1 - text_last) + ["---"] * text_last
    return ["| " + " | ".join(head) + " |", "|" + "|".join(align) + "|"]


def irradiance_block(scenes):
    names = [s for s, _ in scenes]
    rows = combine(scenes, is_irradiance)
    lines = table_head(names, ["mean FLIP", "bytes", "shading ns/sample", "bake s", "best per"],
                       text_last=True)
    for kind in ("lightmap", "volume"):
        group = [c for c in rows if c["name"].startswith(kind)]
        group.sort(key=lambda c: (c["bytes"], round(c["mean_flip"], 3), c["name"]))
        per_byte = front(group, lambda c: c["bytes"])
        per_ns = front(group, lambda c: round(c["ns"]))
        for c in group:
            best = [w for w, f in (("byte", per_byte), ("ns", per_ns)) if c["name"] in f]
            lines.append("| " + " | ".join(
                [c["name"]] + scene_cells(c, names) +
                [g(c["mean_flip"]), "%d %s" % (c["bytes"], c["element"]), "%.0f" % c["ns"],
                 "%.2f%s" % (c["bake"], " (cached)" if c["cached"] else ""),
                 ", ".join(best)]) + " |")
    return lines


def others_block(scenes):
    names = [s for s, _ in scenes]
    rows = combine(scenes, lambda n: not is_irradiance(n))
    rows.sort(key=lambda c: (round(c["mean_flip"], 3), c["name"]))
    lines = table_head(names, ["mean FLIP", "bytes", "shading ns/sample", "bake s"])
    for c in rows:
        lines.append("| " + " | ".join(
            [c["name"]] + scene_cells(c, names) +
            [g(c["mean_flip"]), "%d %s" % (c["bytes"], c["element"]), "%.0f" % c["ns"],
             "%.2f%s" % (c["bake"], " (cached)" if c["cached"] else "")]) + " |")
    return lines


def scene_block(name, t):
    ref = t["reference"]
    rows = sorted(t["representations"], key=lambda r: r["flip"])  # stable: the report's ties
    lines = ["`%s`: %s×%s, reference %s samples per pixel at relative noise %s (every "
             "representation at the same sample positions), %d representations; shared camera "
             "rays %.0f ns per sample, shown apart; %.1f s wall on %s threads. `%s`"
             % (t["scene"], t["width"], t["height"], ref["spp"], g(ref["relative_noise"]),
                len(rows), t["sampling"]["camera_ns_per_sample"] or 0, t["seconds"] or 0,
                t["threads"], t["command"]), "",
             "| representation | FLIP | rel. MSE (floored) | bake s | shading ns/sample | "
             "bytes/element |", "|---|---:|---:|---:|---:|---:|"]
    for r in rows:
        lines.append("| %s | %s | %.2e | %.2f%s | %.0f | %d %s |"
                     % (r["name"], g(r["flip"]), r["rel_mse_floored"], r["bake_seconds"],
                        " (cached)" if r.get("bakes_cached") else "", r["shade_ns_per_sample"],
                        r["bytes_per_element"], r["element"]))
    return lines


def blocks(scenes):
    b = {"irradiance": irradiance_block(scenes), "others": others_block(scenes)}
    for name, t in scenes:
        b["scene:" + name] = scene_block(name, t)
    return b


def sync(path, made, write):
    """Replaces (write) or compares the marked blocks of one file; returns the blocks seen."""
    try:
        with open(path) as f:
            lines = f.read().split("\n")
    except OSError as e:
        raise InputError("%s: cannot read (%s)" % (path, e))
    out, seen, i = [], [], 0
    while i < len(lines):
        out.append(lines[i])
        m = BEGIN.match(lines[i])
        i += 1
        if not m:
            continue
        name = m.group(1)
        if name not in made:
            raise InputError("%s:%d: unknown block %r (the run has: %s)"
                             % (path, i, name, ", ".join(made)))
        j = i
        while j < len(lines) and lines[j] != END:
            j += 1
        if j == len(lines):
            raise InputError("%s:%d: block %r has no %s line" % (path, i, name, END))
        if not write and lines[i:j] != made[name]:
            raise InputError("%s:%d: block %r differs from the run's table (rerun with --update)"
                             % (path, i, name))
        out.extend(made[name])
        seen.append(name)
        i = j
    if not seen:
        raise InputError("%s: no \"<!-- render_summary: NAME -->\" block" % path)
    if write:
        with open(path + ".tmp", "w") as f:
            f.write("\n".join(out))
        os.replace(path + ".tmp", path)
    return seen


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("inputs", nargs="+", help="report.json files or a run saved by --save")
    ap.add_argument("--save", metavar="RUN.json", help="write the fields the tables read")
    ap.add_argument("--md", metavar="FILE", help="write the tables to FILE (else to stdout "
                    "unless --check or --update is given)")
    ap.add_argument("--update", action="append", metavar="FILE", default=[],
                    help="rewrite FILE's marked blocks (repeatable)")
    ap.add_argument("--check", action="append", metavar="FILE", default=[],
                    help="fail where FILE's marked blocks differ (repeatable)")
    a = ap.parse_args()
    try:
        scenes = load(a.inputs)
        made = blocks(scenes)
        if a.save:
            save(a.save, scenes)
        md = "".join("<!-- render_summary: %s -->\n%s\n%s\n\n" % (name, "\n".join(lines), END)
                     for name, lines in made.items())
        if a.md:
            with open(a.md + ".tmp", "w") as f:
                f.write(md)
            os.replace(a.md + ".tmp", a.md)
        elif not a.check and not a.update:
            sys.stdout.write(md)
        for path, write in [(p, False) for p in a.check] + [(p, True) for p in a.update]:
            seen = sync(path, made, write)
            print("%s: %s %d blocks of %s (%s)" % (TOOL, "wrote" if write else "checked",
                                                   len(seen), path, ", ".join(seen)))
    except InputError as err:
        sys.exit("%s: %s" % (TOOL, err))


if __name__ == "__main__":
    main()
