# Tests of `sphbasis project` (label "cli"). Included by tests/CMakeLists.txt after
# cli_tests.cmake, whose helpers it uses. The maps are written by make_envmaps.py (a fixture, a
# few MB in the build tree, about a second); check_project.py runs the command and compares with
# closed forms, the known coefficients the maps were rendered from, and the engines' formulas.
set(_pm ${CMAKE_CURRENT_BINARY_DIR}/project_maps)
set(_py /usr/bin/python3)
add_test(NAME cli_project_maps
         COMMAND ${_py} ${CMAKE_CURRENT_SOURCE_DIR}/cli/make_envmaps.py ${_pm})
set_tests_properties(cli_project_maps PROPERTIES FIXTURES_SETUP project_maps LABELS cli)
foreach(mode constant known layouts irradiance rotate window threejs filament unity frames inputs out)
  add_test(NAME cli_project_${mode}
           COMMAND ${_py} ${CMAKE_CURRENT_SOURCE_DIR}/cli/check_project.py
                   $<TARGET_FILE:sphbasis_cli> ${_pm} ${mode})
  set_tests_properties(cli_project_${mode} PROPERTIES PASS_REGULAR_EXPRESSION
                       "project-${mode}-ok" FIXTURES_REQUIRED project_maps LABELS cli)
endforeach()

# Bad input: one line on stderr, non-zero exit, nothing written.
function(project_bad name regex)
  sphbasis_cli_bad(project_${name} "project: ${regex}" project ${ARGN})
  set_tests_properties(cli_project_${name} PROPERTIES FIXTURES_REQUIRED project_maps)
endfunction()
project_bad(missing_file "cannot read '.*nope.exr': No such file" ${_pm}/nope.exr)
project_bad(not_an_image "cannot read .*: Image not of any known type" ${_pm}/bad_text.exr.txt)
project_bad(cross_aspect ".*--layout cross expects 4:3 .* got 96 x 96" --layout cross ${_pm}/bad_square.exr)
project_bad(faces_unequal "six square faces of one size; face -Z .* is 8 x 8"
            --layout faces ${_pm}/const_face_px.exr ${_pm}/const_face_nx.exr ${_pm}/const_face_py.exr
            ${_pm}/const_face_ny.exr ${_pm}/const_face_pz.exr ${_pm}/bad_face_small.exr)
project_bad(faces_count "--layout faces: expected six face files" --layout faces ${_pm}/const_face_px.exr)
project_bad(nan_texel "pixel \\(7, 5\\) channel G is nan; expected finite radiance" ${_pm}/bad_nan.exr)
project_bad(unknown_format "--format: expected json, cpp, glsl, hlsl, unity, threejs or filament, got 'xml'"
            ${_pm}/const_equirect.exr --format xml)
project_bad(unknown_layout "--layout: expected equirect, cross or faces" ${_pm}/const_equirect.exr --layout octa)
project_bad(bad_window "--window: expected none, auto or sloan:X" ${_pm}/const_equirect.exr --window hann)
project_bad(unknown_frame "--frame: expected sphbasis, threejs, filament or unity, got 'unreal'"
            ${_pm}/const_equirect.exr --frame unreal)
project_bad(bad_sloan "--window sloan:X: expected a finite number" ${_pm}/const_equirect.exr --window sloan:x)
project_bad(bad_quat "--rotate: expected four numbers" ${_pm}/const_equirect.exr --rotate 1,0,0)
project_bad(zero_quat "--rotate: expected a non-zero quaternion" ${_pm}/const_equirect.exr --rotate 0,0,0,0)
project_bad(bands_and_coeffs "give --bands N or --coeffs N, not both" ${_pm}/const_equirect.exr --bands 2 --coeffs 4)
project_bad(bad_coeffs "--coeffs: basis 'sh' expects" ${_pm}/const_equirect.exr --coeffs 5)
project_bad(unknown_basis "--basis: .*unknown basis 'nope'" ${_pm}/const_equirect.exr --basis nope --coeffs 4)
project_bad(engine_bands "--format unity: the engine holds 3 bands" ${_pm}/const_equirect.exr --bands 4 --format unity)
project_bad(threejs_irradiance "--format threejs: SphericalHarmonics3 holds radiance"
            ${_pm}/const_equirect.exr --irradiance --format threejs)
project_bad(hemi_window "--irradiance, --window and --rotate work on SH"
            ${_pm}/const_equirect.exr --basis hsh --coeffs 4 --window auto)
# A failed run leaves no output file behind.
sphbasis_cli_script(project_no_partial "no-partial-ok"
                    "rm -f ${_pm}/partial.json; ! \"${_cli}\" project ${_pm}/bad_nan.exr --out ${_pm}/partial.json 2>/dev/null && test ! -e ${_pm}/partial.json && echo no-partial-ok")
set_tests_properties(cli_project_no_partial PROPERTIES FIXTURES_REQUIRED project_maps)
# A committed real map (data/envmaps, CC0): at 5 bands its radiance rings below zero, and the
# auto window finds a lambda > 0 with a certified non-negative lower bound.
sphbasis_cli_test(project_real_auto_window
                  "\"window\":\\{\"kind\":\"auto\",\"certified_lower_bound\":[0-9][^,]*,\"achieved\":true,\"relative_l2_change\":[^,]*,\"of\":\"radiance\",\"lambda\":0\\.[0-9]*[1-9]"
                  project ${PROJECT_SOURCE_DIR}/data/envmaps/sunset.exr --bands 5 --window auto)
