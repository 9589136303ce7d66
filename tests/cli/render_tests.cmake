# Tests of `sphbasis render`. Included by tests/CMakeLists.txt after bake_tests.cmake. Label
# "cli": options, help and bad input (rejected before any ray is traced; nothing written).
# Label "render": small end-to-end runs (32x24 pixels) checked by check_render_report.py: the
# furnace's closed form, the bake cache (re-render, rotated lighting, corrupt files), the plan's
# skipped passes, the specular comparison, determinism across thread counts, every metric
# finite and in range on the committed dark (Cornell) and specular scenes, the ranking on the
# normal-mapped wall at two image sizes (check_ranking.py), report.html sorting in headless
# chromium (skipped without it).
set(_render $<TARGET_FILE:sphbasis_cli>)
set(_rscenes ${CMAKE_CURRENT_SOURCE_DIR}/data/scenes/render)
set(_check_report ${CMAKE_CURRENT_SOURCE_DIR}/cli/check_render_report.py)

# Passes when `sphbasis render ARGN...` exits non-zero with exactly one line on stderr matching
# regex.
function(sphbasis_render_bad name regex)
  sphbasis_cli_bad(render_bad_${name} "render: ${regex}" render ${ARGN})
endfunction()
function(sphbasis_render_test name regex script)
  sphbasis_script_test(render ${name} "${regex}" "${script}")
endfunction()

# Help.
sphbasis_cli_test(render_help "Usage: sphbasis render.*SCENE.json.*--representations LIST\\|all.*--spp N.*--noise X.*--width W.*--height H.*--threads N.*--seed S.*--exposure X\\|auto.*--tonemap NAME.*--rays N.*--rotate-lighting-deg X,Y,Z.*--no-cache.*--out DIR"
                  render --help)
sphbasis_cli_test(help_lists_render "Subcommands:.*render" --help)

# Bad options: one line, exit 2, before the scene is read.
sphbasis_render_bad(unknown_representation "--representations: unknown representation 'sh9'; expected 'all' or a list of: irradiance-sh9 irradiance-sh9-windowed ao bent prt-vertex prt-texel lightmap-sh4 .* volume volume-ambient-cube volume-ambient-dice volume-ambient-dice-bezier volume-sh-l1-nonlinear volume-zh3-hallucinate volume-zh3 volume-sg9 specular-toksvig specular-aliased .*prt-cpca-16-4 \\(and lxh-pcaM, M <= 36; prt-cpca-C-M, C <= 4096, M <= 64\\)\n"
                    ${_rscenes}/tiny_sun.json --representations ao,sh9)
sphbasis_render_bad(representation_typo "--representations: unknown representation 'prt-vertx' \\(did you mean 'prt-vertex'\\?\\)"
                    ${_rscenes}/tiny_sun.json --representations prt-vertx)
sphbasis_render_bad(representation_twice "--representations: 'ao' given twice" ${_rscenes}/tiny_sun.json --representations ao,ao)
sphbasis_render_bad(representation_empty "--representations: expected 'all' or a list" ${_rscenes}/tiny_sun.json --representations ao,)
sphbasis_render_bad(spp_and_noise "give either --spp or --noise, not both" ${_rscenes}/tiny_sun.json --spp 4 --noise 0.1)
sphbasis_render_bad(noise_range "--noise: expected a relative noise in \\(0, 1\\), got 1.5" ${_rscenes}/tiny_sun.json --noise 1.5)
sphbasis_render_bad(noise_malformed "--noise: expected a finite number, got 'abc'" ${_rscenes}/tiny_sun.json --noise abc)
sphbasis_render_bad(spp_zero "--spp: expected 2 <= N <= 1048576, got 0" ${_rscenes}/tiny_sun.json --spp 0)
sphbasis_render_bad(exposure "--exposure: expected a positive number or auto" ${_rscenes}/tiny_sun.json --exposure -1)
sphbasis_render_bad(tonemap "--tonemap: unknown operator 'filmic' \\(expected clamp, reinhard or aces\\)" ${_rscenes}/tiny_sun.json --tonemap filmic)
sphbasis_render_bad(rotate_count "--rotate-lighting-deg: expected x,y,z" ${_rscenes}/tiny_sun.json --rotate-lighting-deg 0,90)
sphbasis_render_bad(noise_limit "--noise-limit: expected a positive fraction, got 0" ${_rscenes}/tiny_sun.json --noise-limit 0)
# Bad scenes: one line naming the file and the place.
sphbasis_render_bad(missing_scene "[^ ]*no_such_scene.json: cannot open the scene file" ${_rscenes}/no_such_scene.json)
sphbasis_render_bad(no_camera "[^ ]*no_camera.json: no \"camera\": the renderer needs one" ${_rscenes}/no_camera.json)
sphbasis_render_bad(camera_width "[^ ]*bad_width.json: camera.width: expected an integer in \\[1, 16384\\], got 0" ${_rscenes}/bad_width.json)
sphbasis_render_bad(camera_up "[^ ]*camera_up_parallel.json: camera.up: expected a direction not parallel to the view direction" ${_rscenes}/camera_up_parallel.json)
sphbasis_render_bad(camera_points "[^ ]*camera_same_points.json: camera: expected look_at different from position" ${_rscenes}/camera_same_points.json)
sphbasis_render_bad(scene_tonemap "[^ ]*bad_tonemap.json: render.tonemap: unknown tone-mapping operator 'filmic'" ${_rscenes}/bad_tonemap.json)
sphbasis_render_bad(scene_bounces "[^ ]*bad_bounces.json: render.bounces: expected an integer in \\[-1, 64\\], got -2" ${_rscenes}/bad_bounces.json)
sphbasis_render_bad(scene_exposure "[^ ]*bad_exposure.json: render.exposure: expected a positive number or \"auto\", got 'bright'" ${_rscenes}/bad_exposure.json)
sphbasis_render_bad(scene_spp_noise "[^ ]*spp_and_noise.json: render: expected at most one of \"spp\" and \"noise\"" ${_rscenes}/spp_and_noise.json)
sphbasis_render_bad(scene_typo "[^ ]*render_typo.json: render: unknown key 'bounce' \\(did you mean 'bounces'\\?\\)" ${_rscenes}/render_typo.json)
sphbasis_render_bad(shininess "[^ ]*bad_shininess.json: meshes\\[0\\].shininess: expected a Blinn-Phong exponent in \\[0, 1e6\\]" ${_rscenes}/bad_shininess.json)
sphbasis_render_bad(specular "[^ ]*bad_specular.json: meshes\\[0\\].specular\\[0\\]: expected a value in \\[0, 1\\], got 2" ${_rscenes}/bad_specular.json)
# Only the effects a scene calls for: asking for the specular comparison of a scene without a
# shiny material is an error (with "all" it is skipped and the plan says so).
sphbasis_render_bad(specular_without_shininess "--representations: specular-toksvig needs a shiny material and a directional light, but in this scene no material declares a \"shininess\""
                    ${_rscenes}/tiny_sun.json --representations ao,specular-toksvig)
sphbasis_render_bad(out_unwritable "cannot create output directory '/dev/null/x'" ${_rscenes}/tiny_sun.json --out /dev/null/x)
# Bad input writes nothing: no output directory is created.
sphbasis_cli_script(render_bad_input_writes_nothing "nothing-written-ok"
  "rm -rf render_nothing && ! \"${_render}\" render ${_rscenes}/no_camera.json --out render_nothing 2>/dev/null && ! \"${_render}\" render ${_rscenes}/tiny_sun.json --representations nope --out render_nothing 2>/dev/null && ! test -e render_nothing && echo nothing-written-ok")

# --- End-to-end runs (label "render") ---------------------------------------------------------

# White furnace: a white convex sphere under a constant unit environment, no bounces needed:
# the reference is 1 at every pixel, and so are
# irradiance-sh9 (exact for a constant environment) and prt-vertex (analytic: nothing occludes).
# Every covered pixel is judged: cosine samples about the interpolated normal that dip below a
# facet of the tessellated sphere are folded above it (path_tracer.hpp), so the silhouette is 1
# too. No bounce rays (bounces 0), no normal-map or specular work.
sphbasis_render_test(furnace "render-report-ok"
  "rm -rf render_furnace && \"${_render}\" render ${_rscenes}/tiny_sphere.json --representations irradiance-sh9,prt-vertex --rays 64 --out render_furnace && python3 ${_check_report} render_furnace rows=2 judged_min=1 max_rel_mse=irradiance-sh9:1e-4 max_rel_mse=prt-vertex:1e-4 counter=bounce_rays:0 counter=normal_map_lookups:0 counter=specular_evaluations:0 effect!~specular effect!~normal")
# The plan is printed on stderr before the work, with the reference's effects and the bakes.
sphbasis_render_test(plan_printed "plan for [^\n]*tiny_sun.json \\(32x24\\):.*reference: path tracer, bounces 1.*bake 1: "
  "rm -rf render_plan && \"${_render}\" render ${_rscenes}/tiny_sun.json --representations ao,prt-vertex --rays 16 --out render_plan 2>&1 >/dev/null")
# The bake cache: a second run bakes nothing; a rotated environment re-bakes nothing for PRT.
sphbasis_render_test(cache_reuse "render-report-ok\nrender-report-ok\nrender-report-ok"
  "rm -rf render_cache && \"${_render}\" render ${_rscenes}/tiny_sun.json --representations prt-vertex,ao --rays 16 --out render_cache 2>/dev/null && python3 ${_check_report} render_cache bakes_loaded=0 && \"${_render}\" render ${_rscenes}/tiny_sun.json --representations prt-vertex,ao --rays 16 --out render_cache 2>/dev/null && python3 ${_check_report} render_cache bakes_run=0 && \"${_render}\" render ${_rscenes}/tiny_sun.json --representations prt-vertex --rays 16 --rotate-lighting-deg 0,0,90 --out render_cache 2>/dev/null && python3 ${_check_report} render_cache bakes_run=0 plan~lighting")
# A corrupt cache file is re-baked with a warning, not an error.
sphbasis_render_test(cache_corrupt "warning: [^\n]*unreadable cache file.*render-report-ok"
  "rm -rf render_corrupt && \"${_render}\" render ${_rscenes}/tiny_sun.json --representations prt-vertex --rays 16 --out render_corrupt 2>/dev/null && for f in render_corrupt/cache/*.bin; do printf 'garbage' > $f; done && \"${_render}\" render ${_rscenes}/tiny_sun.json --representations prt-vertex --rays 16 --out render_corrupt 2>&1 >/dev/null | grep warning; python3 ${_check_report} render_corrupt bakes_loaded=0")
# One flipped bit in a cache entry's results (a file of the right size and layout) is caught by
# its checksum (docs/bake-format.md): warned about and re-baked, never used.
sphbasis_render_test(cache_bit_flip "warning: [^\n]*unreadable cache file \\(sphbasis::render::read_bake_file\\(\\): expected the checksum to match, got a corrupt file\\); baking again.*render-report-ok"
  "rm -rf render_flip && \"${_render}\" render ${_rscenes}/tiny_sun.json --representations ao --rays 16 --out render_flip 2>/dev/null && for f in render_flip/cache/*.bin; do python3 -c \"import sys; p=sys.argv[1]; b=bytearray(open(p,'rb').read()); b[len(b)-30]^=1; open(p,'wb').write(b)\" $f; done && \"${_render}\" render ${_rscenes}/tiny_sun.json --representations ao --rays 16 --out render_flip 2>&1 >/dev/null | grep warning; python3 ${_check_report} render_flip bakes_loaded=0")
# A render reuses what `sphbasis bake` stored for the same settings (docs/bake-format.md, "Reuse
# by render"): with --bake it runs no bake, every bake it reads comes from the bake's directory
# (the plan says so), the values are byte for byte those of the same render baking itself, and
# so are its images (check_bake_reuse.py). Vertex PRT transfer with a bounce and texel ao + bent.
set(_check_reuse ${CMAKE_CURRENT_SOURCE_DIR}/cli/check_bake_reuse.py)
sphbasis_render_test(bake_reuse "plan-ok\nbake-reuse-ok: 4 bakes, [0-9]+ points, 2 images identical\nrender-report-ok"
  "rm -rf reuse_b reuse_r reuse_f && \"${_render}\" bake ${_rscenes}/tiny_sun.json --quantities transfer --bands 3 --bounces 1 --rays 16 --out reuse_b 2>/dev/null && \"${_render}\" bake ${_rscenes}/tiny_sun.json --quantities ao,bent --target texels:8 --rays 16 --out reuse_b 2>/dev/null && \"${_render}\" render ${_rscenes}/tiny_sun.json --representations prt-vertex,ao --lightmap-size 8 --rays 16 --bake reuse_b --out reuse_r 2>reuse_r.err && grep -q 'reuse: 4 of 4 bakes from reuse_b' reuse_r.err && grep -q '4 from --bake reuse_b' reuse_r.err && echo plan-ok && \"${_render}\" render ${_rscenes}/tiny_sun.json --representations prt-vertex,ao --lightmap-size 8 --rays 16 --out reuse_f 2>/dev/null && python3 ${_check_reuse} reuse_b reuse_r reuse_f && python3 ${_check_report} reuse_r bakes_run=0 bakes_loaded=4")
# A bake of other settings, of another scene, or none at all is refused before any work, with
# one line saying why; no output directory is created.
sphbasis_render_test(bake_reuse_settings "render: --bake reuse_s: none of its bakes has this render's settings \\(it holds vertex transfer: bands 3, rays 16, bounces 1, seed 1; this render needs vertex transfer: bands 3, rays 16, bounces 1, seed 0\\); bake with these or drop --bake\nrefused-ok"
  "rm -rf reuse_s reuse_so && \"${_render}\" bake ${_rscenes}/tiny_sun.json --quantities transfer --bands 3 --bounces 1 --rays 16 --seed 1 --out reuse_s 2>/dev/null && ! \"${_render}\" render ${_rscenes}/tiny_sun.json --representations prt-vertex --rays 16 --bake reuse_s --out reuse_so 2>&1 >/dev/null && ! test -e reuse_so && echo refused-ok")
# An adaptive bake's entries carry its adaptive settings in their key: never taken for the fixed
# count render bakes (named in the refusal).
sphbasis_render_test(bake_reuse_adaptive "render: --bake reuse_a: none of its bakes has this render's settings \\(it holds vertex transfer: bands 3, rays 16, bounces 1, seed 0, adaptive to 64 rays; this render needs vertex transfer: bands 3, rays 16, bounces 1, seed 0\\); bake with these or drop --bake\nrefused-ok"
  "rm -rf reuse_a reuse_ao && \"${_render}\" bake ${_rscenes}/tiny_sun.json --quantities transfer --bands 3 --bounces 1 --rays 16 --target-error 0.05 --max-rays 64 --out reuse_a 2>/dev/null && grep -q '\"render_cache\"' reuse_a/bake.json && ! \"${_render}\" render ${_rscenes}/tiny_sun.json --representations prt-vertex --rays 16 --bake reuse_a --out reuse_ao 2>&1 >/dev/null && ! test -e reuse_ao && echo refused-ok")
sphbasis_render_test(bake_reuse_scene "render: --bake reuse_o: its bakes are of another scene \\(other geometry, albedos or lighting\\); bake this scene or drop --bake\nrefused-ok"
  "rm -rf reuse_o reuse_oo && \"${_render}\" bake ${_rscenes}/tiny_sun.json --quantities transfer --bands 3 --bounces 1 --rays 16 --out reuse_o 2>/dev/null && ! \"${_render}\" render ${_rscenes}/tiny_sphere.json --representations prt-vertex --rays 16 --bake reuse_o --out reuse_oo 2>&1 >/dev/null && ! test -e reuse_oo && echo refused-ok")
sphbasis_render_test(bake_reuse_empty "render: --bake reuse_e: no bakes there \\(expected reuse_e/cache/<key>.bin, written by `sphbasis bake --out reuse_e`\\)\nrefused-ok"
  "rm -rf reuse_e reuse_eo && mkdir reuse_e && ! \"${_render}\" render ${_rscenes}/tiny_sun.json --representations prt-vertex --rays 16 --bake reuse_e --out reuse_eo 2>&1 >/dev/null && ! test -e reuse_eo && echo refused-ok")
# --no-cache keeps no cache directory.
sphbasis_render_test(no_cache "no-cache-ok"
  "rm -rf render_nocache && \"${_render}\" render ${_rscenes}/tiny_sun.json --representations ao --rays 16 --no-cache --out render_nocache 2>/dev/null && ! test -e render_nocache/cache && echo no-cache-ok")
# "all" on a scene without a shiny material: the specular comparison is skipped (and said so).
sphbasis_render_test(all_without_specular "render-report-ok"
  "rm -rf render_all && \"${_render}\" render ${_rscenes}/tiny_sun.json --rays 16 --lightmap-size 8 --out render_all 2>/dev/null && python3 ${_check_report} render_all rows=51 plan~skipped effect!~specular")
# The specular comparison on a bumpy normal map under minification: Toksvig is closer to the
# supersampled reference than the aliased lobe.
sphbasis_render_test(specular_toksvig "render-report-ok"
  "rm -rf render_spec && \"${_render}\" render ${_rscenes}/tiny_shiny.json --representations specular-toksvig,specular-aliased --out render_spec 2>/dev/null && test -s render_spec/specular_reference.png && python3 ${_check_report} render_spec rows=2 less=specular-toksvig:specular-aliased")
# Deterministic whatever the thread count: the reference's EXR is byte-identical.
sphbasis_render_test(threads_deterministic "deterministic-ok"
  "rm -rf render_t1 render_t2 && \"${_render}\" render ${_rscenes}/tiny_sun.json --representations irradiance-sh9 --threads 1 --out render_t1 2>/dev/null && \"${_render}\" render ${_rscenes}/tiny_sun.json --representations irradiance-sh9 --threads 2 --out render_t2 2>/dev/null && cmp render_t1/reference.exr render_t2/reference.exr && cmp render_t1/irradiance-sh9.exr render_t2/irradiance-sh9.exr && echo deterministic-ok")
# All or none: a failure during the run (the cache directory is a file, so storing a bake
# fails) leaves no image and no report.
sphbasis_render_test(all_or_none "all-or-none-ok"
  "rm -rf render_aon && mkdir render_aon && : > render_aon/cache && ! \"${_render}\" render ${_rscenes}/tiny_sun.json --representations ao --rays 16 --out render_aon 2>/dev/null && test -z \"$(ls render_aon | grep -v '^cache$')\" && echo all-or-none-ok")

# White furnace on meshes as files deliver them: the open boxes of data/scenes/furnace (albedo 1,
# constant unit sky; OBJ with flat normals, without normals, with normals smoothed across the
# edges, with mixed winding with and without normals). The reference (unbounded bounces) is 1
# at every pixel, and so is irradiance-sh9 (unshadowed, exact for a constant sky): their relative
# MSE is the reference's noise alone (2e-4 to 6e-4 at 64 spp). A reference losing light where
# the shading normals tilt below the faces, or on faces wound against their normals, read 0.84
# or 0.30 on the box (a relative MSE of order 1e-2 over the image).
foreach(_v flat nonormals smooth mixed mixed_nonormals)
  sphbasis_render_test(furnace_obj_${_v} "render-report-ok"
    "rm -rf render_furnace_${_v} && \"${_render}\" render ${CMAKE_CURRENT_SOURCE_DIR}/data/scenes/furnace/open_box_${_v}.json --representations irradiance-sh9 --spp 64 --out render_furnace_${_v} && python3 ${_check_report} render_furnace_${_v} rows=1 judged_min=1 max_rel_mse=irradiance-sh9:0.005")
endforeach()

# The metrics on the committed scenes at a small size: every metric of every row finite and in
# its range and the ranks in the order of FLIP (check_render_report.py checks both always), the
# floored relative MSE sane (with all representations at 48x36 the earlier rel_mse reads 5e7 on
# the Cornell box and 1.6e6 on the aliased specular row, where the reference is dark; the floored
# one 71 and 1.2e3), FLIP ordering what the scenes are for: the dark, interreflecting Cornell box and the grazing
# specular panel.
set(_scenes ${PROJECT_SOURCE_DIR}/scenes)
sphbasis_render_test(metrics_cornell "render-report-ok"
  "rm -rf render_m_cornell && \"${_render}\" render ${_scenes}/cornell.json --representations irradiance-sh9,ao,prt-vertex,lightmap-sh9,volume --width 32 --height 32 --spp 16 --rays 16 --lightmap-size 8 --out render_m_cornell 2>/dev/null && python3 ${_check_report} render_m_cornell rows=5 max_metric=rel_mse_floored:10 less_flip=lightmap-sh9:irradiance-sh9")
# The engine bases (ambient cube and dice, SG9, L1 with the Geomerics reconstruction, ZH3): as
# probes and as tangent-space lightmaps (SG9 by each solver); every metric finite and in range.
# Ambient Dice over the faces: the report's bytes per element (30 and 10 floats a channel, the
# YCoCg variant's 30 + 10 + 10, the Bezier volume's 36 a channel).
sphbasis_render_test(metrics_engine_bases "render-report-ok"
  "rm -rf render_m_engine && \"${_render}\" render ${_scenes}/cornell.json --representations volume,volume-ambient-cube,volume-ambient-dice,volume-sh-l1-nonlinear,volume-zh3-hallucinate,volume-zh3,volume-sg9,lightmap-ambient-cube5,lightmap-ambient-dice12,lightmap-sg9,lightmap-sg9-nnls,lightmap-sg9-running,lightmap-zh3,lightmap-zh3-hallucinate,lightmap-sh-l1-nonlinear,volume-ambient-dice-bezier,lightmap-ambient-dice-bezier30,lightmap-ambient-dice-linear10,lightmap-ambient-dice-ycocg --width 32 --height 32 --spp 16 --rays 16 --lightmap-size 8 --out render_m_engine 2>/dev/null && python3 ${_check_report} render_m_engine rows=19 max_metric=rel_mse_floored:10 bytes=lightmap-ambient-dice-bezier30:360 bytes=lightmap-ambient-dice-linear10:120 bytes=lightmap-ambient-dice-ycocg:200 bytes=volume-ambient-dice-bezier:432")
sphbasis_render_test(metrics_specular_bumps "render-report-ok"
  "rm -rf render_m_spec && \"${_render}\" render ${_scenes}/specular_bumps.json --representations specular-toksvig,specular-aliased,irradiance-sh9 --width 40 --height 30 --spp 16 --specular-ss 4 --out render_m_spec 2>/dev/null && python3 ${_check_report} render_m_spec rows=3 max_metric=rel_mse_floored:1e3 less_flip=specular-toksvig:specular-aliased")
# Every committed scene that needs no downloaded data, with all of its representations at a
# tiny size (about 0.6 s each): every metric of every row finite and in range (scan.json reads
# out/data/bunny.off, which scripts/render extracts from Debian's libcgal-demo: not run here).
foreach(_s furnace sphere_sun normal_wall)
  sphbasis_render_test(metrics_all_${_s} "render-report-ok"
    "rm -rf render_all_${_s} && \"${_render}\" render ${_scenes}/${_s}.json --representations all --width 32 --height 24 --spp 16 --rays 16 --lightmap-size 8 --out render_all_${_s} 2>/dev/null && python3 ${_check_report} render_all_${_s}")
endforeach()
# One image loop, equal sampling: on the normal-mapped wall the six representations rank alike at
# 96x72 and 320x240, and prt-texel (which ignores the normal map) ranks below lightmap-sh9 at both
# (when the representations had one camera ray per pixel centre against the reference's 64
# jittered samples, prt-texel ranked first at 96x72, FLIP 0.082 against 0.173 for lightmap-sh9,
# and 4 of the 15 pairs changed order: the test failed). Two pairs may change order, each for a
# reason the images show, not the sampling: lightmap-sh4 and lightmap-hbasis6 are a tie (FLIP
# within 0.6% at both sizes; the check allows 2%), and prt-texel and irradiance-sh9
# cross near 160x120 (FLIP 0.082 / 0.085 at 96x72, 0.082 / 0.082 at 160x120, 0.10 / 0.078 at
# 320x240): the bumps prt-texel misses are averaged within the pixels of the small image, the
# sun's shadow irradiance-sh9 misses is not. The bakes of the first run are reused by the
# second (the cache). About 9 s of CPU time.
set(_check_ranking ${CMAKE_CURRENT_SOURCE_DIR}/cli/check_ranking.py)
set(_six irradiance-sh9,lightmap-sh4,lightmap-sh9,lightmap-hbasis6,lightmap-hl2,prt-texel)
sphbasis_render_test(ranking_normal_wall "ranking-ok"
  "rm -rf render_rank render_rank_small.json && \"${_render}\" render ${_scenes}/normal_wall.json --representations ${_six} --width 96 --height 72 --spp 64 --rays 64 --out render_rank 2>/dev/null && cp render_rank/report.json render_rank_small.json && \"${_render}\" render ${_scenes}/normal_wall.json --representations ${_six} --width 320 --height 240 --spp 64 --rays 64 --out render_rank 2>/dev/null && python3 ${_check_ranking} render_rank_small.json render_rank/report.json below=prt-texel:lightmap-sh9 tie=lightmap-sh4:lightmap-hbasis6:0.02 crossing=prt-texel:irradiance-sh9")

# report.html sorts in a real browser: a click on a column header (headless chromium, see
# check_report_sort_browser.py); skipped, saying so, where chromium is not installed.
set(_check_sort ${CMAKE_CURRENT_SOURCE_DIR}/cli/check_report_sort_browser.py)
sphbasis_render_test(report_sorts_in_browser "browser-sort-ok"
  "rm -rf render_sort && \"${_render}\" render ${_rscenes}/tiny_shiny.json --representations specular-toksvig,specular-aliased,irradiance-sh9 --out render_sort 2>/dev/null && python3 ${_check_sort} render_sort")
set_tests_properties(render_report_sorts_in_browser PROPERTIES
                     SKIP_REGULAR_EXPRESSION "browser-check-skipped")

# The committed scenes' verdict (tools/plot/render_summary.py, label cli, no rendering): its
# tables on a hand-made fixture equal the ones worked out by hand (check_render_summary.py).
set(_summary ${CMAKE_CURRENT_SOURCE_DIR}/../tools/plot/render_summary.py)
sphbasis_cli_script(render_summary "render-summary-ok"
  "/usr/bin/python3 ${CMAKE_CURRENT_SOURCE_DIR}/cli/check_render_summary.py ${_summary} ${CMAKE_CURRENT_SOURCE_DIR}/data/render_summary_fixture.json render_summary_work")
# The tables in README.md ("On the committed scenes") and docs/rendering.md are the ones
# render_summary.py makes of the committed run (tests/data/render_readme_run.json), so their
# numbers trace to that run.
sphbasis_cli_script(render_summary_readme "checked [0-9]+ blocks of [^\n]*README.md[^\n]*\n[^\n]*checked [0-9]+ blocks of [^\n]*rendering.md"
  "/usr/bin/python3 ${_summary} --check ${PROJECT_SOURCE_DIR}/README.md --check ${PROJECT_SOURCE_DIR}/docs/rendering.md ${CMAKE_CURRENT_SOURCE_DIR}/data/render_readme_run.json")
