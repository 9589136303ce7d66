#!/usr/bin/env python3
"""Checks in a headless browser that report.html's table sorts when a column header is clicked
(tests/cli/render_tests.cmake).

Usage: check_report_sort_browser.py DIR. Copies DIR/report.html beside itself with a probe
script appended that clicks the headers the way a user does (dispatching click events on the
<th> cells) and writes the resulting row orders into the page; Debian's chromium loads the copy
(--headless --dump-dom, no network, a fresh profile) and the DOM it prints is read back. The
orders must be: FLIP once -> ascending by FLIP, twice -> descending; "representation" once ->
ascending names. Prints "browser-sort-ok"; "browser-check-skipped: ..." (exit 0) when chromium
is not installed; else one line saying what failed (exit 1).
"""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

PROBE = """<script>
(function () {
  var t = document.getElementById('results'), heads = t.tHead.rows[0].cells, out = {};
  function col(name) {
    for (var i = 0; i < heads.length; ++i) if (heads[i].textContent.trim() === name) return i;
    return -1;
  }
  function names() {
    var c = col('representation');
    return Array.prototype.map.call(t.tBodies[0].rows, function (r) {
      return r.cells[c].textContent.trim();
    });
  }
  var f = heads[col('FLIP')], n = heads[col('representation')];
  f.dispatchEvent(new MouseEvent('click', {bubbles: true}));
  out.flip_up = names();
  out.flip_up_sort = f.getAttribute('aria-sort');
  f.dispatchEvent(new MouseEvent('click', {bubbles: true}));
  out.flip_down = names();
  out.flip_down_sort = f.getAttribute('aria-sort');
  n.dispatchEvent(new MouseEvent('click', {bubbles: true}));
  out.name_up = names();
  var p = document.createElement('pre');
  p.id = 'probe-result';
  p.textContent = JSON.stringify(out);
  document.body.appendChild(p);
})();
</script>
"""


def fail(msg):
    print("browser-sort-FAILED: " + msg)
    sys.exit(1)


def main():
    d = sys.argv[1]
    browser = shutil.which("chromium") or shutil.which("chromium-browser")
    if not browser:
        print("browser-check-skipped: chromium is not installed (Debian: apt-get install "
              "chromium); the sort script of report.html was not run in a browser")
        return
    with open(os.path.join(d, "report.json")) as f:
        rows = json.load(f)["representations"]
    html = open(os.path.join(d, "report.html")).read()
    if "</body>" not in html:
        fail("report.html has no </body>")
    page = os.path.join(d, "sort_probe.html")
    with open(page, "w") as f:
        f.write(html.replace("</body>", PROBE + "</body>"))
    profile = tempfile.mkdtemp(prefix="sphbasis-chromium-")
    try:
        p = subprocess.run(
            [browser, "--headless", "--no-sandbox", "--disable-gpu",
             "--disable-background-networking", "--no-first-run", "--disable-component-update",
             "--disable-sync", "--user-data-dir=" + profile, "--dump-dom",
             "file://" + os.path.abspath(page)],
            stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=120)
    finally:
        shutil.rmtree(profile, ignore_errors=True)
        os.remove(page)
    m = re.search(r'<pre id="probe-result">(.*?)</pre>', p.stdout.decode("utf-8", "replace"), re.S)
    if not m:
        fail("no probe result in the DOM chromium printed (exit %d): %s"
             % (p.returncode, p.stderr.decode("utf-8", "replace")[-300:]))
    out = json.loads(m.group(1).replace("&quot;", '"').replace("&amp;", "&"))

    def label(r):
        return r["name"] + ("" if r["against"] == "path tracer" else " (vs %s)" % r["against"])

    by_flip = [label(r) for r in sorted(rows, key=lambda r: r["flip"])]
    flips = {label(r): r["flip"] for r in rows}
    if [flips[n] for n in out["flip_up"]] != [flips[n] for n in by_flip]:
        fail("after one click on FLIP: %s, expected ascending FLIP %s" % (out["flip_up"], by_flip))
    if [flips[n] for n in out["flip_down"]] != [flips[n] for n in reversed(by_flip)]:
        fail("after two clicks on FLIP: %s, expected descending FLIP" % out["flip_down"])
    if out["flip_up_sort"] != "ascending" or out["flip_down_sort"] != "descending":
        fail("aria-sort %s then %s" % (out["flip_up_sort"], out["flip_down_sort"]))
    names = [label(r) for r in rows]
    if sorted(out["name_up"]) != sorted(names) or len(out["name_up"]) != len(names):
        fail("the rows changed: %s" % out["name_up"])
    if out["name_up"] != sorted(out["name_up"]):
        fail("after a click on representation: %s, not by name" % out["name_up"])
    print("browser-sort-ok: %d rows sorted by FLIP up, down and by name" % len(rows))


if __name__ == "__main__":
    main()
