# Tests of the `sphbasis` command-line tool (label "cli"): each runs the built binary and checks
# its output or its exit status.
set(_cli $<TARGET_FILE:sphbasis_cli>)
function(sphbasis_cli_test name regex)
  add_test(NAME cli_${name} COMMAND ${_cli} ${ARGN})
  set_tests_properties(cli_${name} PROPERTIES PASS_REGULAR_EXPRESSION "${regex}" LABELS cli)
endfunction()
function(sphbasis_cli_fails name)
  add_test(NAME cli_${name} COMMAND ${_cli} ${ARGN})
  set_tests_properties(cli_${name} PROPERTIES WILL_FAIL TRUE LABELS cli)
endfunction()

# eval: y_{2000,-1234}(-0.6, 0, 0.8) = 0 exactly (sin(1234 pi) = 0), both option spellings.
sphbasis_cli_test(eval_lm_equals "^\\{\"basis\":\"sh\",\"dir\":\\[-0.59999999999999998,0,0.80000000000000004\\],\"values\":\\[0\\]\\}"
                  eval --basis sh --lm=2000,-1234 --dir=-0.6,0,0.8)
sphbasis_cli_test(eval_lm_separate "\"values\":\\[0\\]" eval --basis sh --lm 2000,-1234 --dir -0.6,0,0.8)
# y_11 at +x is sqrt(3/(4 pi)) = 0.48860251190291992.
sphbasis_cli_test(eval_coeffs "\"values\":\\[0.28209479177387814,0,0,0.48860251190291992\\]"
                  eval --basis sh --coeffs 4 --dir 1,0,0)
sphbasis_cli_test(eval_two_dirs "values.*\n.*values" eval --basis sh --coeffs 1 --dir 1,0,0 0,1,0)
sphbasis_cli_fails(eval_unknown_basis eval --basis nope --coeffs 4 --dir 0,0,1)
sphbasis_cli_fails(eval_bad_size eval --basis sh --coeffs 5 --dir 0,0,1)
sphbasis_cli_fails(eval_zero_dir eval --basis sh --coeffs 4 --dir 0,0,0)
sphbasis_cli_fails(eval_bad_lm eval --basis sh --lm 2,3 --dir 0,0,1)
sphbasis_cli_fails(eval_no_dirs eval --basis sh --coeffs 4)
sphbasis_cli_fails(eval_unknown_option eval --basis sh --coeffs 4 --dir 0,0,1 --bogus 1)
sphbasis_cli_fails(unknown_command frobnicate)
add_test(NAME cli_eval_stdin
         COMMAND sh -c "printf '# comment\\n0 0 2\\n\\n1 0 0\\n' | \"$<TARGET_FILE:sphbasis_cli>\" eval --basis sh --coeffs 4 --dirs -")
set_tests_properties(cli_eval_stdin PROPERTIES LABELS cli
  PASS_REGULAR_EXPRESSION "\"dir\":\\[0,0,2\\],\"values\":\\[0.28209479177387814,0,0.48860251190291992,0\\]\\}\n.*\"dir\":\\[1,0,0\\]")
add_test(NAME cli_eval_stdin_malformed
         COMMAND sh -c "printf '0 0\\n' | \"$<TARGET_FILE:sphbasis_cli>\" eval --basis sh --coeffs 4 --dirs -")
set_tests_properties(cli_eval_stdin_malformed PROPERTIES LABELS cli WILL_FAIL TRUE)

# params (issue 5): a small run lists the DX10 cube map; bad options fail.
sphbasis_cli_test(params_small "cube_dx10" params --points 2000)
sphbasis_cli_fails(params_bad_points params --points 0)
sphbasis_cli_fails(params_bad_option params --bogus 1)
# eval for the hemispherical bases and their sizes.
sphbasis_cli_test(eval_hbasis_pole "\"values\":\\[0.398942280401432[0-9]*,0,0.69098829894267[0-9]*,0,0,0\\]"
                  eval --basis hbasis --coeffs 6 --dir 0,0,1)
sphbasis_cli_test(eval_zernike_lm "\"values\":\\[" eval --basis zernike --lm 2,-2 --dir 0.3,0.2,0.9)
sphbasis_cli_fails(eval_zernike_bad_size eval --basis zernike --coeffs 4 --dir 0,0,1)
sphbasis_cli_fails(eval_hl2_lm eval --basis hl2 --lm 1,0 --dir 0,0,1)
sphbasis_cli_fails(eval_hbasis_bad_size eval --basis hbasis --coeffs 5 --dir 0,0,1)
