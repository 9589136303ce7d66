#!/usr/bin/env python3
"""Checks the output directory of `sphbasis render` (tests/cli/render_tests.cmake).

Usage: check_render_report.py DIR [CHECK ...]; prints "render-report-ok" when every check holds,
else one line saying what failed (exit 1). Always checked: report.json parses and has the
documented keys; every file it names exists beside it, with the PNG and OpenEXR signatures;
report.md and report.html exist and link every image; no temporary file or staging directory
is left in DIR.
CHECKs:
  rows=N              N representations in the table
  bakes_run=N         prepare() ran N bakes (bakes_loaded=N likewise)
  max_rel_mse=NAME:X  NAME's relative MSE is at most X
  less=A:B            A's relative MSE is below B's
  judged_min=X        every row judged at least a fraction X of its pixels
  counter=NAME:N      the reference's counter NAME equals N (e.g. bounce_rays:0)
  effect~TEXT         some effect of the plan contains TEXT; effect!~TEXT: none does
  plan~TEXT           some plan step (what: reason) contains TEXT
"""
import json
import os
import sys

PNG = b"\x89PNG\r\n\x1a\n"
EXR = b"\x76\x2f\x31\x01"


def fail(msg):
    print("render-report-FAILED: " + msg)
    sys.exit(1)


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
                  "cannot_show", "image", "error_image", "exr"):
            if k not in row:
                fail("representation %s: no key %r" % (row.get("name"), k))
        files += [row["image"], row["error_image"], row["exr"]]
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
