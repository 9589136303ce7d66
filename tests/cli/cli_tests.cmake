# Tests of the `sphbasis` command-line tool (label "cli"): each runs the built binary and checks
# its output or its exit status.
set(_cli $<TARGET_FILE:sphbasis_cli>)
function(sphbasis_cli_test name regex)
  add_test(NAME cli_${name} COMMAND ${_cli} ${ARGN})
  set_tests_properties(cli_${name} PROPERTIES PASS_REGULAR_EXPRESSION "${regex}" LABELS cli)
endfunction()
# A shell script (sh -c) around the binary that passes when its output matches regex.
function(sphbasis_cli_script name regex script)
  add_test(NAME cli_${name} COMMAND sh -c "${script}")
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
sphbasis_cli_script(eval_stdin "\"dir\":\\[0,0,2\\],\"values\":\\[0.28209479177387814,0,0.48860251190291992,0\\]\\}\n.*\"dir\":\\[1,0,0\\]"
                    "printf '# comment\\n0 0 2\\n\\n1 0 0\\n' | \"$<TARGET_FILE:sphbasis_cli>\" eval --basis sh --coeffs 4 --dirs -")
add_test(NAME cli_eval_stdin_malformed
         COMMAND sh -c "printf '0 0\\n' | \"$<TARGET_FILE:sphbasis_cli>\" eval --basis sh --coeffs 4 --dirs -")
set_tests_properties(cli_eval_stdin_malformed PROPERTIES LABELS cli WILL_FAIL TRUE)

# params: a small run lists the DX10 cube map; bad options fail.
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

# Help: `--help` and `-h` of the top level and of every command exit 0 on stdout and list the
# options (CLI11 writes the help).
sphbasis_cli_test(help "Subcommands:.*eval.*imse.*params.*gaunt.*rotate" --help)
sphbasis_cli_test(help_short "Subcommands:.*eval.*imse.*params.*gaunt.*rotate" -h)
sphbasis_cli_test(eval_help "Usage: sphbasis eval.*--basis NAME.*--coeffs N.*--lm L,M.*--dir X,Y,Z.*--dirs" eval --help)
sphbasis_cli_test(eval_help_short "Usage: sphbasis eval.*--basis" eval -h)
sphbasis_cli_test(imse_help "Usage: sphbasis imse.*--protocol.*--signals N.*--seed S.*--json PATH.*--csv PATH.*--md PATH" imse --help)
sphbasis_cli_test(imse_help_short "Usage: sphbasis imse.*--signals" imse -h)
sphbasis_cli_test(params_help "Usage: sphbasis params.*--points N.*--json PATH.*--csv PATH.*--threads T.*--seed S.*--subtexel-bits B" params --help)
sphbasis_cli_test(params_help_short "Usage: sphbasis params.*--points" params -h)
sphbasis_cli_test(gaunt_help "Usage: sphbasis gaunt.*L1.*M1.*L2.*M2.*L3.*M3" gaunt --help)
sphbasis_cli_test(gaunt_help_short "Usage: sphbasis gaunt.*L1" gaunt -h)
sphbasis_cli_test(rotate_help "Usage: sphbasis rotate.*--bands N.*--quat W,X,Y,Z.*--coeffs C0,C1" rotate --help)
sphbasis_cli_test(rotate_help_short "Usage: sphbasis rotate.*--bands" rotate -h)
# Help is not an error: exit status 0 (a pass regex alone would not check it).
sphbasis_cli_script(help_exit_codes "help-ok"
                    "b=\"$<TARGET_FILE:sphbasis_cli>\"; for a in --help -h; do $b $a >/dev/null || exit 1; for c in eval imse params gaunt rotate; do $b $c $a >/dev/null || exit 1; done; done; echo help-ok")
# Bad input: one line "sphbasis <command>: ..." on stderr and exit status 2.
sphbasis_cli_script(bad_input_exit_2 "exit2-ok"
                    "b=\"$<TARGET_FILE:sphbasis_cli>\"; $b imse --signals abc 2>err.txt; s=$?; test $s -eq 2 && test $(wc -l < err.txt) -eq 1 && grep -q '^sphbasis imse: --signals: expected an integer' err.txt && $b gaunt 1 x 1 0 0 0 2>/dev/null; test $? -eq 2 && $b frobnicate 2>/dev/null; test $? -eq 2 && $b 2>/dev/null; test $? -eq 2 && echo exit2-ok")
# gaunt and rotate: a value and an error each.
sphbasis_cli_test(gaunt_value "^0.21850968611841581\n$" gaunt 1 1 1 -1 2 -2)
sphbasis_cli_fails(gaunt_bad_m gaunt 1 2 1 0 0 0)
sphbasis_cli_test(rotate_value "^\\{\"bands\":2,\"quat\":\\[0.70710678118654757,0,0,0.70710678118654757\\],\"coeffs\":\\[1,1,0,0\\]\\}\n$"
                  rotate --bands 2 --quat 0.70710678118654752,0,0,0.70710678118654752 --coeffs 1,0,0,1)
sphbasis_cli_fails(rotate_zero_quat rotate --bands 2 --quat 0,0,0,0 --coeffs 1,0,0,1)
# One number grammar: no octal (010 is ten), no hex.
sphbasis_cli_test(params_decimal_only "\n10 points, 1 threads" params --points 010 --threads 1)
sphbasis_cli_fails(params_hex params --points 0x10)
