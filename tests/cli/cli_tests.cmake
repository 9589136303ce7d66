# Tests of the `sphbasis` command-line tool (label "cli"): each runs the built binary and checks
# its output or its exit status.
set(_cli $<TARGET_FILE:sphbasis_cli>)
function(sphbasis_cli_test name regex)
  add_test(NAME cli_${name} COMMAND ${_cli} ${ARGN})
  set_tests_properties(cli_${name} PROPERTIES PASS_REGULAR_EXPRESSION "${regex}" LABELS cli)
endfunction()
# A shell script (sh -c) that passes when its output matches regex: test <label>_<name>, with
# label <label> ("cli" for option and input checks, "bake" and "render" for runs that trace rays).
function(sphbasis_script_test label name regex script)
  add_test(NAME ${label}_${name} COMMAND sh -c "${script}")
  set_tests_properties(${label}_${name} PROPERTIES PASS_REGULAR_EXPRESSION "${regex}"
                       LABELS ${label})
endfunction()
# A shell script (sh -c) around the binary that passes when its output matches regex.
function(sphbasis_cli_script name regex script)
  sphbasis_script_test(cli ${name} "${regex}" "${script}")
endfunction()
# Bad input: passes when `sphbasis ARGN...` exits non-zero with exactly one line on stderr (and
# nothing on stdout) matching "sphbasis <what>" (what: the command's name, then ": " and the
# message's regex). Test cli_<name>.
function(sphbasis_cli_bad name what)
  string(JOIN " " _args ${ARGN})
  add_test(NAME cli_${name}
           COMMAND sh -c "err=$(\"${_cli}\" ${_args} 2>&1 >/dev/null); rc=$?; n=$(printf '%s\\n' \"$err\" | wc -l); if [ $rc -ne 0 ] && [ $n -eq 1 ]; then echo \"bad-input-ok: $err\"; else echo \"rc=$rc lines=$n: $err\"; fi")
  set_tests_properties(cli_${name} PROPERTIES
                       PASS_REGULAR_EXPRESSION "bad-input-ok: sphbasis ${what}"
                       LABELS cli)
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

# ---------------------------------------------------------------------------------------------
# No success that lost data: standard output full (/dev/full) or closed (>&-) is exit status 1
# with one line "sphbasis <command>: cannot write standard output..." for every command.
# sphbasis_cli_lost_output(name redirect command args...): runs `sphbasis command args` with
# standard output redirected by `redirect` and checks the status and the one-line message.
function(sphbasis_cli_lost_output name redirect command)
  list(JOIN ARGN " " _args)
  sphbasis_cli_script(${name} "lost-output-ok"
    "\"$<TARGET_FILE:sphbasis_cli>\" ${command} ${_args} ${redirect} 2>${name}.err; s=$?; test $s -eq 1 && test $(wc -l < ${name}.err) -eq 1 && grep -q '^sphbasis ${command}: cannot write standard output' ${name}.err && echo lost-output-ok")
  set_tests_properties(cli_${name} PROPERTIES TIMEOUT 60)
endfunction()
foreach(_how full closed)
  if(_how STREQUAL "full")
    set(_redirect ">/dev/full")
  else()
    set(_redirect ">&-")
  endif()
  sphbasis_cli_lost_output(stdout_${_how}_eval "${_redirect}" eval --basis sh --coeffs 4 --dir 0,0,1)
  sphbasis_cli_lost_output(stdout_${_how}_gaunt "${_redirect}" gaunt 1 1 1 -1 2 -2)
  sphbasis_cli_lost_output(stdout_${_how}_rotate "${_redirect}" rotate --bands 2 --quat 1,0,0,0 --coeffs 1,0,0,1)
  sphbasis_cli_lost_output(stdout_${_how}_params "${_redirect}" params --points 1000 --threads 1)
  sphbasis_cli_lost_output(stdout_${_how}_imse "${_redirect}" imse --signals 20)
endforeach()
# The reason is named: ENOSPC for /dev/full, and "closed" before any work for >&-.
sphbasis_cli_script(stdout_full_message "sphbasis gaunt: cannot write standard output: No space left on device"
                    "\"$<TARGET_FILE:sphbasis_cli>\" gaunt 1 1 1 -1 2 -2 >/dev/full")
sphbasis_cli_script(stdout_closed_message "sphbasis params: cannot write standard output: it is closed"
                    "\"$<TARGET_FILE:sphbasis_cli>\" params --points 1000 >&-")
# Help is output too.
sphbasis_cli_lost_output(stdout_full_help ">/dev/full" eval --help)
# Endless input into a full output stops within one buffer (the test's timeout would catch a
# run that reads on).
sphbasis_cli_script(stdout_full_streaming "streaming-ok"
                    "yes '0 0 1' | \"$<TARGET_FILE:sphbasis_cli>\" eval --basis sh --coeffs 4 --dirs - >/dev/full 2>streaming.err; s=$?; test $s -eq 1 && grep -q 'cannot write standard output' streaming.err && echo streaming-ok")
set_tests_properties(cli_stdout_full_streaming PROPERTIES TIMEOUT 30)

# Standard input lines are bounded (1 MiB): /dev/zero is an error at once, status 2.
sphbasis_cli_script(eval_stdin_zero "zero-ok"
                    "\"$<TARGET_FILE:sphbasis_cli>\" eval --basis sh --coeffs 1 --dirs - </dev/zero >/dev/null 2>zero.err; s=$?; test $s -eq 2 && test $(wc -l < zero.err) -eq 1 && grep -q '^sphbasis eval: standard input line 1: longer than 1048576 bytes' zero.err && echo zero-ok")
set_tests_properties(cli_eval_stdin_zero PROPERTIES TIMEOUT 30)
# A line of NUL bytes is a one-line message with the bytes escaped and shortened.
sphbasis_cli_script(eval_stdin_nul "nul-ok"
                    "head -c 5000 /dev/zero | \"$<TARGET_FILE:sphbasis_cli>\" eval --basis sh --coeffs 1 --dirs - 2>nul.err; s=$?; test $s -eq 2 && test $(wc -c < nul.err) -lt 300 && grep -q 'x00.*5000 bytes' nul.err && echo nul-ok")
# The last line needs no newline.
sphbasis_cli_script(eval_stdin_no_newline "\"dir\":\\[0,0,1\\],\"values\":\\[0.28209479177387814\\]\\}\n.*\"dir\":\\[1,0,0\\]"
                    "printf '0 0 1\\n1 0 0' | \"$<TARGET_FILE:sphbasis_cli>\" eval --basis sh --coeffs 1 --dirs -")
# JSON lines: eval's own output fed back, and arrays.
sphbasis_cli_script(eval_stdin_json "\"dir\":\\[0.5,0,-2\\],\"values\":\\[0.28209479177387814,0,-0.47401"
                    "b=\"$<TARGET_FILE:sphbasis_cli>\"; $b eval --basis sh --coeffs 1 --dir 0.5,0,-2 | $b eval --basis sh --coeffs 4 --dirs -")
sphbasis_cli_script(eval_stdin_json_array "\"dir\":\\[1,2,3\\]"
                    "printf '[1, 2, 3]\\n' | \"$<TARGET_FILE:sphbasis_cli>\" eval --basis sh --coeffs 1 --dirs -")
# Directions of any finite magnitude are scaled before they are normalised.
sphbasis_cli_test(eval_huge_dir "\"dir\":\\[9.9999999999999997e\\+199,0,0\\],\"values\":\\[0.28209479177387814,0,0,0.48860251190291992\\]"
                  eval --basis sh --coeffs 4 --dir 1e200,0,0)

# rotate --coeffs -: 100 bands (10000 coefficients, more than a command line holds) through a
# pipe: rotating by q and then by its conjugate gives the input back (to 1e-10; the rotation's
# own error at 100 bands is ~1e-13), and the second rotate reads the first's JSON line.
sphbasis_cli_script(rotate_stdin_round_trip "round-trip-ok"
                    "b=\"$<TARGET_FILE:sphbasis_cli>\"; awk 'BEGIN { for (i = 0; i < 10000; i++) printf \"%.17g%s\", sin(0.37 * i + 0.1) / (1 + i / 1000), (i % 7 == 6 ? \"\\n\" : \" \") }' > rt_in.txt && $b rotate --bands 100 --quat 0.3,0.5,-0.2,0.7 --coeffs - < rt_in.txt > rt_mid.json && $b rotate --bands 100 --quat 0.3,-0.5,0.2,-0.7 --coeffs - < rt_mid.json | sed 's/.*\"coeffs\":\\[//; s/\\].*//' | tr , '\\n' > rt_out.txt && tr ' ' '\\n' < rt_in.txt | grep . > rt_in1.txt && test $(wc -l < rt_out.txt) -eq 10000 && paste rt_in1.txt rt_out.txt | awk '{ d = $1 - $2; if (d < 0) d = -d; if (d > m) m = d } END { if (NR == 10000 && m < 1e-10) print \"round-trip-ok\"; else print \"max diff \" m }'")
sphbasis_cli_script(rotate_stdin_commas "\"coeffs\":\\[1,1,0,0\\]"
                    "printf '# comment\\n1,0\\n0 1\\n' | \"$<TARGET_FILE:sphbasis_cli>\" rotate --bands 2 --quat 0.70710678118654752,0,0,0.70710678118654752 --coeffs -")
sphbasis_cli_script(rotate_stdin_too_many "expected N\\^2 = 4 coefficients for --bands 2, got more"
                    "printf '1 2 3 4 5\\n' | \"$<TARGET_FILE:sphbasis_cli>\" rotate --bands 2 --quat 1,0,0,0 --coeffs -")
sphbasis_cli_script(rotate_stdin_too_few "expected N\\^2 = 4 coefficients for --bands 2, got 3"
                    "printf '1 2 3' | \"$<TARGET_FILE:sphbasis_cli>\" rotate --bands 2 --quat 1,0,0,0 --coeffs -")
sphbasis_cli_script(rotate_stdin_wrong_bands "\"bands\":3, expected 2 \\(--bands\\)"
                    "b=\"$<TARGET_FILE:sphbasis_cli>\"; $b rotate --bands 3 --quat 1,0,0,0 --coeffs 1,0,0,0,0,0,0,0,0 | $b rotate --bands 2 --quat 1,0,0,0 --coeffs -")

# Limits said before any allocation, with their reason (no bare std::bad_alloc).
sphbasis_cli_test(params_points_limit "^sphbasis params: --points: expected 1 <= N <= 100000000 \\(56 bytes of memory per point"
                  params --points 1000000000)
sphbasis_cli_test(eval_lm_range "^sphbasis eval: --lm: expected 0 <= L <= 8191 for basis 'sh'.*got L = 100000\n$"
                  eval --basis sh --lm 100000,0 --dir 0,0,1)
sphbasis_cli_test(eval_lm_range_hsh "--lm: expected 0 <= L <= 2047 for basis 'hsh'" eval --basis hsh --lm 3000,0 --dir 0,0,1)
sphbasis_cli_test(eval_lm_range_huge "--lm: expected 0 <= L <= 8191 for basis 'sh'.*got L = 9000000000000000000"
                  eval --basis sh --lm 9000000000000000000,0 --dir 0,0,1)
# One function of the largest degree without a table of 8192^2 values: under a 400 MB address
# space limit (the table alone would take 537 MB).
sphbasis_cli_script(eval_lm_max_small_memory "\"values\":\\[-?[1-9]"
                    "ulimit -v 400000; \"$<TARGET_FILE:sphbasis_cli>\" eval --basis sh --lm 8191,8191 --dir 1,0.001,0")

# ---------------------------------------------------------------------------------------------
# Outputs all or none: a bad second output path fails before the run and leaves an existing
# first output untouched (it used to be truncated to 0 bytes); a good run replaces both, with no
# temporary left behind.
sphbasis_cli_script(params_outputs_all_or_none "all-or-none-ok"
  "d=params_outputs.d; rm -rf $d; mkdir -p $d && echo keep > $d/old.json && \"$<TARGET_FILE:sphbasis_cli>\" params --points 2000 --threads 1 --json $d/old.json --csv /proc/no/such.csv >/dev/null 2>$d/err; s=$?; test $s -ne 0 && test \"$(cat $d/old.json)\" = keep && test $(wc -l < $d/err) -eq 1 && test -z \"$(ls -A $d | grep tmp)\" && echo all-or-none-ok")
sphbasis_cli_script(imse_outputs_all_or_none "all-or-none-ok"
  "d=imse_outputs.d; rm -rf $d; mkdir -p $d && echo keep > $d/old.json && \"$<TARGET_FILE:sphbasis_cli>\" imse --signals 2 --json $d/old.json --md $d/new.md --csv /proc/no/such.csv >/dev/null 2>$d/err; s=$?; test $s -ne 0 && test \"$(cat $d/old.json)\" = keep && test ! -e $d/new.md && test -z \"$(ls -A $d | grep tmp)\" && echo all-or-none-ok")
