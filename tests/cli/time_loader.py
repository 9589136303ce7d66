#!/usr/bin/env python3
"""Times the scene loader on a scene of N quads whose last mesh is wrong.

Usage: time_loader.py SPHBASIS N MAX_CPU_SECONDS

Writes loader_N.json in the current directory, runs `sphbasis bake` on it and prints
"loader-time-ok" when the command fails with the one expected line (naming meshes[N-1]) within
MAX_CPU_SECONDS of CPU time (user + system of the child, which a loaded machine does not
inflate the way it does wall time). Both times are printed either way.
"""
import json
import resource
import subprocess
import sys
import time


def main():
    exe, n, limit = sys.argv[1], int(sys.argv[2]), float(sys.argv[3])
    meshes = [{"name": "q%d" % i, "shape": "quad", "center": [i % 300, i // 300, 0]}
              for i in range(n)]
    meshes[-1]["albedo"] = [2, 0, 0]  # outside [0, 1]: found only after every other mesh
    path = "loader_%d.json" % n
    with open(path, "w") as f:
        json.dump({"meshes": meshes}, f)
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.monotonic()
    p = subprocess.run([exe, "bake", path], capture_output=True, text=True, timeout=300)
    wall = time.monotonic() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    err = p.stderr.strip()
    print("loader: %d meshes: %.3f s CPU, %.3f s wall, exit %d: %s" % (n, cpu, wall,
                                                                     p.returncode, err))
    want = "meshes[%d].albedo[0]: expected a value in [0, 1]" % (n - 1)
    if p.returncode != 0 and err.count("\n") == 0 and want in err and cpu <= limit:
        print("loader-time-ok")


if __name__ == "__main__":
    main()
