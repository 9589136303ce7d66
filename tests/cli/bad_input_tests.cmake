# Bad input to the scene loader and the command line: each case exits non-zero with one line
# naming the file and the place (label "cli"; nothing is traced), never a signal, a hang, a
# non-finite result at exit 0 or a bare std::bad_alloc. Included by tests/CMakeLists.txt after
# the other CLI tests (it uses their scenes and sphbasis_cli_bad).
set(_bi_cli $<TARGET_FILE:sphbasis_cli>)
set(_bi_scenes ${CMAKE_CURRENT_SOURCE_DIR}/data/scenes)
set(_bi_bad ${CMAKE_CURRENT_SOURCE_DIR}/data/scenes/bad)
set(_bi_render ${CMAKE_CURRENT_SOURCE_DIR}/data/scenes/render)

# As sphbasis_cli_bad, with `setup` (shell commands, e.g. creating a FIFO) run first and `env`
# (assignments such as SPHBASIS_MAX_MEMORY=1G, or "") before the command; a 60 s timeout turns
# a hang into a failure.
function(sphbasis_cli_bad_env name what setup env)
  string(JOIN " " _args ${ARGN})
  add_test(NAME cli_${name}
           COMMAND sh -c "${setup} err=$(${env} timeout 60 \"${_bi_cli}\" ${_args} 2>&1 >/dev/null); rc=$?; n=$(printf '%s\\n' \"$err\" | wc -l); if [ $rc -ne 0 ] && [ $rc -ne 124 ] && [ $rc -lt 128 ] && [ $n -eq 1 ]; then echo \"bad-input-ok: $err\"; else echo \"rc=$rc lines=$n: $err\"; fi")
  set_tests_properties(cli_${name} PROPERTIES PASS_REGULAR_EXPRESSION "bad-input-ok: sphbasis ${what}"
                       LABELS cli)
endfunction()

# --- Bounds on coordinates and light values (Embree aborted on finite coordinates near 2e18;
# an environment scale of 1e39 wrote inf into the outputs).
sphbasis_cli_bad(bad_huge_coordinate "bake: [^ ]*huge_coordinate.json: meshes\\[0\\].center\\[0\\]: expected a coordinate in \\[-1e15, 1e15\\], got 2e\\+18\n"
                 bake ${_bi_bad}/huge_coordinate.json)
sphbasis_cli_bad(bad_huge_transform "bake: [^ ]*huge_transform.json: meshes\\[0\\]: position [0-9]+ at vertex [0-9]+ outside \\[-1e15, 1e15\\] \\(after the transform\\)\n"
                 bake ${_bi_bad}/huge_transform.json)
sphbasis_cli_bad(bad_huge_env_scale "bake: [^ ]*huge_env_scale.json: environment.scale: expected a number in \\[0, 1e15\\], got [.0-9]+e\\+3[89]\n"
                 bake ${_bi_bad}/huge_env_scale.json)
sphbasis_cli_bad(bad_huge_radiance "bake: [^ ]*huge_radiance.json: environment.scale: expected scale x the largest radiance at most 1e15, got 10000000000 x 10000000000\n"
                 bake ${_bi_bad}/huge_radiance.json)
sphbasis_cli_bad(bad_huge_light "bake: [^ ]*huge_light.json: lights\\[0\\].color\\[0\\]: expected a value in \\[0, 1000000000000000\\], got 1e\\+20\n"
                 bake ${_bi_bad}/huge_light.json)
sphbasis_cli_bad(bad_camera_far "render: [^ ]*camera_far.json: camera.position\\[0\\]: expected a coordinate in \\[-1e15, 1e15\\], got 1[.0-9]*e\\+300\n"
                 render ${_bi_render}/camera_far.json)

# --- Wrong or internal messages.
sphbasis_cli_bad(bad_unknown_shape "bake: [^ ]*unknown_shape.json: meshes\\[0\\].shape: unknown shape 'torus' \\(expected sphere, box or quad\\)\n"
                 bake ${_bi_bad}/unknown_shape.json)
sphbasis_cli_bad(bad_duplicate_name "bake: [^ ]*duplicate_name.json: meshes\\[1\\]: duplicate mesh name 'a'\n"
                 bake ${_bi_bad}/duplicate_name.json)
sphbasis_cli_bad(bad_scene_directory "bake: [^ ]*scenes/bad: a directory, not a scene file\n"
                 bake ${_bi_bad})
sphbasis_cli_bad(bad_mesh_directory "bake: [^ ]*mesh_directory.json: meshes\\[0\\].file: '[^']*' is a directory, not a file\n"
                 bake ${_bi_bad}/mesh_directory.json)
sphbasis_cli_bad(bad_nul_file_name "bake: [^ ]*nul_file_name.json: meshes\\[0\\].file: expected a file name without NUL bytes, got '../quad_uv.obj.x00.png'\n"
                 bake ${_bi_bad}/nul_file_name.json)
sphbasis_cli_bad(bad_nan_normal "bake: [^ ]*nan_normal.json: meshes\\[0\\]: non-finite normal at vertex [0-9]+ of '[^']*nan_normal.ply'\n"
                 bake ${_bi_bad}/nan_normal.json)
sphbasis_cli_bad(bad_probes_quantities "bake: --target probes: probes bake only radiance"
                 bake ${_bi_scenes}/lone_sphere.json --target probes)
# A FIFO as the scene, as a mesh and as a texture: refused at once (opening one blocks).
sphbasis_cli_bad_env(bad_scene_fifo "bake: [^ ]*bi_scene.fifo: not a regular file"
                     "rm -f bi_scene.fifo && mkfifo bi_scene.fifo &&" "" bake bi_scene.fifo)
sphbasis_cli_bad_env(bad_mesh_fifo "bake: [^ ]*bi_mesh.json: meshes\\[0\\].file: '[^']*bi_mesh.fifo' is not a regular file"
                     "rm -f bi_mesh.fifo && mkfifo bi_mesh.fifo && echo '{\"meshes\": [{\"file\": \"bi_mesh.fifo\"}]}' > bi_mesh.json &&"
                     "" bake bi_mesh.json)
sphbasis_cli_bad_env(bad_texture_fifo "bake: [^ ]*bi_tex.json: meshes\\[0\\].albedo_map: '[^']*bi_tex.fifo' is not a regular file"
                     "rm -f bi_tex.fifo && mkfifo bi_tex.fifo && echo '{\"meshes\": [{\"shape\": \"quad\", \"albedo_map\": \"bi_tex.fifo\"}]}' > bi_tex.json &&"
                     "" bake bi_tex.json)

# --- Stated maxima that do not fit in memory are refused before allocating (the limit set to
# 1 GiB so that the outcome does not depend on the machine).
sphbasis_cli_bad_env(bad_max_sphere "bake: [^ ]*max_sphere.json: meshes\\[0\\]: needs [0-9.]+ GiB \\(a sphere of 4096 rings x 8192 segments\\); at most 1.0 GiB allowed \\(SPHBASIS_MAX_MEMORY\\)\n"
                     "" "SPHBASIS_MAX_MEMORY=1G" bake ${_bi_bad}/max_sphere.json)
sphbasis_cli_bad_env(bad_max_quad "bake: [^ ]*max_quad.json: meshes\\[0\\]: needs [0-9.]+ GiB \\(a quad of 8192 x 8192 subdivisions\\); at most 1.0 GiB allowed"
                     "" "SPHBASIS_MAX_MEMORY=1G" bake ${_bi_bad}/max_quad.json)
sphbasis_cli_bad_env(bad_max_probes "bake: [^ ]*max_probes.json: needs [0-9.]+ [GT]iB \\(baking 67108864 probes at [0-9.]+ [Kb].*\\); at most 1.0 GiB allowed"
                     "" "SPHBASIS_MAX_MEMORY=1G" bake ${_bi_bad}/max_probes.json --target probes --quantities radiance)
sphbasis_cli_bad_env(bad_max_texels "bake: [^ ]*lone_sphere.json: needs [0-9.]+ GiB \\(baking 268435456 texels at .*\\); at most 1.0 GiB allowed"
                     "" "SPHBASIS_MAX_MEMORY=1G" bake ${_bi_scenes}/lone_sphere.json --target texels:16384)
sphbasis_cli_bad_env(bad_max_camera "render: [^ ]*tiny_sun.json: needs [0-9.]+ [GT]iB \\(16384 x 16384 pixels, .*\\); at most 1.0 GiB allowed"
                     "" "SPHBASIS_MAX_MEMORY=1G" render ${_bi_render}/tiny_sun.json --width 16384 --height 16384)
sphbasis_cli_bad_env(bad_max_lightmap "render: [^ ]*tiny_sun.json: needs [0-9.]+ [GT]iB \\(32 x 24 pixels, 134217728 lightmap texels, 0 probes\\); at most 1.0 GiB allowed"
                     "" "SPHBASIS_MAX_MEMORY=1G" render ${_bi_render}/tiny_sun.json --lightmap-size 8192)
sphbasis_cli_bad(bad_huge_ply_header "bake: [^ ]*huge_ply.json: meshes\\[0\\].file: '[^']*huge_header.ply': the PLY header declares 2147483648 vertices and 1 faces, more than the file's [0-9]+ bytes can hold\n"
                 bake ${_bi_bad}/huge_ply.json)
sphbasis_cli_bad_env(bad_memory_variable "bake: SPHBASIS_MAX_MEMORY: expected a positive number of bytes"
                     "" "SPHBASIS_MAX_MEMORY=lots" bake ${_bi_scenes}/lone_sphere.json)

# --- Option ranges equal to the library's, checked before the scene is read.
sphbasis_cli_bad(bad_bake_bands "bake: --bands: expected 1 <= N <= 16, got 17\n"
                 bake ${_bi_scenes}/lone_sphere.json --bands 17)
sphbasis_cli_bad(bad_render_prt_bands "render: --prt-bands: expected 1 <= B <= 8, got 9\n"
                 render ${_bi_render}/tiny_sun.json --prt-bands 9)
# Standard error needs two samples: --spp 1 wrote an all-NaN reference_stderr.exr.
sphbasis_cli_bad(bad_render_spp_one "render: --spp: expected 2 <= N <= 1048576, got 1\n"
                 render ${_bi_render}/tiny_sun.json --spp 1)
sphbasis_cli_bad(bad_render_max_spp_one "render: --max-spp: expected 2 <= N <= 1048576, got 1\n"
                 render ${_bi_render}/tiny_sun.json --max-spp 1)
sphbasis_cli_bad(bad_scene_spp_one "render: [^ ]*spp_one.json: render.spp: expected an integer in \\[2, 1048576\\], got 1\n"
                 render ${_bi_render}/spp_one.json)
# The families of docs/rendering.md are accepted (the error is the next option's) ...
sphbasis_cli_bad(render_family_names "render: --noise: expected a relative noise in \\(0, 1\\), got 1.5\n"
                 render ${_bi_render}/tiny_sun.json --representations lxh-pca36,prt-cpca-7-3,lxh-pca1 --noise 1.5)
# ... and their bounds are not.
sphbasis_cli_bad(bad_render_family_bound "render: --representations: unknown representation 'lxh-pca37'"
                 render ${_bi_render}/tiny_sun.json --representations lxh-pca37)
sphbasis_cli_bad(bad_render_cpca_bound "render: --representations: unknown representation 'prt-cpca-4097-2'"
                 render ${_bi_render}/tiny_sun.json --representations prt-cpca-4097-2)
# Integers beyond long long name the range, not "expected an integer".
sphbasis_cli_bad(bad_eval_coeffs_huge "eval: --coeffs: expected -9223372036854775808 <= N <= 9223372036854775807, got 9223372036854775808\n"
                 eval --basis sh --coeffs 9223372036854775808 --dir 0,0,1)
sphbasis_cli_bad(bad_rotate_bands_huge "rotate: --bands: expected 1 <= N <= [0-9]+, got 18446744073709551617\n"
                 rotate --bands 18446744073709551617 --quat 1,0,0,0 --coeffs 1)
sphbasis_cli_bad(bad_bake_seed_huge "bake: --seed: expected a non-negative integer at most 9223372036854775807, got 99999999999999999999\n"
                 bake ${_bi_scenes}/lone_sphere.json --seed 99999999999999999999)
# Reals: a subnormal is a number (accepted below); one that rounds to zero says so.
sphbasis_cli_bad(bad_eval_underflow "eval: --dir: expected a number that does not round to zero"
                 eval --basis sh --coeffs 1 --dir 1e-400,0,1)
sphbasis_cli_test(eval_subnormal_dir "\"values\":\\[0.28209479177387814,0,0,0.48860251190291992\\]"
                  eval --basis sh --coeffs 4 --dir 1e-320,0,0)
# A tiny finite quaternion is normalised (scaled first): 90 degrees about z, as the help's
# example with (0.70710678118654752, 0, 0, 0.70710678118654752).
sphbasis_cli_test(rotate_tiny_quaternion "\"coeffs\":\\[1,1,(-?[0-9.e-]+),(-?[0-9.e-]+)\\]"
                  rotate --bands 2 --quat 1e-310,0,0,1e-310 --coeffs 1,0,0,1)

# --- Long input is abbreviated: a 5 MB unknown key (before: a 5 MB line after 12-20 s and
# 608 MB) and a long option value give short lines (the key shown in 40 characters, then the
# allowed keys).
sphbasis_cli_script(bad_long_key "long-key-ok [0-9]+ chars"
  "python3 -c \"import json; json.dump({'meshes': [{'shape': 'quad', 'k' * 5000000: 1}]}, open('bi_long_key.json', 'w'))\" && err=$(timeout 60 \"${_bi_cli}\" bake bi_long_key.json 2>&1 >/dev/null); rc=$?; n=$(printf '%s' \"$err\" | wc -c); if [ $rc -eq 1 ] && [ $n -le 200 ] && printf '%s' \"$err\" | grep -q \"meshes\\[0\\]: unknown key 'kkkk.*(5000000 bytes)\"; then echo \"long-key-ok $n chars: $err\"; else echo \"rc=$rc $n chars\"; fi")
sphbasis_cli_script(bad_long_option "long-option-ok [0-9]+ chars"
  "err=$(\"${_bi_cli}\" bake ${_bi_scenes}/lone_sphere.json --target $(python3 -c \"print('x' * 100000)\") 2>&1 >/dev/null); rc=$?; n=$(printf '%s' \"$err\" | wc -c); if [ $rc -eq 2 ] && [ $n -le 200 ]; then echo \"long-option-ok $n chars: $err\"; else echo \"rc=$rc $n chars\"; fi")

# --- The loader is linear in the scene's size: 80,000 meshes, the last one wrong, reported in
# at most 2 s of CPU time (before: more than 60 s; 20,000 took 2.1 s and 40,000 10.5 s).
sphbasis_cli_script(loader_80000_meshes "loader-time-ok"
  "python3 ${CMAKE_CURRENT_SOURCE_DIR}/cli/time_loader.py \"${_bi_cli}\" 80000 2.0")

# --- bake-merge: a shard whose header lost a key (or has one of the wrong type), with a valid
# checksum (cli/edit_shard.py recomputes it), is one line naming the file, not nlohmann's
# exception text (label bake: it bakes the shard first).
set(_bi_edit_shard ${CMAKE_CURRENT_SOURCE_DIR}/cli/edit_shard.py)
sphbasis_script_test(bake bad_merge_header_key "bad-input-ok: sphbasis bake-merge: [^ ]*bi_merge/bake.shard-0-of-2.bin: corrupt shard header \\(key 'rays' not found\\)\n"
  "rm -rf bi_merge && \"${_bi_cli}\" bake ${_bi_scenes}/lone_sphere.json --rays 4 --shard 0/2 --out bi_merge 2>/dev/null && python3 ${_bi_edit_shard} bi_merge/bake.shard-0-of-2.bin rays DELETE && err=$(\"${_bi_cli}\" bake-merge bi_merge/bake.shard-0-of-2.bin 2>&1 >/dev/null); rc=$?; n=$(printf '%s\\n' \"$err\" | wc -l); if [ $rc -eq 1 ] && [ $n -eq 1 ]; then echo \"bad-input-ok: $err\"; else echo \"rc=$rc lines=$n: $err\"; fi")
sphbasis_script_test(bake bad_merge_header_type "bad-input-ok: sphbasis bake-merge: [^ ]*bi_merge2/bake.shard-0-of-2.bin: corrupt shard header \\(type must be number, but is null\\)\n"
  "rm -rf bi_merge2 && \"${_bi_cli}\" bake ${_bi_scenes}/lone_sphere.json --rays 4 --shard 0/2 --out bi_merge2 2>/dev/null && python3 ${_bi_edit_shard} bi_merge2/bake.shard-0-of-2.bin points null && err=$(\"${_bi_cli}\" bake-merge bi_merge2/bake.shard-0-of-2.bin 2>&1 >/dev/null); rc=$?; n=$(printf '%s\\n' \"$err\" | wc -l); if [ $rc -eq 1 ] && [ $n -eq 1 ]; then echo \"bad-input-ok: $err\"; else echo \"rc=$rc lines=$n: $err\"; fi")
# A mesh name longer than a file name can be.
sphbasis_cli_bad_env(bad_long_mesh_name "bake: [^ ]*bi_name.json: meshes\\[0\\].name: expected at most 200 characters \\(it names output files\\), got 'nnnnn[n]*... \\(300 bytes\\)'\n"
                     "python3 -c \"import json; json.dump({'meshes': [{'shape': 'quad', 'name': 'n' * 300}]}, open('bi_name.json', 'w'))\" &&"
                     "" bake bi_name.json)
sphbasis_cli_bad(bad_huge_matrix "bake: [^ ]*huge_matrix.json: meshes\\[0\\].transform: expected a transform with entries in \\[-1e15, 1e15\\]"
                 bake ${_bi_bad}/huge_matrix.json)

# --- Bake points from standard input: a coordinate beyond 1e15 (before: SIGABRT in Embree), a
# free point with a surface quantity (before: render::Baker::bake()'s message), and a tiny or
# huge normal, which is a direction like any other (before: "expected a non-zero finite normal").
sphbasis_cli_script(bad_point_far "bad-input-ok: sphbasis bake: standard input line 2: expected coordinates in \\[-1e15, 1e15\\], got '2e18'\n"
  "err=$(printf '0 0 0 0 0 1\\n2e18 0 0 0 0 1\\n' | \"${_bi_cli}\" bake ${_bi_scenes}/lone_sphere.json --points - 2>&1 >/dev/null); rc=$?; n=$(printf '%s\\n' \"$err\" | wc -l); if [ $rc -eq 2 ] && [ $n -eq 1 ]; then echo \"bad-input-ok: $err\"; else echo \"rc=$rc lines=$n: $err\"; fi")
sphbasis_cli_script(bad_point_free "bad-input-ok: sphbasis bake: standard input: point 1 is 'x y z' \\(no normal\\): ao, bent, visibility, transfer and irradiance need 'x y z nx ny nz'; free points bake radiance\n"
  "err=$(printf '0 0 5\\n' | \"${_bi_cli}\" bake ${_bi_scenes}/lone_sphere.json --points - 2>&1 >/dev/null); rc=$?; n=$(printf '%s\\n' \"$err\" | wc -l); if [ $rc -eq 2 ] && [ $n -eq 1 ]; then echo \"bad-input-ok: $err\"; else echo \"rc=$rc lines=$n: $err\"; fi")
# Points whose hemisphere misses the unit sphere (at (5, 0, 0) facing away from it, at (0, 0, 5)
# facing up): ao = 1 exactly.
sphbasis_cli_script(point_tiny_normal "\"n\":\\[[0-9.]+e-32[01],0,[0-9.]+e-32[01]\\],\"ao\":1,.*\n.*\"n\":\\[0,0,1[.0-9]*e\\+300\\],\"ao\":1,"
  "printf '5 0 0 1e-320 0 1e-320\\n0 0 5 0 0 1e300\\n' | \"${_bi_cli}\" bake ${_bi_scenes}/lone_sphere.json --points - --rays 16")
