# Tests of `sphbasis bake` and `sphbasis bake-merge`. Included by tests/CMakeLists.txt after
# cli_tests.cmake. Label "cli": options, help and bad scene files (rejected before any ray is
# traced). Label "bake": runs that trace rays with render::Baker (ctest -L bake).
set(_bake $<TARGET_FILE:sphbasis_cli>)
set(_scenes ${CMAKE_CURRENT_SOURCE_DIR}/data/scenes)
set(_check_points ${CMAKE_CURRENT_SOURCE_DIR}/cli/check_bake_points.py)

# Passes when the command exits non-zero with exactly one line on stderr matching regex (and
# nothing on stdout).
function(sphbasis_bake_bad name regex)
  sphbasis_cli_bad(bake_bad_${name} "bake[-a-z]*: ${regex}" ${ARGN})
endfunction()
function(sphbasis_bake_test name regex script)
  sphbasis_script_test(bake ${name} "${regex}" "${script}")
endfunction()

# Help.
sphbasis_cli_test(bake_help "Usage: sphbasis bake.*SCENE.json.*--quantities.*--bands N.*--basis NAME.*--coeffs N.*--rays N.*--bounces B.*--seed S.*--max-distance D.*--target.*--points FILE\\|-.*--out DIR.*--shard I/N"
                  bake --help)
sphbasis_cli_test(bake_merge_help "Usage: sphbasis bake-merge.*SHARD.bin.*--out DIR" bake-merge --help)
sphbasis_cli_test(help_lists_bake "Subcommands:.*bake.*bake-merge" --help)

# Bad scene files: one line naming the file and the place, non-zero exit.
sphbasis_bake_bad(missing_scene "[^ ]*no_such_scene.json: cannot open the scene file"
                  bake ${_scenes}/no_such_scene.json)
sphbasis_bake_bad(malformed "[^ ]*malformed.json: malformed JSON: parse error at line 1"
                  bake ${_scenes}/bad/malformed.json)
sphbasis_bake_bad(unknown_key "[^ ]*unknown_key.json: meshes\\[0\\]: unknown key 'albdo' \\(did you mean 'albedo'\\?\\)"
                  bake ${_scenes}/bad/unknown_key.json)
sphbasis_bake_bad(unknown_top_key "[^ ]*unknown_top.json: unknown key 'light' \\(did you mean 'lights'\\?\\)"
                  bake ${_scenes}/bad/unknown_top.json)
sphbasis_bake_bad(nan_transform "[^ ]*nan_transform.json: malformed JSON: .*NaN and Infinity are not JSON numbers"
                  bake ${_scenes}/bad/nan_transform.json)
sphbasis_bake_bad(inf_transform "[^ ]*inf_transform.json: expected finite numbers"
                  bake ${_scenes}/bad/inf_transform.json)
sphbasis_bake_bad(overflow_transform "[^ ]*overflow_transform.json: meshes\\[0\\].transform: expected a transform with entries in \\[-1e15, 1e15\\]"
                  bake ${_scenes}/bad/overflow_transform.json)
sphbasis_bake_bad(singular_transform "[^ ]*singular_transform.json: meshes\\[0\\].transform: singular or non-finite transform"
                  bake ${_scenes}/bad/singular_transform.json)
sphbasis_bake_bad(bad_length "[^ ]*bad_length.json: meshes\\[0\\].albedo: expected an array of 3 numbers, got an array of 2"
                  bake ${_scenes}/bad/bad_length.json)
sphbasis_bake_bad(bad_color "[^ ]*bad_color.json: environment.constant\\[1\\]: expected a value in"
                  bake ${_scenes}/bad/bad_color.json)
sphbasis_bake_bad(bad_light "[^ ]*bad_light.json: lights\\[0\\].type: unknown light type 'spot'"
                  bake ${_scenes}/bad/bad_light.json)
sphbasis_bake_bad(missing_mesh "[^ ]*missing_mesh.json: meshes\\[0\\].file: cannot open mesh file"
                  bake ${_scenes}/bad/missing_mesh.json)
sphbasis_bake_bad(empty_mesh "[^ ]*empty_mesh.json: meshes\\[0\\]: empty mesh"
                  bake ${_scenes}/bad/empty_mesh.json)
sphbasis_bake_bad(texels_without_uvs "[^ ]*no_uvs.json: meshes\\[0\\] \\('mesh0'\\): a texel bake needs a UV set"
                  bake ${_scenes}/no_uvs.json --target texels:16)
sphbasis_bake_bad(probes_without_grid "[^ ]*sphere_over_quad.json: --target probes needs a \"probes\" grid"
                  bake ${_scenes}/sphere_over_quad.json --target probes --quantities radiance)
# Bad options.
sphbasis_bake_bad(shard_out_of_range "--shard: expected I/N with 0 <= I < N" bake ${_scenes}/lone_sphere.json --shard 2/2)
sphbasis_bake_bad(shard_malformed "--shard: expected I/N" bake ${_scenes}/lone_sphere.json --shard a/b)
sphbasis_bake_bad(shard_zero "--shard: expected I/N" bake ${_scenes}/lone_sphere.json --shard 0/0)
sphbasis_bake_bad(shard_empty "--shard: expected I/N with 0 <= I < N <= 1000000, got ''" bake ${_scenes}/lone_sphere.json --shard '')
sphbasis_bake_bad(target_unknown "--target: expected vertices, texels:RES or probes, got 'faces'" bake ${_scenes}/lone_sphere.json --target faces)
sphbasis_bake_bad(target_texels_zero "--target: expected texels:RES with 1 <= RES <= 16384" bake ${_scenes}/lone_sphere.json --target texels:0)
sphbasis_bake_bad(quantity_unknown "--quantities: unknown quantity 'bnet' \\(did you mean 'bent'\\?\\)" bake ${_scenes}/lone_sphere.json --quantities ao,bnet)
sphbasis_bake_bad(basis_unknown "--basis: " bake ${_scenes}/lone_sphere.json --basis nope)
sphbasis_bake_bad(coeffs_invalid "--coeffs: basis 'hbasis' expects" bake ${_scenes}/lone_sphere.json --basis hbasis --coeffs 5)
sphbasis_bake_bad(coeffs_invalid_sg "--coeffs: basis 'sg' expects 5, 6, 9 or 12 functions, got 7" bake ${_scenes}/lone_sphere.json --basis sg --coeffs 7)
sphbasis_bake_bad(target_and_points "give either --target or --points" bake ${_scenes}/lone_sphere.json --target vertices --points -)
sphbasis_bake_bad(max_distance "--max-distance: expected a positive distance" bake ${_scenes}/lone_sphere.json --max-distance 0)
add_test(NAME cli_bake_bad_points_line
         COMMAND sh -c "printf '0 0\\n' | \"${_bake}\" bake ${_scenes}/lone_sphere.json --points -")
set_tests_properties(cli_bake_bad_points_line PROPERTIES WILL_FAIL TRUE LABELS cli)
sphbasis_bake_bad(merge_not_a_shard "[^ ]*lone_sphere.json: not a shard file" bake-merge ${_scenes}/lone_sphere.json)

# --- Tests that trace rays (label "bake") ----------------------------------------------------

# A sphere (r = 1, centre height 2) over a plane: ao and the bent normal at points on the plane
# against their closed forms (check_bake_points.py documents them).
sphbasis_bake_test(points_closed_form "points-closed-form-ok 5"
  "printf '0 0 0 0 0 1\\n0.5 0 0 0 0 2\\n1 1 0 0 0 1\\n-2 0.5 0 0 0 1\\n4 0 0 0 0 1\\n' | \"${_bake}\" bake ${_scenes}/sphere_over_quad.json --points - --quantities ao,bent --rays 4096 --seed 3 | python3 ${_check_points} 2 1")
# The output line format: exactly these keys in this order (each quantity followed by its
# standard error), "n" echoed as given (only for a surface point), 17 significant digits.
sphbasis_bake_test(points_format "\\{\"p\":\\[0.5,0,0\\],\"n\":\\[0,0,2\\],\"ao\":.*\n\\{\"p\":\\[1,0,0\\],\"n\":\\[0,0,1\\],\"ao\":.*points-format-ok 2"
  "printf '0.5 0 0 0 0 2\\n1 0 0 0 0 1\\n' | \"${_bake}\" bake ${_scenes}/sphere_over_quad.json --points - --quantities ao,bent,visibility,transfer --bands 3 --rays 64 | tee bake_points_format.txt && python3 ${_check_points} format 3 < bake_points_format.txt")
# A free point (x y z): no "n"; radiance as three lists (R, G, B), its standard error (one list)
# and the inside flag.
sphbasis_bake_test(points_free "\\{\"p\":\\[0,0,5\\],\"radiance\":\\[\\[[-0-9.e,]*\\],\\[[-0-9.e,]*\\],\\[[-0-9.e,]*\\]\\],\"radiance_stderr\":\\[[-0-9.e]+,[-0-9.e]+,[-0-9.e]+,[-0-9.e]+\\],\"inside\":false\\}"
  "printf '0 0 5\\n' | \"${_bake}\" bake ${_scenes}/sphere_over_quad.json --points - --quantities radiance --bands 2 --rays 64")
# Spherical Gaussians (BakingLab's 9 lobes): the irradiance fitted in their span, 9 numbers a channel.
sphbasis_bake_test(points_sg9 "\"irradiance\":\\[\\[[0-9.e-]+,[0-9.e-]+,[0-9.e-]+,[0-9.e-]+,[0-9.e-]+,[0-9.e-]+,[0-9.e-]+,[0-9.e-]+,[0-9.e-]+\\]"
  "printf '0.5 0 0 0 0 1\\n' | \"${_bake}\" bake ${_scenes}/sphere_over_quad.json --points - --quantities irradiance --basis sg --coeffs 9 --rays 64")
# The engine names: sg9 with NNLS (9 amplitudes, none negative), ZH3 (5 values a channel), the
# non-linear L1 per texel (4 channels a colour; bake.json says what they hold); bad combinations.
sphbasis_bake_test(points_sg9_nnls "\"irradiance\":\\[\\[[0-9][0-9.e-]*,[0-9][0-9.e-]*,[0-9][0-9.e-]*,[0-9][0-9.e-]*,[0-9][0-9.e-]*,[0-9][0-9.e-]*,[0-9][0-9.e-]*,[0-9][0-9.e-]*,[0-9][0-9.e-]*\\]"
  "printf '0.5 0 0 0 0 1\\n' | \"${_bake}\" bake ${_scenes}/sphere_over_quad.json --points - --quantities irradiance --basis sg9 --sg-solver nnls --rays 64")
sphbasis_bake_test(points_zh3 "\"irradiance\":\\[\\[[-0-9.e]+,[-0-9.e]+,[-0-9.e]+,[-0-9.e]+,[-0-9.e]+\\]"
  "printf '0.5 0 0 0 0 1\\n' | \"${_bake}\" bake ${_scenes}/sphere_over_quad.json --points - --quantities irradiance --basis zh3 --rays 64")
sphbasis_bake_test(texels_l1_nonlinear "l1-nonlinear-ok"
  "rm -rf bake_l1n && \"${_bake}\" bake ${_scenes}/quad_obj.json --target texels:8 --quantities irradiance --basis sh-l1-nonlinear --rays 16 --out bake_l1n && grep -q '\"storage\": *\"sh-l1-nonlinear\"' bake_l1n/bake.json && grep -a -q irr_r_3 bake_l1n/mesh0.exr && ! grep -a -q irr_r_4 bake_l1n/mesh0.exr && echo l1-nonlinear-ok")
sphbasis_bake_bad(sg_solver_not_sg "--sg-solver: only for --basis sg5\\|sg6\\|sg9\\|sg12 \\(or sg\\), got 'zh3'"
  bake ${_scenes}/lone_sphere.json --basis zh3 --sg-solver nnls)
# An explicit --sg-solver is refused without an SG basis even at its default (ls); with one it
# bakes what the default does.
sphbasis_bake_bad(sg_solver_ls_not_sg "--sg-solver: only for --basis sg5\\|sg6\\|sg9\\|sg12 \\(or sg\\), got 'sh'"
  bake ${_scenes}/lone_sphere.json --sg-solver ls)
sphbasis_bake_test(sg_solver_ls_explicit "sg-ls-same"
  "printf '0.5 0 0 0 0 1\\n' | \"${_bake}\" bake ${_scenes}/sphere_over_quad.json --points - --quantities irradiance --basis sg9 --sg-solver ls --rays 16 > bake_sg_ls.txt && printf '0.5 0 0 0 0 1\\n' | \"${_bake}\" bake ${_scenes}/sphere_over_quad.json --points - --quantities irradiance --basis sg9 --rays 16 > bake_sg_default.txt && cmp bake_sg_ls.txt bake_sg_default.txt && echo sg-ls-same")
sphbasis_bake_bad(sg_solver_unknown "--sg-solver: expected ls, nnls or running, got 'svd'"
  bake ${_scenes}/lone_sphere.json --basis sg9 --sg-solver svd)
sphbasis_bake_bad(coeffs_zh3 "--coeffs: 'zh3' stores 5 values, got 9"
  bake ${_scenes}/lone_sphere.json --basis zh3 --coeffs 9)
# Ambient Dice over the faces: 30 (Bezier) and 10 (linear) values a channel on the tangent
# hemisphere without --coeffs; the whole sphere's 36 and 12 and the YCoCg variant refused.
sphbasis_bake_test(texels_dice_bezier "dice-bezier-ok"
  "rm -rf bake_dice && \"${_bake}\" bake ${_scenes}/quad_obj.json --target texels:8 --quantities irradiance --basis ambient-dice-bezier --rays 16 --out bake_dice && grep -q '\"basis\": *\"ambient-dice-bezier\"' bake_dice/bake.json && grep -q '\"coeffs\": *30' bake_dice/bake.json && grep -a -q irr_b_29 bake_dice/mesh0.exr && ! grep -a -q irr_r_30 bake_dice/mesh0.exr && echo dice-bezier-ok")
sphbasis_bake_test(points_dice_linear "\"irradiance\":\\[\\[[-0-9.e]+,[-0-9.e]+,[-0-9.e]+,[-0-9.e]+,[-0-9.e]+,[-0-9.e]+,[-0-9.e]+,[-0-9.e]+,[-0-9.e]+,[-0-9.e]+\\]"
  "printf '0.5 0 0 0 0 1\\n' | \"${_bake}\" bake ${_scenes}/sphere_over_quad.json --points - --quantities irradiance --basis ambient-dice-linear --rays 64")
sphbasis_bake_bad(coeffs_dice_full "--coeffs: 'ambient-dice-bezier' stores 30 values on the tangent hemisphere \\(36 is the whole sphere's\\), got 36"
  bake ${_scenes}/lone_sphere.json --quantities irradiance --basis ambient-dice-bezier --coeffs 36)
sphbasis_bake_bad(basis_dice_ycocg "--basis: ambient-dice-ycocg stores 30 luma and 10 \\+ 10 chroma values, but a bake stores the same count for R, G and B; bake ambient-dice-bezier and ambient-dice-linear"
  bake ${_scenes}/lone_sphere.json --quantities irradiance --basis ambient-dice-ycocg)
# Irradiance and radiance with their standard errors at a surface point: "irradiance" (three
# lists of --coeffs), "irradiance_stderr" (one list), "radiance", "radiance_stderr", "inside".
sphbasis_bake_test(points_stderr_keys "\\{\"p\":\\[0.5,0,0\\],\"n\":\\[0,0,1\\],\"irradiance\":\\[\\[[-0-9.e,]*\\],\\[[-0-9.e,]*\\],\\[[-0-9.e,]*\\]\\],\"irradiance_stderr\":\\[[0-9.e-]+,[0-9.e-]+,[0-9.e-]+,[0-9.e-]+\\],\"radiance\":\\[\\[[-0-9.e,]*\\],\\[[-0-9.e,]*\\],\\[[-0-9.e,]*\\]\\],\"radiance_stderr\":\\[[0-9.e-]+,[0-9.e-]+,[0-9.e-]+,[0-9.e-]+,[0-9.e-]+,[0-9.e-]+,[0-9.e-]+,[0-9.e-]+,[0-9.e-]+\\],\"inside\":false\\}"
  "printf '0.5 0 0 0 0 1\\n' | \"${_bake}\" bake ${_scenes}/sphere_over_quad.json --points - --quantities irradiance,radiance --basis hbasis --coeffs 4 --bands 3 --rays 64")
# The files carry the same errors as channels: irr_stderr_<i> and rad_stderr_<i>.
sphbasis_bake_test(stderr_channels "stderr-channels-ok"
  "rm -rf bake_se && \"${_bake}\" bake ${_scenes}/sphere_over_quad.json --quantities irradiance,radiance --basis hbasis --coeffs 4 --bands 2 --rays 16 --out bake_se && grep -a -q 'property float irr_stderr_3' bake_se/ground.ply && grep -a -q 'property float rad_stderr_3' bake_se/ball.ply && grep -q '\"irr_stderr_0\"' bake_se/bake.json && grep -q '\"rad_stderr_3\"' bake_se/bake.json && echo stderr-channels-ok")
# Vertex bake: one PLY per mesh with the documented properties, and the summary with a plan.
sphbasis_bake_test(vertices_files "vertices-ok"
  "rm -rf bake_v && \"${_bake}\" bake ${_scenes}/sphere_over_quad.json --quantities ao,bent,visibility --rays 32 --out bake_v && grep -a -q 'property float ao_stderr' bake_v/ground.ply && grep -a -q 'property float vis_8' bake_v/ball.ply && grep -a -q 'property float bent_z' bake_v/ball.ply && grep -a -q 'property float bent_stderr' bake_v/ball.ply && grep -q '\"plan\":\\[' bake_v/bake.json && grep -q '\"reason\":' bake_v/bake.json && ! ls -a bake_v | grep -q tmp && echo vertices-ok")
# Texel bake: a multi-channel EXR per mesh (the OBJ mesh and the procedural floor).
sphbasis_bake_test(texels_files "texels-ok"
  "rm -rf bake_t && \"${_bake}\" bake ${_scenes}/quad_obj.json --target texels:32 --quantities ao,bent,transfer --bands 2 --rays 32 --out bake_t && test -s bake_t/mesh0.exr && test -s bake_t/floor.exr && grep -q '\"coverage\"' bake_t/bake.json && grep -q '\"transfer_stderr_3\"' bake_t/bake.json && grep -q '\"bent_stderr\"' bake_t/bake.json && grep -a -q 'bent_stderr' bake_t/floor.exr && echo texels-ok")
# Probes: the grid around a lone sphere; the centre probe is inside it.
sphbasis_bake_test(probes_file "probes-ok"
  "rm -rf bake_p && \"${_bake}\" bake ${_scenes}/lone_sphere.json --target probes --quantities radiance --bands 2 --rays 64 --out bake_p && grep -q '\"index\":13,\"p\":\\[0,0,0\\],\"inside\":true' bake_p/probes.json && echo probes-ok")
# Sharding: two processes (xargs -P 2) bake halves; bake-merge is byte-identical to one run.
sphbasis_bake_test(shard_merge_vertices "shard-vertices-ok"
  "rm -rf bake_s1 bake_sh bake_sm && \"${_bake}\" bake ${_scenes}/sphere_over_quad.json --quantities ao,bent,transfer --bands 3 --rays 64 --seed 5 --out bake_s1 && printf '0/2\\n1/2\\n' | xargs -P 2 -I{} \"${_bake}\" bake ${_scenes}/sphere_over_quad.json --quantities ao,bent,transfer --bands 3 --rays 64 --seed 5 --out bake_sh --shard {} && \"${_bake}\" bake-merge bake_sh/bake.shard-0-of-2.bin bake_sh/bake.shard-1-of-2.bin --out bake_sm && cmp bake_s1/ground.ply bake_sm/ground.ply && cmp bake_s1/ball.ply bake_sm/ball.ply && echo shard-vertices-ok")
sphbasis_bake_test(shard_merge_texels "shard-texels-ok"
  "rm -rf bake_t1 bake_th bake_tm && \"${_bake}\" bake ${_scenes}/quad_obj.json --target texels:16 --quantities ao,irradiance --basis hbasis --coeffs 6 --rays 64 --out bake_t1 && printf '0/2\\n1/2\\n' | xargs -P 2 -I{} \"${_bake}\" bake ${_scenes}/quad_obj.json --target texels:16 --quantities ao,irradiance --basis hbasis --coeffs 6 --rays 64 --out bake_th --shard {} && \"${_bake}\" bake-merge bake_th/bake.shard-1-of-2.bin bake_th/bake.shard-0-of-2.bin --out bake_tm && cmp bake_t1/mesh0.exr bake_tm/mesh0.exr && cmp bake_t1/floor.exr bake_tm/floor.exr && echo shard-texels-ok")
# Shards are render/bake_file.hpp files (docs/bake-format.md): a flipped bit anywhere is caught by
# the checksum; a shard of the earlier format (magic SPHBSHRD) is refused by its magic; and a mesh
# file edited between bake and merge (the bytes of every file the scene reads are in the input
# hash) is refused, though the scene JSON is unchanged.
sphbasis_bake_test(merge_corrupt_shard "bake-merge: .*bake.shard-0-of-2.bin: not a shard file of this sphbasis bake \\(sphbasis::render::read_bake_file\\(\\): expected the checksum to match, got a corrupt file\\)"
  "rm -rf bake_cs && \"${_bake}\" bake ${_scenes}/lone_sphere.json --rays 16 --out bake_cs --shard 0/2 && \"${_bake}\" bake ${_scenes}/lone_sphere.json --rays 16 --out bake_cs --shard 1/2 && python3 -c \"import sys; p=sys.argv[1]; b=bytearray(open(p,'rb').read()); b[len(b)-20]^=4; open(p,'wb').write(b)\" bake_cs/bake.shard-0-of-2.bin && ! \"${_bake}\" bake-merge bake_cs/bake.shard-0-of-2.bin bake_cs/bake.shard-1-of-2.bin --out bake_cs/m 2>&1")
sphbasis_bake_test(merge_old_format "bake-merge: .*bake.shard-0-of-2.bin: not a shard file of this sphbasis bake \\(sphbasis::render::read_bake_file\\(\\): expected a bake file \\(magic SPHBFILE\\)"
  "rm -rf bake_of && \"${_bake}\" bake ${_scenes}/lone_sphere.json --rays 16 --out bake_of --shard 0/2 && \"${_bake}\" bake ${_scenes}/lone_sphere.json --rays 16 --out bake_of --shard 1/2 && python3 -c \"import sys; p=sys.argv[1]; b=open(p,'rb').read(); open(p,'wb').write(b'SPHBSHRD'+b[8:])\" bake_of/bake.shard-0-of-2.bin && ! \"${_bake}\" bake-merge bake_of/bake.shard-0-of-2.bin bake_of/bake.shard-1-of-2.bin --out bake_of/m 2>&1")
sphbasis_bake_test(merge_mesh_edited "bake-merge: .*quad_obj.json: the scene or a file it reads changed since the shards were baked"
  "rm -rf bake_me && mkdir bake_me && cp ${_scenes}/quad_obj.json ${_scenes}/quad_uv.obj bake_me/ && \"${_bake}\" bake bake_me/quad_obj.json --rays 16 --out bake_me --shard 0/2 && \"${_bake}\" bake bake_me/quad_obj.json --rays 16 --out bake_me --shard 1/2 && printf '# edited after the bake\\n' >> bake_me/quad_uv.obj && ! \"${_bake}\" bake-merge bake_me/bake.shard-0-of-2.bin bake_me/bake.shard-1-of-2.bin --out bake_me/m 2>&1 && ! test -e bake_me/m/mesh0.ply")
# A missing shard is an error, not a partial file.
sphbasis_bake_test(merge_missing_shard "missing-shard-ok"
  "rm -rf bake_ms && \"${_bake}\" bake ${_scenes}/lone_sphere.json --rays 16 --out bake_ms --shard 0/3 && ! \"${_bake}\" bake-merge bake_ms/bake.shard-0-of-3.bin --out bake_ms/merged 2>/dev/null && ! test -e bake_ms/merged/mesh0.ply && echo missing-shard-ok")
# Rays per second at the end, on stderr.
sphbasis_bake_test(rate_report "sphbasis bake: [0-9]+ points, [0-9]+ rays in [0-9.]+ s: [0-9.e+]+ rays/s"
  "rm -rf bake_r && \"${_bake}\" bake ${_scenes}/lone_sphere.json --rays 16 --out bake_r 2>&1 >/dev/null")
# Textures (PNG through stb_image), an OBJ with a 4x4 matrix, a box and an EXR environment:
# irradiance at a point on the tile next to the crate.
sphbasis_bake_test(textured_scene "\\{\"p\":\\[1,0,0\\],\"n\":\\[0,0,1\\],\"ao\":[-0-9.e]+,\"ao_stderr\":[-0-9.e]+,\"irradiance\":\\[\\["
  "printf '1 0 0 0 0 1\\n' | \"${_bake}\" bake ${_scenes}/textured.json --points - --quantities ao,irradiance --basis hbasis --coeffs 6 --rays 128")
# An output directory that cannot be created fails before any work.
sphbasis_bake_bad(out_unwritable "cannot create output directory '/dev/null/x'" bake ${_scenes}/lone_sphere.json --out /dev/null/x)

# White furnace on meshes as files deliver them (label "bake"): the open box of
# data/scenes/furnace (albedo 1, constant unit sky) read from OBJ files with flat normals, without
# normals (generated with the default crease angle), with normals smoothed across its edges and
# with mixed winding (with and without normals). The exit radiance is 1 at every vertex
# (check_furnace_ply.py: within 5 standard errors).
foreach(_v flat nonormals smooth mixed mixed_nonormals)
  sphbasis_bake_test(furnace_obj_${_v} "furnace-ok"
    "rm -rf bake_furnace_${_v} && \"${_bake}\" bake ${_scenes}/furnace/open_box_${_v}.json --quantities transfer --bands 1 --bounces 24 --rays 64 --out bake_furnace_${_v} >/dev/null && python3 ${CMAKE_CURRENT_SOURCE_DIR}/cli/check_furnace_ply.py bake_furnace_${_v}/mesh0.ply")
endforeach()

# Engine exports (--format gltf, docs/export-format.md). The glTF's attributes equal the native
# PLY's values (the same bake: results depend only on seed, point and settings), read by a GLB
# reader written from the specification (check_gltf_bake.py); lightmaps and probe slices are
# written, and listed in bake.json. tests/tools/test_engine_export.cpp reads them back with
# tinygltf, Assimp, stb_image and OpenEXR within the stated quantisation bound.
sphbasis_bake_test(gltf_vertices "gltf-bake-ok 2 [0-9]+"
  "rm -rf bake_gn bake_gg && \"${_bake}\" bake ${_scenes}/sphere_over_quad.json --quantities ao,bent,irradiance --rays 32 --seed 4 --out bake_gn && \"${_bake}\" bake ${_scenes}/sphere_over_quad.json --quantities ao,bent,irradiance --rays 32 --seed 4 --out bake_gg --format gltf && python3 ${CMAKE_CURRENT_SOURCE_DIR}/cli/check_gltf_bake.py bake_gg bake_gn _AO=ao _BENT=bent_x,bent_y,bent_z _SH0=irr_r_0,irr_g_0,irr_b_0 _SH8=irr_r_8,irr_g_8,irr_b_8")
sphbasis_bake_test(gltf_texels "gltf-texels-ok"
  "rm -rf bake_gt && \"${_bake}\" bake ${_scenes}/quad_obj.json --target texels:16 --quantities ao,irradiance --rays 16 --out bake_gt --format gltf --encoding png16 && test -s bake_gt/scene.glb && test -s bake_gt/mesh0.ao.png && test -s bake_gt/floor.sh8.png && grep -q '\"encoding\":\"png16\"' bake_gt/lightmaps.json && grep -q '\"lightmaps.json\"' bake_gt/bake.json && ! test -e bake_gt/mesh0.exr && echo gltf-texels-ok")
sphbasis_bake_test(gltf_probes "gltf-probes-ok"
  "rm -rf bake_gp && \"${_bake}\" bake ${_scenes}/lone_sphere.json --target probes --quantities radiance --bands 2 --rays 16 --out bake_gp --format gltf --encoding half && test -s bake_gp/probes.rad3.z2.exr && test -s bake_gp/probes.inside.z0.exr && grep -q '\"counts\":\\[3,3,3\\]' bake_gp/probes.grid.json && echo gltf-probes-ok")
sphbasis_bake_bad(format_unknown "--format: expected native or gltf, got 'fbx'" bake ${_scenes}/lone_sphere.json --format fbx)
sphbasis_bake_bad(encoding_unknown "--encoding: expected png8, png16, half or float, got 'jpg'" bake ${_scenes}/lone_sphere.json --format gltf --encoding jpg)
sphbasis_bake_bad(format_gltf_shard "--format gltf: not with --points or --shard" bake ${_scenes}/lone_sphere.json --format gltf --shard 0/2)
sphbasis_bake_test(gltf_cpca "gltf-cpca-ok"
  "rm -rf bake_gc && \"${_bake}\" bake ${_scenes}/sphere_over_quad.json --quantities transfer --bands 3 --rays 16 --out bake_gc --format gltf --export cpca:4:3 && grep -q '\"clusters\":4,\"vectors\":3,\"coefficients\":9' bake_gc/cpca.json && test -s bake_gc/cpca.bin && grep -q '\"kind\":\"cpca\"' bake_gc/bake.json && echo gltf-cpca-ok")
sphbasis_bake_bad(export_malformed "--export: expected pca:M or cpca:C:M" bake ${_scenes}/lone_sphere.json --format gltf --export cpca:2)
sphbasis_bake_bad(export_without_transfer "--export: compresses transfer vectors; give --quantities transfer" bake ${_scenes}/lone_sphere.json --format gltf --export pca:2)
sphbasis_bake_bad(export_without_gltf "--export: needs --format gltf" bake ${_scenes}/lone_sphere.json --export pca:2)
sphbasis_bake_test(gltf_toksvig "gltf-toksvig-ok"
  "rm -rf bake_gk && \"${_bake}\" bake ${_scenes}/lone_sphere.json --rays 8 --out bake_gk --format gltf --export toksvig:32 && test -s bake_gk/toksvig.png && grep -q '\"shininess\":32' bake_gk/toksvig.json && echo gltf-toksvig-ok")
# The L x H table and the SVD normal basis (cube-map faces side by side; one image per function),
# the CPCA of a texel bake as lightmap-UV textures, and bake-merge writing the same engine files
# as one unsharded bake (records bit for bit: the files compare equal).
sphbasis_bake_test(gltf_lxh_svd "gltf-lxh-svd-ok"
  "rm -rf bake_gx && \"${_bake}\" bake ${_scenes}/lone_sphere.json --rays 8 --out bake_gx --format gltf --export lxh:3:2:8,svd:4:16 && test -s bake_gx/lxh.k8.png && ! test -e bake_gx/lxh.k9.png && test -s bake_gx/svd.b3.png && grep -q '\"face_size\":8' bake_gx/lxh.json && grep -q '\"kind\":\"normal basis\"' bake_gx/bake.json && echo gltf-lxh-svd-ok")
sphbasis_bake_bad(export_lxh_malformed "--export: expected lxh:K" bake ${_scenes}/lone_sphere.json --format gltf --export lxh:17)
sphbasis_bake_bad(export_svd_malformed "--export: expected svd:M" bake ${_scenes}/lone_sphere.json --format gltf --export svd:4:x)
sphbasis_bake_bad(export_lxh_without_gltf "--export: needs --format gltf" bake ${_scenes}/lone_sphere.json --export lxh:3)
# --encoding and --export shape only glTF files: given without --format gltf (even at the
# default png8, or an empty list) they are refused, by bake and by bake-merge.
sphbasis_bake_bad(encoding_without_gltf "--encoding: needs --format gltf" bake ${_scenes}/lone_sphere.json --encoding png8)
sphbasis_bake_bad(export_empty_without_gltf "--export: needs --format gltf" bake ${_scenes}/lone_sphere.json --export '')
sphbasis_bake_bad(merge_encoding_without_gltf "--encoding: needs --format gltf" bake-merge nothing.bin --encoding half)
sphbasis_bake_bad(merge_export_without_gltf "--export: needs --format gltf" bake-merge nothing.bin --export pca:2)
sphbasis_bake_test(gltf_cpca_texels "gltf-cpca-texels-ok"
  "rm -rf bake_gct && \"${_bake}\" bake ${_scenes}/quad_obj.json --target texels:16 --quantities transfer --bands 2 --rays 8 --out bake_gct --format gltf --export pca:2 && test -s bake_gct/floor.cpca_cluster.png && test -s bake_gct/floor.cpca_w1.png && grep -q '\"textures\"' bake_gct/cpca.json && echo gltf-cpca-texels-ok")
sphbasis_bake_test(gltf_merge "gltf-merge-ok"
  "rm -rf bake_gm1 bake_gm2 bake_gms && \"${_bake}\" bake ${_scenes}/quad_obj.json --target texels:16 --quantities ao,irradiance --rays 8 --out bake_gm1 --format gltf && \"${_bake}\" bake ${_scenes}/quad_obj.json --target texels:16 --quantities ao,irradiance --rays 8 --out bake_gms --shard 0/2 && \"${_bake}\" bake ${_scenes}/quad_obj.json --target texels:16 --quantities ao,irradiance --rays 8 --out bake_gms --shard 1/2 && \"${_bake}\" bake-merge bake_gms/bake.shard-0-of-2.bin bake_gms/bake.shard-1-of-2.bin --out bake_gm2 --format gltf && cmp bake_gm1/scene.glb bake_gm2/scene.glb && cmp bake_gm1/floor.sh8.png bake_gm2/floor.sh8.png && cmp bake_gm1/lightmaps.json bake_gm2/lightmaps.json && echo gltf-merge-ok")
# A texel bake on a glTF's second UV set (check_two_uv_bake.py writes the file): TEXCOORD_1 in the
# export, the lightmaps on texCoord 1, the AO lightmap covering set 1's rectangle only.
sphbasis_bake_test(gltf_two_uv "two-uv-ok 256"
  "rm -rf bake_g2uv bake_g2uv_out && python3 ${CMAKE_CURRENT_SOURCE_DIR}/cli/check_two_uv_bake.py write bake_g2uv && \"${_bake}\" bake bake_g2uv/scene.json --target texels:32 --quantities ao --rays 16 --out bake_g2uv_out --format gltf && python3 ${CMAKE_CURRENT_SOURCE_DIR}/cli/check_two_uv_bake.py check bake_g2uv_out 32")
sphbasis_bake_bad(merge_format_unknown "--format: expected native or gltf, got 'fbx'" bake-merge nothing.bin --format fbx)
# High to low (render/high_to_low.hpp; scenes/high_to_low.json: a quad over a disk with a
# hemispherical pit): ambient occlusion 1/2 in the pit and 1 on the disk, the pit's normals in
# the normal map, misses off the disk (check_high_to_low.py); the texel bake's channels and the
# projection pass in bake.json; a sharded bake merged equals one run; the scene keys' errors.
set(_h2l ${PROJECT_SOURCE_DIR}/scenes/high_to_low.json)
sphbasis_bake_test(high_to_low_vertices "high-to-low-ok"
  "rm -rf bake_h2l && \"${_bake}\" bake ${_h2l} --quantities ao,normal_map --rays 512 --out bake_h2l >/dev/null 2>&1 && python3 ${CMAKE_CURRENT_SOURCE_DIR}/cli/check_high_to_low.py bake_h2l/panel.ply")
sphbasis_bake_test(high_to_low_texels "h2l-texels-ok"
  "rm -rf bake_h2lt && \"${_bake}\" bake ${_h2l} --quantities normal-map,bent --rays 16 --target texels:16 --out bake_h2lt >/dev/null 2>&1 && python3 -c \"import json,sys; j=json.load(open('bake_h2lt/bake.json')); o=[x for x in j['outputs'] if x['mesh']=='panel'][0]; assert {'normal_x','normal_y','normal_z','bent_x','coverage'} <= set(o['channels']), o; p=j['plan'][0]; assert p['name']=='project' and p['rays']>=2*256, p; print('h2l-texels-ok')\"")
sphbasis_bake_test(high_to_low_normal_map_only "h2l-only-ok"
  "rm -rf bake_h2lo && \"${_bake}\" bake ${_h2l} --quantities normal_map --out bake_h2lo >/dev/null 2>&1 && python3 -c \"import json; j=json.load(open('bake_h2lo/bake.json')); assert [p['name'] for p in j['plan']]==['project'], j['plan']; assert j['rays']==j['plan'][0]['rays']; print('h2l-only-ok')\"")
sphbasis_bake_test(high_to_low_shards "h2l-shards-ok"
  "rm -rf bake_h2ls && \"${_bake}\" bake ${_h2l} --quantities ao,normal_map --rays 32 --out bake_h2ls/one >/dev/null 2>&1 && \"${_bake}\" bake ${_h2l} --quantities ao,normal_map --rays 32 --out bake_h2ls --shard 0/2 2>/dev/null && \"${_bake}\" bake ${_h2l} --quantities ao,normal_map --rays 32 --out bake_h2ls --shard 1/2 2>/dev/null && \"${_bake}\" bake-merge bake_h2ls/bake.shard-0-of-2.bin bake_h2ls/bake.shard-1-of-2.bin --out bake_h2ls/merged 2>/dev/null && cmp bake_h2ls/one/panel.ply bake_h2ls/merged/panel.ply && echo h2l-shards-ok")
# A high-to-low bake stores render-cache entries under keys of its own: every mesh's differs
# from that of the same scene without the "source" (where the panel occludes and is baked on its
# own surface).
sphbasis_bake_test(high_to_low_cache_keys "h2l-keys-ok"
  "rm -rf bake_h2lk && mkdir bake_h2lk && python3 -c \"import json; s=json.load(open('${_h2l}')); s['meshes'][0]['file']='${PROJECT_SOURCE_DIR}/scenes/pitted_disk.ply'; del s['meshes'][1]['source'], s['meshes'][1]['max_ray_distance']; json.dump(s, open('bake_h2lk/plain.json', 'w'))\" && \"${_bake}\" bake ${_h2l} --quantities ao --rays 8 --out bake_h2lk/h2l >/dev/null 2>&1 && \"${_bake}\" bake bake_h2lk/plain.json --quantities ao --rays 8 --out bake_h2lk/plain >/dev/null 2>&1 && python3 -c \"import json; k=lambda d: {e['mesh']: e['key'] for e in json.load(open(d + '/bake.json'))['render_cache']}; a=k('bake_h2lk/h2l'); b=k('bake_h2lk/plain'); assert set(a)==set(b)=={'detail','panel'}, (a, b); assert all(a[m]!=b[m] for m in a), (a, b); print('h2l-keys-ok')\"")
sphbasis_bake_bad(h2l_unknown_source "[^ ]*h2l_unknown_source.json: meshes\\[1\\].source: no mesh named 'detial' \\(did you mean 'detail'\\?\\)"
                  bake ${_scenes}/bad/h2l_unknown_source.json)
sphbasis_bake_bad(h2l_cage_mismatch "[^ ]*h2l_cage_mismatch.json: meshes\\[1\\].cage: expected a mesh of the same 9 vertices and 8 triangles as the mesh, got 16 vertices and 18 triangles"
                  bake ${_scenes}/bad/h2l_cage_mismatch.json)
sphbasis_bake_bad(h2l_distance_without_source "[^ ]*h2l_distance_without_source.json: meshes\\[0\\].max_ray_distance: needs a \"source\" mesh"
                  bake ${_scenes}/bad/h2l_distance_without_source.json)
sphbasis_bake_bad(h2l_chain "[^ ]*h2l_chain.json: meshes\\[0\\].source: the source 'b' has a source itself"
                  bake ${_scenes}/bad/h2l_chain.json)
sphbasis_bake_bad(h2l_normal_map_points "--quantities normal_map: the tangent-space normal map is baked per vertex or texel"
                  bake ${_h2l} --quantities normal_map --points -)
# A cage (data/scenes/high_to_low_cage.json: a coarse sphere with a larger copy as its cage
# inside a fine one): every ray from the cage hits the source.
sphbasis_bake_test(high_to_low_cage "h2l-cage-ok"
  "rm -rf bake_h2lc && \"${_bake}\" bake ${_scenes}/high_to_low_cage.json --quantities ao,normal_map --rays 8 --target texels:16 --out bake_h2lc >/dev/null 2>&1 && python3 -c \"import json,re; p=json.load(open('bake_h2lc/bake.json'))['plan'][0]; m=re.search(r'rays from ([0-9]+) points .*, ([0-9]+) hit', p['reason']); assert p['name']=='project' and m and m.group(1)==m.group(2) and int(m.group(1)) <= p['rays'] <= 3*int(m.group(1)), p; print('h2l-cage-ok')\"")
