#!/usr/bin/env python3
"""Checks the output directory of `sphbasis render` (tests/cli/render_tests.cmake).

Usage: check_render_report.py DIR [CHECK ...]; prints "render-report-ok" when every check holds,
else one line saying what failed (exit 1). Always checked: report.json parses and has the
documented keys; every file it names exists beside it, with the PNG and OpenEXR signatures;
report.md and report.html exist and link every image; no temporary file or staging directory
is left in DIR; every
metric of every row is a finite number in its range (flip in [0, 1], smape_floored in [0, 2],
outside_3_stderr in [0, 1], the rest >= 0); the ranks are 1..N in the order of flip; report.json
names the ranking metric and defines every metric; the sampling rule (every representation at
its reference's sample count, a finite shading time); report.html has the sortable table (id
"results", one row per representation, a data-v sort key in every numeric cell), the inline sort
script, an inline SVG plot with a point per representation, each representation's image in its
row, and no external resource (no http(s): URL in a src or href).
CHECKs:
  rows=N              N representations in the table
  bakes_run=N         prepare() ran N bakes (bakes_loaded=N likewise)
  max_rel_mse=NAME:X  NAME's relative MSE is at most X
  less=A:B            A's relative MSE is below B's
  less_flip=A:B       A's FLIP is below B's
  max_flip=NAME:X     NAME's FLIP is at most X
  max_metric=KEY:X    every row's metric KEY is at most X (e.g. rel_mse_floored:10)
  bytes=NAME:N        NAME stores N bytes per element (texel, vertex or probe)
  judged_min=X        every row judged at least a fraction X of its pixels
  counter=NAME:N      the reference's counter NAME equals N (e.g. bounce_rays:0)
  effect~TEXT         some effect of the plan contains TEXT; effect!~TEXT: none does
  plan~TEXT           some plan step (what: reason) contains TEXT
"""
import json
import math
import os
import re
import sys

PNG = b"\x89PNG\r\n\x1a\n"
EXR = b"\x76\x2f\x31\x01"


def fail(msg):
    print("render-report-FAILED: " + msg)
    sys.exit(1)


# Every metric of a row and its upper bound.
METRICS = {"rmse": math.inf, "rel_mse": math.inf, "smape": 1.0, "rel_mse_floored": math.inf,
           "smape_floored": 2.0, "outside_3_stderr": 1.0, "flip": 1.0}


def check_html(html, r):
    m = re.search(r'<table id="results">(.*?)</table>', html, re.S)
    if not m:
        fail("report.html: no table with id 'results'")
    body = re.search(r"<tbody>(.*?)</tbody>", m.group(1), re.S)
    rows = re.findall(r"<tr>(.*?)</tr>", body.group(1) if body else "", re.S)
    if len(rows) != len(r["representations"]):
        fail("report.html: %d table rows, expected %d" % (len(rows), len(r["representations"])))
    for row in r["representations"]:
        mine = [t for t in rows if ">%s<" % row["name"] in t or ">%s (" % row["name"] in t]
        if not mine or 'src="%s"' % row["image"] not in mine[0]:
            fail("report.html: the row of %s does not show its image" % row["name"])
    for t in rows:
        for v in re.findall(r'data-v="([^"]*)"', t):
            if not math.isfinite(float(v)):
                fail("report.html: a sort key %r is not a finite number" % v)
    if "<script>" not in html or "aria-sort" not in html or "addEventListener('click'" not in html:
        fail("report.html: no inline sort script")
    svg = re.search(r'<svg id="cost-plot".*?</svg>', html, re.S)
    if not svg or svg.group(0).count("<circle") != len(r["representations"]):
        fail("report.html: no inline SVG plot with a point per representation")
    if re.search(r'(src|href)="(https?:)?//', html) or "<script src" in html:
        fail("report.html: an external resource")


def main():
    d = sys.argv[1]
    try:
        with open(os.path.join(d, "report.json")) as f:
            r = json.load(f)
    except Exception as e:  # noqa: BLE001
        fail("report.json: %s" % e)
    for k in ("tool", "scene", "plan", "reference", "bakes", "bakes_run", "bakes_loaded",
              "representations", "width", "height", "threads", "tonemap", "exposure"):
        if k not in r:
            fail("report.json: no key %r" % k)
    files = [r["reference"]["image"], r["reference"]["exr"], r["reference"]["stderr_exr"]]
    for row in r["representations"]:
        for k in ("name", "rmse", "rel_mse", "smape", "judged_fraction", "bake_seconds",
                  "render_ms_1_thread", "render_ms_all_threads", "bytes_per_element",
                  "cannot_show", "image", "error_image", "exr", "rel_mse_floored",
                  "smape_floored", "outside_3_stderr", "flip", "rank", "flip_image"):
            if k not in row:
                fail("representation %s: no key %r" % (row.get("name"), k))
        for k, hi in METRICS.items():
            v = row[k]
            if not isinstance(v, (int, float)) or not math.isfinite(v) or v < 0 or v > hi:
                fail("representation %s: %s = %r, expected a finite number in [0, %s]"
                     % (row["name"], k, v, hi))
        files += [row["image"], row["error_image"], row["flip_image"], row["exr"]]
    # The sampling rule: every representation has the sample count of the reference it is
    # compared with (the path tracer's final count, or the specular reference's ss x ss), and a
    # shading time apart from the shared camera rays.
    smp = r.get("sampling", {})
    for k in ("rule", "filter", "representation_spp", "specular_spp", "camera_ns_per_sample"):
        if k not in smp:
            fail("report.json: sampling has no key %r" % k)
    if smp["representation_spp"] != r["reference"]["spp"]:
        fail("report.json: representations at %r spp, the reference at %r"
             % (smp["representation_spp"], r["reference"]["spp"]))
    for row in r["representations"]:
        want = (smp["specular_spp"] if row["against"] == "specular reference"
                else smp["representation_spp"])
        if row.get("spp") != want:
            fail("representation %s: %r spp, expected %r (its reference's)"
                 % (row["name"], row.get("spp"), want))
        v = row.get("shade_ns_per_sample")
        if not isinstance(v, (int, float)) or not math.isfinite(v) or v < 0:
            fail("representation %s: shade_ns_per_sample = %r" % (row["name"], v))
    if "specular_reference" in r and \
            smp["specular_spp"] != r["specular_reference"]["supersampling"] ** 2:
        fail("report.json: specular representations at %r spp, the reference at %r^2"
             % (smp["specular_spp"], r["specular_reference"]["supersampling"]))
    if r.get("ranked_by") != "flip" or not r.get("ranking_reason"):
        fail("report.json: ranked_by %r, expected 'flip' with a ranking_reason" % r.get("ranked_by"))
    for k in METRICS:
        if k not in r.get("metrics", {}):
            fail("report.json: metrics has no definition of %r" % k)
    ranked = sorted(r["representations"], key=lambda x: x["rank"])
    if [x["rank"] for x in ranked] != list(range(1, len(ranked) + 1)):
        fail("ranks %s, expected 1..%d" % ([x["rank"] for x in ranked], len(ranked)))
    if any(a["flip"] > b["flip"] for a, b in zip(ranked, ranked[1:])):
        fail("ranks not in the order of flip")
    md = open(os.path.join(d, "report.md")).read()
    html = open(os.path.join(d, "report.html")).read()
    for name in files:
        p = os.path.join(d, name)
        if not os.path.isfile(p):
            fail("missing file " + name)
        head = open(p, "rb").read(8)
        if name.endswith(".png") and head != PNG:
            fail(name + ": not a PNG")
        if name.endswith(".exr") and head[:4] != EXR:
            fail(name + ": not an OpenEXR file")
        if name.endswith(".png") and (name not in md or 'src="%s"' % name not in html):
            fail(name + ": not linked from report.md and report.html")
    check_html(html, r)
    for f in os.listdir(d):
        if ".tmp-" in f or f.startswith(".sphbasis-staging-"):
            fail("temporary file left: " + f)
    rows = {row["name"]: row for row in r["representations"]}
    for c in sys.argv[2:]:
        if c.startswith("rows="):
            if len(rows) != int(c[5:]):
                fail("%d rows, expected %s" % (len(rows), c[5:]))
        elif c.startswith("bakes_run=") or c.startswith("bakes_loaded="):
            k, v = c.split("=")
            if r[k] != int(v):
                fail("%s = %s, expected %s" % (k, r[k], v))
        elif c.startswith("max_rel_mse="):
            name, x = c[12:].split(":")
            if name not in rows or not rows[name]["rel_mse"] <= float(x):
                fail("%s: rel_mse %s > %s" % (name, rows.get(name, {}).get("rel_mse"), x))
        elif c.startswith("less="):
            a, b = c[5:].split(":")
            if a not in rows or b not in rows or not rows[a]["rel_mse"] < rows[b]["rel_mse"]:
                fail("%s: rel_mse not below %s's" % (a, b))
        elif c.startswith("less_flip="):
            a, b = c[10:].split(":")
            if a not in rows or b not in rows or not rows[a]["flip"] < rows[b]["flip"]:
                fail("%s: flip not below %s's" % (a, b))
        elif c.startswith("max_flip="):
            name, x = c[9:].split(":")
            if name not in rows or not rows[name]["flip"] <= float(x):
                fail("%s: flip %s > %s" % (name, rows.get(name, {}).get("flip"), x))
        elif c.startswith("max_metric="):
            k, x = c[11:].split(":")
            for row in rows.values():
                if not row[k] <= float(x):
                    fail("%s: %s = %s > %s" % (row["name"], k, row[k], x))
        elif c.startswith("bytes="):
            name, n = c[6:].split(":")
            if name not in rows or rows[name]["bytes_per_element"] != int(n):
                fail("%s: %s bytes per element, expected %s"
                     % (name, rows.get(name, {}).get("bytes_per_element"), n))
        elif c.startswith("judged_min="):
            for row in rows.values():
                if row["judged_fraction"] < float(c[11:]):
                    fail("%s: judged %s" % (row["name"], row["judged_fraction"]))
        elif c.startswith("counter="):
            name, n = c[8:].split(":")
            v = r["reference"]["counters"][name]
            if v != int(n):
                fail("counter %s = %s, expected %s" % (name, v, n))
        elif c.startswith("effect!~"):
            if any(c[8:] in e for e in r["reference"]["effects"]):
                fail("an effect contains %r: %s" % (c[8:], r["reference"]["effects"]))
        elif c.startswith("effect~"):
            if not any(c[7:] in e for e in r["reference"]["effects"]):
                fail("no effect contains %r: %s" % (c[7:], r["reference"]["effects"]))
        elif c.startswith("plan~"):
            if not any(c[5:] in p["what"] + ": " + p["reason"] for p in r["plan"]):
                fail("no plan step contains %r" % c[5:])
        else:
            fail("unknown check " + c)
    print("render-report-ok")


if __name__ == "__main__":
    main()
