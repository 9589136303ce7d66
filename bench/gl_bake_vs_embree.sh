#!/bin/sh
# Times `sphbasis bake --engine gl` (Hill's depth maps, tools/gl/gl_bake.hpp) beside the Embree
# bake on the same points, in one run: ao and transfer (3 bands, 0 bounces), gl with N
# directions and R^2 maps, Embree with N cosine-weighted rays per point (the same number of
# samples per point; gl's are deterministic, half of them below the horizon). Prints one line
# per case: the bake seconds of each (bake.json "seconds.bake"; gl's includes creating the
# context), their ratio and gl's renderer.
# Usage: bench/gl_bake_vs_embree.sh [BUILD_DIR] (default build); N and R from GL_DIRECTIONS and
# GL_RESOLUTION (default 1024, 512).
set -e
build=${1:-build}
bin=$build/bin/sphbasis
here=$(cd "$(dirname "$0")/.." && pwd)
n=${GL_DIRECTIONS:-1024}
r=${GL_RESOLUTION:-512}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for case in "furnace.json vertices" "furnace.json texels:64" "cornell.json texels:64" \
            "sphere_sun.json texels:128"; do
    set -- $case
    "$bin" bake "$here/scenes/$1" --target "$2" --quantities ao,transfer --no-cache \
        --engine gl --gl-directions "$n" --gl-resolution "$r" --out "$out/gl" 2>/dev/null
    "$bin" bake "$here/scenes/$1" --target "$2" --quantities ao,transfer --no-cache \
        --rays "$n" --out "$out/embree" 2>/dev/null
    python3 - "$out/gl/bake.json" "$out/embree/bake.json" "$1 $2" <<'PY'
import json, sys
g, e = (json.load(open(p)) for p in sys.argv[1:3])
tg, te = g["seconds"]["bake"], e["seconds"]["bake"]
print(f"{sys.argv[3]:28s} {g['points']:7d} points  gl {tg:7.2f} s  embree {te:7.2f} s  "
      f"gl/embree {tg / te:6.2f}  ({g['engine']['directions']} directions, "
      f"{g['engine']['resolution']}^2, {g['engine']['renderer']})")
PY
done
