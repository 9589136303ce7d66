#!/usr/bin/python3
"""The README's peer table from ONE run of bench_peers (JSON, ideally with repetitions):

    build/bench/peers/bench_peers --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \\
        --benchmark_out=peers.json --benchmark_out_format=json
    bench/peers/peer_table.py peers.json

Benchmarks are named group/param/implementation with a `per_item` counter (seconds per item).
Per group/param it compares the fastest sphbasis entry point (implementations starting with
"sphbasis") with the fastest peer (everything else except "ref_" rows), separately for the
unit-input calls (names ending in "_unit") and the rest. Ratio = peer / sphbasis: > 1 means
sphbasis is faster. Medians where the run has them, else the mean of the iterations.
"""
import json
import sys
from collections import OrderedDict


def main():
    data = json.load(open(sys.argv[1]))
    per = OrderedDict()  # name -> seconds per item
    agg = {}
    for b in data["benchmarks"]:
        name = b.get("run_name", b["name"])
        if b.get("run_type") == "aggregate":
            if b.get("aggregate_name") == "median":
                agg[name] = b["per_item"]
        else:
            per.setdefault(name, []).append(b["per_item"])
    times = OrderedDict()
    for name in list(agg) + [n for n in per if n not in agg]:
        times[name] = agg.get(name, sum(per.get(name, [0])) / max(1, len(per.get(name, []))))
    groups = OrderedDict()
    for name, t in times.items():
        g, p, impl = name.split("/", 2)
        groups.setdefault((g, p), []).append((impl, t * 1e9))
    print("| operation | bands | sphbasis | ns | fastest peer | ns | peer / sphbasis |")
    print("|---|---:|---|---:|---|---:|---:|")
    for (g, p), rows in groups.items():
        for unit in (True, False):
            sb = [r for r in rows if r[0].startswith("sphbasis") and r[0].endswith("_unit") == unit]
            pe = [r for r in rows if not r[0].startswith(("sphbasis", "ref_")) and
                  r[0].endswith("_unit") == unit]
            if not sb or not pe:
                continue
            s = min(sb, key=lambda r: r[1])
            q = min(pe, key=lambda r: r[1])
            print("| %s | %s | %s | %.3g | %s | %.3g | %.2f |" % (g, p, s[0], s[1], q[0], q[1],
                                                                  q[1] / s[1]))


if __name__ == "__main__":
    main()
