# `sphbasis bake --target-error / --max-rays` (adaptive sampling) and the seam stitching of texel
# bakes. Included by tests/CMakeLists.txt after bake_tests.cmake (its helpers and variables).

# Sharded adaptive bakes merge bit for bit into one run's files; bake.json reports the rays.
sphbasis_bake_test(adaptive_shard_merge "adaptive-ok"
  "rm -rf bake_a1 bake_ah bake_am && \"${_bake}\" bake ${_scenes}/sphere_over_quad.json --quantities ao,bent --rays 32 --target-error ao:0.02 --max-rays 1024 --seed 5 --out bake_a1 && printf '0/2\\n1/2\\n' | xargs -P 2 -I{} \"${_bake}\" bake ${_scenes}/sphere_over_quad.json --quantities ao,bent --rays 32 --target-error ao:0.02 --max-rays 1024 --seed 5 --out bake_ah --shard {} && \"${_bake}\" bake-merge bake_ah/bake.shard-1-of-2.bin bake_ah/bake.shard-0-of-2.bin --out bake_am && cmp bake_a1/ground.ply bake_am/ground.ply && cmp bake_a1/ball.ply bake_am/ball.ply && grep -q '\"rays_saved\"' bake_a1/bake.json && grep -q '\"unconverged_points\": *0' bake_am/bake.json && echo adaptive-ok")
# A texel bake stitches the sphere's seam: bake.json reports the jumps.
sphbasis_bake_test(texels_seams "seams-ok"
  "rm -rf bake_sm2 && \"${_bake}\" bake ${_scenes}/sphere_over_quad.json --target texels:32 --quantities ao --rays 64 --out bake_sm2 && grep -q '\"max_jump_after\"' bake_sm2/bake.json && echo seams-ok")
sphbasis_bake_bad(target_error_quantity "--target-error: 'irradiance' is not one of the --quantities \\(ao\\)"
                  bake ${_scenes}/lone_sphere.json --target-error irradiance:0.1)
sphbasis_bake_bad(target_error_zero "--target-error: expected errors > 0, got '0'"
                  bake ${_scenes}/lone_sphere.json --target-error 0)
sphbasis_bake_bad(target_error_empty "--target-error: expected errors > 0, got ''"
                  bake ${_scenes}/lone_sphere.json --target-error '')
sphbasis_bake_bad(max_rays_alone "--max-rays needs --target-error"
                  bake ${_scenes}/lone_sphere.json --max-rays 512)
sphbasis_bake_bad(max_rays_below_rays "--max-rays: expected at least --rays \\(256\\), got 128"
                  bake ${_scenes}/lone_sphere.json --target-error 0.01 --max-rays 128)
