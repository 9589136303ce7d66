#!/usr/bin/env bash
# What including sphbasis costs a user: g++ -fsyntax-only wall time (median of 3) and peak
# memory for a file that includes only the given header, all in one run so rows compare.
#   bench/include_cost.sh [[DIR:]header ...]   (default: the umbrellas, basis/sh.hpp,
#                                   ops/imse.hpp and Eigen/Dense for scale). DIR: an include
#                                   directory other than include/, e.g. an older checkout's, so
#                                   old and new are compared in one run.
set -euo pipefail
cd "$(dirname "$0")/.."
cxx=${CXX:-g++}
headers=("$@")
[ ${#headers[@]} -eq 0 ] && headers=(sphbasis/core.hpp sphbasis/basis/sh.hpp sphbasis/sphbasis.hpp
                                       sphbasis/ops/imse.hpp Eigen/Dense)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
printf '%-28s %10s %10s\n' header "wall s" "peak MB"
for h in "${headers[@]}"; do
  inc=include
  hdr=$h
  if [[ $h == *:* ]]; then inc=${h%%:*}; hdr=${h#*:}; fi
  echo "#include <$hdr>" >"$tmp/t.cpp"
  ts=()
  mem=0
  for _ in 1 2 3; do
    start=$(date +%s.%N)
    kb=$( { /usr/bin/time -f '%M' "$cxx" -std=c++17 -fsyntax-only -I"$inc" -I/usr/include/eigen3 \
            "$tmp/t.cpp" ; } 2>&1 | tail -1)
    ts+=("$(echo "$(date +%s.%N) - $start" | bc)")
    mem=$kb
  done
  med=$(printf '%s\n' "${ts[@]}" | sort -n | sed -n 2p)
  printf '%-28s %10.2f %10d\n' "$h" "$med" $((mem / 1024))
done
