# Tests of `sphbasis bake --engine gl` (Hill's depth-map bake, tools/gl/gl_bake.hpp). Included by
# tests/CMakeLists.txt after bake_tests.cmake. Label "cli": refused combinations (checked before
# any GL call, so they pass with or without a driver). Label "bake": runs on the driver (Mesa's
# llvmpipe in CI), skipped when no headless OpenGL 4.3 context can be created or the build has
# no EGL.
set(_check_gl ${CMAKE_CURRENT_SOURCE_DIR}/cli/check_gl_bake.py)
set(_gl_scene ${CMAKE_CURRENT_SOURCE_DIR}/data/scenes/sphere_over_small_quad.json)

sphbasis_cli_test(bake_gl_help "--engine embree\\|gl.*--gl-directions N.*--gl-resolution R" bake --help)
sphbasis_bake_bad(gl_irradiance "--engine gl: bakes the quantities ao, transfer and visibility only, got 'irradiance' \\(use --engine embree\\)"
                  bake ${_gl_scene} --engine gl --quantities ao,irradiance)
sphbasis_bake_bad(gl_bounces "--engine gl: bakes transfer without bounces \\(--bounces 0\\), got --bounces 2"
                  bake ${_gl_scene} --engine gl --quantities transfer --bounces 2)
sphbasis_bake_bad(gl_target_error "--engine gl: samples a fixed direction set: no --target-error or --max-rays"
                  bake ${_gl_scene} --engine gl --target-error 0.01)
sphbasis_bake_bad(gl_rays "--engine gl: samples --gl-directions directions, not --rays"
                  bake ${_gl_scene} --engine gl --rays 64)
# Given is given: --rays at its default value (256) is refused too.
sphbasis_bake_bad(gl_rays_default "--engine gl: samples --gl-directions directions, not --rays"
                  bake ${_gl_scene} --engine gl --rays 256)
sphbasis_bake_bad(gl_max_distance "--engine gl: a depth map holds the nearest surface to the sky only: no --max-distance"
                  bake ${_gl_scene} --engine gl --max-distance 1)
sphbasis_bake_bad(gl_shard "--engine gl: bakes in one run: no --shard" bake ${_gl_scene} --engine gl --shard 0/2)
sphbasis_bake_bad(gl_probes "--engine gl: bakes the quantities ao, transfer and visibility only, got 'radiance'"
                  bake ${_gl_scene} --engine gl --target probes --quantities radiance)
sphbasis_bake_bad(gl_high_to_low "--engine gl: does not bake high to low" bake ${PROJECT_SOURCE_DIR}/scenes/high_to_low.json --engine gl)
sphbasis_bake_bad(gl_options_without_engine "--gl-directions, --gl-resolution: only with --engine gl"
                  bake ${_gl_scene} --gl-directions 64)
sphbasis_bake_bad(gl_unknown_engine "--engine: expected embree or gl, got 'vulkan'" bake ${_gl_scene} --engine vulkan)
sphbasis_bake_bad(gl_directions_zero "--gl-directions: expected 1 <= N <= 1048576" bake ${_gl_scene} --engine gl --gl-directions 0)

# Points on the plane under the sphere: ao against its closed form and against Embree (4096
# rays), transfer against Embree, within 0.02: the maps' texel w = 2R/512 = 0.029 (R = 7.35, the
# scene's bounding sphere) moves the sphere's silhouette by at most w/sqrt(2) at distance >= 2,
# 0.01 rad, so sin^2 alpha by at most 0.01; the 1024 directions add about 0.005, Embree's QMC
# error 0.004. Measured: 0.0073.
set(_gl_points "0 0 0 0 0 1\\n0.5 0 0 0 0 2\\n1 1 0 0 0 1\\n-2 0.5 0 0 0 1\\n4 0 0 0 0 1\\n")
sphbasis_bake_test(gl_points "gl-points-ok 5"
  "printf '${_gl_points}' | \"${_bake}\" bake ${_gl_scene} --points - --quantities ao,transfer --engine gl > bake_gl_points.txt && printf '${_gl_points}' | \"${_bake}\" bake ${_gl_scene} --points - --quantities ao,transfer --rays 4096 > bake_gl_points_embree.txt && python3 ${_check_gl} points bake_gl_points.txt bake_gl_points_embree.txt 2 1 0.02")
# Vertex and texel bakes write the Embree bake's files and channels; bake.json records the engine.
sphbasis_bake_test(gl_files "gl-layout-ok 2.*gl-layout-ok 2"
  "rm -rf bake_gl_f && \"${_bake}\" bake ${_gl_scene} --engine gl --quantities ao,transfer --gl-directions 64 --gl-resolution 128 --out bake_gl_f/v && \"${_bake}\" bake ${_gl_scene} --quantities ao,transfer --rays 8 --out bake_gl_f/ve && python3 ${_check_gl} layout bake_gl_f/v/bake.json bake_gl_f/ve/bake.json && \"${_bake}\" bake ${_gl_scene} --engine gl --target texels:16 --quantities ao,visibility --gl-directions 64 --gl-resolution 128 --out bake_gl_f/t && \"${_bake}\" bake ${_gl_scene} --target texels:16 --quantities ao,visibility --rays 8 --out bake_gl_f/te && python3 ${_check_gl} layout bake_gl_f/t/bake.json bake_gl_f/te/bake.json")
set_tests_properties(bake_gl_points bake_gl_files PROPERTIES
                     SKIP_REGULAR_EXPRESSION "no OpenGL 4.3 context|built without EGL")
