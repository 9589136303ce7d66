#!/usr/bin/env python3
"""Checks tools/plot/render_summary.py on the committed fixture
tests/data/render_summary_fixture.json (two made-up scenes "a" and "b"; volume and
volume-ambient-cube ran on "a" only, prt-texel on "b" only; lightmap-ambient-dice-ycocg is a name
the tool has no list of).

Usage: check_render_summary.py TOOL FIXTURE WORKDIR
The irradiance table must equal the one worked out by hand below: the rows picked by name pattern
(lightmap-*, volume*), lightmaps then volumes, each by bytes then mean FLIP (ties by name); mean
FLIP the mean over the scenes a row ran on, "—" where it did not run, ns the median over the
scenes, bake s the sum; "best per" the Pareto fronts of bytes (ns) against mean FLIP within
texels and within probes. Then: the other rows by mean FLIP; --update writes the blocks of a
document and --check passes on it, fails on one changed digit (naming the block) and on an
unknown block; bad input is one line and exit 1. Prints "render-summary-ok".
"""
import os
import subprocess
import sys

# By hand from the fixture. ycocg (84 bytes, 0.050) beats sh9 (108, 0.060) per byte; sh9 (210 ns)
# is faster than ycocg (300 ns), so both are on the ns front. sh4 and hbasis4 tie in bytes and
# FLIP (both per byte); hbasis4 is faster (90 ns against the median of 100 and 120: 110). sg9 is
# dominated by sh9 in both. volume is better and faster than volume-ambient-cube, which has fewer
# bytes.
IRRADIANCE = """\
| representation | a FLIP / rel. MSE | b FLIP / rel. MSE | mean FLIP | bytes | shading ns/sample | bake s | best per |
|---|---:|---:|---:|---:|---:|---:|---|
| lightmap-hl2 | 0.300 / 3.0e-02 | 0.400 / 1.0e-01 | 0.350 | 36 texel | 80 | 0.50 | byte, ns |
| lightmap-hbasis4 | 0.100 / 2.0e-03 | 0.200 / 2.0e-02 | 0.150 | 48 texel | 90 | 0.50 | byte, ns |
| lightmap-sh4 | 0.100 / 2.0e-03 | 0.200 / 2.0e-02 | 0.150 | 48 texel | 110 | 0.50 | byte |
| lightmap-ambient-dice-ycocg | 0.040 / 9.0e-04 | 0.060 / 1.5e-03 | 0.050 | 84 texel | 300 | 2.00 | byte, ns |
| lightmap-sh9 | 0.050 / 1.0e-03 | 0.070 / 2.0e-03 | 0.060 | 108 texel | 210 | 1.00 | ns |
| lightmap-sg9 | 0.090 / 4.0e-03 | 0.110 / 5.0e-03 | 0.100 | 108 texel | 500 | 1.00 |  |
| volume-ambient-cube | 0.120 / 1.0e-02 | — | 0.120 | 72 probe | 160 | 0.00 | byte |
| volume | 0.080 / 5.0e-03 | — | 0.080 | 108 probe | 150 | 0.00 | byte, ns |"""
OTHERS = ["ao", "irradiance-sh9", "prt-texel"]  # mean FLIP 0.200, 0.250, 0.250 (ties by name)


def run(*args):
    p = subprocess.run([sys.executable, TOOL] + list(args), capture_output=True, text=True)
    return p.returncode, p.stdout, p.stderr


def block(text, name):
    head = "<!-- render_summary: %s -->\n" % name
    start = text.index(head) + len(head)
    return text[start:text.index("\n<!-- /render_summary -->", start)]


def fails(what, expected, *args):
    rc, out, err = run(*args)
    if rc != 1 or out or err.count("\n") != 1 or expected not in err:
        sys.exit("%s: expected exit 1 and one line with %r, got rc %d, stdout %r, stderr %r"
                 % (what, expected, rc, out, err))


def main():
    global TOOL
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    TOOL, fixture, work = sys.argv[1:]
    os.makedirs(work, exist_ok=True)
    rc, out, err = run(fixture)
    if rc != 0:
        sys.exit("render_summary.py failed: " + err)
    got = block(out, "irradiance")
    if got != IRRADIANCE:
        sys.exit("irradiance table differs from the hand-made one:\n%s\nexpected:\n%s"
                 % (got, IRRADIANCE))
    others = [line.split(" | ")[0][2:] for line in block(out, "others").split("\n")[2:]]
    if others != OTHERS:
        sys.exit("others: expected %s, got %s" % (OTHERS, others))
    scene_a = block(out, "scene:a").split("\n")
    if "10 representations" not in scene_a[0] or not scene_a[4].startswith(
            "| lightmap-ambient-dice-ycocg | 0.040 | 9.00e-04 | 1.00 | 300 | 84 texel |"):
        sys.exit("scene:a: expected 10 representations ranked by FLIP, got:\n" + "\n".join(scene_a))
    # A saved run reads back to the same tables.
    saved = os.path.join(work, "saved.json")
    rc, out2, err = run("--save", saved, fixture)
    rc2, out3, _ = run(saved)
    if rc or rc2 or out2 != out or out3 != out:
        sys.exit("--save: the saved run does not give the same tables: " + err)
    # A document with two blocks: --update fills them, --check accepts them and refuses a change.
    doc = os.path.join(work, "doc.md")
    with open(doc, "w") as f:
        f.write("# t\n<!-- render_summary: irradiance -->\nold\n<!-- /render_summary -->\n"
                "text\n<!-- render_summary: scene:b -->\n<!-- /render_summary -->\n")
    rc, out, err = run("--update", doc, fixture)
    if rc or "wrote 2 blocks of" not in out:
        sys.exit("--update: " + out + err)
    rc, out, err = run("--check", doc, fixture)
    if rc or "checked 2 blocks of" not in out:
        sys.exit("--check after --update: " + out + err)
    with open(doc) as f:
        text = f.read()
    if "old" in text or "text\n" not in text or IRRADIANCE not in text:
        sys.exit("--update: the document is not the blocks around its own text:\n" + text)
    with open(doc, "w") as f:
        f.write(text.replace("| 0.060 | 108 texel |", "| 0.061 | 108 texel |"))
    fails("--check of a changed number", "block 'irradiance' differs", "--check", doc, fixture)
    with open(doc, "w") as f:
        f.write("<!-- render_summary: scene:c -->\n<!-- /render_summary -->\n")
    fails("--check of an unknown block", "unknown block 'scene:c'", "--check", doc, fixture)
    # Bad input.
    bad = os.path.join(work, "bad.json")
    with open(bad, "w") as f:
        f.write('{"tool": "sphbasis render", "scene": "x.json", "reference": {}, "sampling": {}, '
                '"representations": [{"name": "ao", "flip": NaN}]}')
    fails("a NaN", "flip: expected a finite number", bad)
    with open(bad, "w") as f:
        f.write('{"tool": "sphbasis render", "scene": "x.json", "representations": []}')
    fails("no reference", 'expected the objects "reference" and "sampling"', bad)
    with open(bad, "w") as f:
        f.write('{"protocol": "paper", "rows": []}')
    fails("not a report", "expected a report.json of `sphbasis render`", bad)
    fails("a missing file", "cannot read JSON", os.path.join(work, "none.json"))
    fails("a scene twice", "scene 'a' given twice", fixture, fixture)
    print("render-summary-ok")


if __name__ == "__main__":
    main()
