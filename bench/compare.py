#!/usr/bin/python3
"""Compares two builds of one Google Benchmark binary in one run: runs OLD and NEW alternately
(ROUNDS rounds, each with --benchmark_repetitions=REPS), takes each benchmark's minimum real
time over all of its runs, and prints new/old ratios (below 1: the new build is faster). The
alternation spreads the drift of a shared machine over both builds.

Usage: bench/compare.py OLD_BINARY NEW_BINARY [--filter REGEX] [--rounds N] [--reps N]
"""
import argparse
import json
import subprocess


def run(binary, flt, reps):
    out = subprocess.run([binary, "--benchmark_format=json", "--benchmark_filter=" + flt,
                          "--benchmark_repetitions=%d" % reps],
                         check=True, capture_output=True, text=True).stdout
    times = {}
    for b in json.loads(out)["benchmarks"]:
        if b.get("run_type") != "iteration":
            continue
        name = b["run_name"] if "run_name" in b else b["name"]
        times.setdefault(name, []).append(b["real_time"])
    return times


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("old")
    ap.add_argument("new")
    ap.add_argument("--filter", default=".")
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--reps", type=int, default=3)
    a = ap.parse_args()
    best = {"old": {}, "new": {}}
    for _ in range(a.rounds):
        for key, binary in (("old", a.old), ("new", a.new)):
            for name, ts in run(binary, a.filter, a.reps).items():
                best[key][name] = min(ts + [best[key].get(name, float("inf"))])
    names = [n for n in best["new"] if n in best["old"]]
    print("%-52s %12s %12s %8s" % ("benchmark", "old", "new", "new/old"))
    ratios = []
    for n in names:
        o, w = best["old"][n], best["new"][n]
        ratios.append(w / o)
        print("%-52s %12.4g %12.4g %8.3f" % (n, o, w, w / o))
    missing = sorted(set(best["old"]) ^ set(best["new"]))
    if missing:
        print("only in one build: " + ", ".join(missing))
    if ratios:
        ratios.sort()
        print("ratios: min %.3f, median %.3f, max %.3f over %d benchmarks"
              % (ratios[0], ratios[len(ratios) // 2], ratios[-1], len(ratios)))


if __name__ == "__main__":
    main()
