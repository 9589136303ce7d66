# Tests of how the `sphbasis` commands write their outputs (tools/support/output_file.hpp): by
# the kind of the path (a symlink written through, a device, FIFO or standard output written
# directly and never replaced, a directory in the way refused before any work), all or none per
# command, and interrupted runs (SIGINT, SIGTERM, SIGKILL) that leave every destination as it was.
# Included by tests/CMakeLists.txt after render_tests.cmake. Label "cli" for runs that trace no
# rays, "bake" and "render" for the interrupted runs. Each test works in its own directory.
set(_out_b $<TARGET_FILE:sphbasis_cli>)
set(_out_scenes ${CMAKE_CURRENT_SOURCE_DIR}/data/scenes)
set(_out_interrupt ${CMAKE_CURRENT_SOURCE_DIR}/cli/check_interrupt.py)
set(_params "params --points 2000 --threads 1")

# A symlink given as --json stays a link; its target gets the JSON.
sphbasis_cli_script(output_symlink "symlink-ok"
  "d=out_symlink; rm -rf $d; mkdir $d && echo old > $d/target.json && ln -s target.json $d/link.json && \"${_out_b}\" ${_params} --json $d/link.json >/dev/null && test -L $d/link.json && grep -q '\"experiment\":\"params\"' $d/target.json && test $(ls -A $d | wc -l) -eq 2 && echo symlink-ok")
# /dev/null is written, not replaced (run as root, a rename would have replaced the node).
sphbasis_cli_script(output_dev_null "dev-null-ok"
  "\"${_out_b}\" ${_params} --json /dev/null --csv /dev/null >/dev/null && test -c /dev/null && echo dev-null-ok")
# /dev/stdout: after the table, into a file (still a regular file, both there) or a pipe.
sphbasis_cli_script(output_dev_stdout "dev-stdout-ok"
  "d=out_stdout; rm -rf $d; mkdir $d && \"${_out_b}\" ${_params} --json /dev/stdout > $d/so.txt && test -f $d/so.txt && grep -q cube_dx10 $d/so.txt && tail -n 1 $d/so.txt | grep -q '^\\]}$' && test $(\"${_out_b}\" ${_params} --json /dev/stdout | grep -c '\"experiment\":\"params\"') -eq 1 && echo dev-stdout-ok")
# A FIFO is opened and written (a reader gets the JSON) and stays a FIFO.
sphbasis_cli_script(output_fifo "fifo-ok"
  "d=out_fifo; rm -rf $d; mkdir $d && mkfifo $d/f && (cat $d/f > $d/got &) && \"${_out_b}\" ${_params} --json $d/f >/dev/null && sleep 0.2 && test -p $d/f && grep -q '\"experiment\":\"params\"' $d/got && echo fifo-ok")
# A private copy of /dev/full (root only: mknod): not replaced, and ENOSPC fails the command
# with one line, leaving the other output (--csv) unwritten.
sphbasis_cli_script(output_char_device "chardev-(ok|skipped)"
  "d=out_chardev; rm -rf $d; mkdir $d && if ! mknod $d/full c 1 7 2>/dev/null; then echo chardev-skipped; exit 0; fi; \"${_out_b}\" ${_params} --json $d/full --csv $d/new.csv >/dev/null 2>$d/err; s=$?; test $s -eq 1 && test -c $d/full && test $(wc -l < $d/err) -eq 1 && grep -q \"^sphbasis params: cannot write '$d/full': No space left on device\" $d/err && ! test -e $d/new.csv && test $(ls -A $d | wc -l) -eq 2 && echo chardev-ok")
# A directory in the way: one line naming it, before any work (no table on stdout), nothing
# written.
sphbasis_cli_script(output_directory_in_way "dir-in-way-ok"
  "d=out_dir; rm -rf $d; mkdir -p $d/r.json && \"${_out_b}\" ${_params} --csv $d/new.csv --json $d/r.json >$d/stdout 2>$d/err; s=$?; test $s -eq 1 && ! test -s $d/stdout && test $(wc -l < $d/err) -eq 1 && grep -q \"^sphbasis params: cannot write '$d/r.json': Is a directory\" $d/err && test $(ls -A $d | wc -l) -eq 3 && echo dir-in-way-ok")
sphbasis_cli_script(render_output_directory_in_way "render-dir-in-way-ok"
  "d=out_rdir; rm -rf $d; mkdir -p $d/report.md && \"${_out_b}\" render ${_out_scenes}/render/tiny_sun.json --representations ao --rays 16 --out $d >/dev/null 2>$d.err; s=$?; test $s -eq 1 && test $(wc -l < $d.err) -eq 1 && grep -q \"^sphbasis render: cannot write '$d/report.md': Is a directory\" $d.err && test \"$(ls -A $d)\" = report.md && echo render-dir-in-way-ok")
# The same file twice is an error, before any work.
sphbasis_cli_script(output_same_file_twice "twice-ok"
  "d=out_twice; rm -rf $d; mkdir $d && ! \"${_out_b}\" ${_params} --json $d/x --csv $d/./x >$d.out 2>$d.err && ! test -s $d.out && grep -q 'the same file as the output' $d.err && test -z \"$(ls -A $d)\" && echo twice-ok")
# A mesh name too long (300 characters; names name output files): refused by the loader (16M rays per
# vertex would take minutes), and no output directory is created.
sphbasis_cli_script(bake_name_too_long "long-name-ok"
  "d=out_long; rm -rf $d $d.json && python3 -c 'import json, sys; s = json.load(open(sys.argv[1])); s[\"meshes\"][0][\"name\"] = \"a\" * 300; json.dump(s, open(sys.argv[2], \"w\"))' ${_out_scenes}/lone_sphere.json $d.json && \"${_out_b}\" bake $d.json --rays 16777216 --out $d 2>$d.err; s=$?; test $s -eq 1 && test $(wc -l < $d.err) -eq 1 && grep -q 'name: expected at most 200 characters' $d.err && ! test -e $d && echo long-name-ok")
set_tests_properties(cli_bake_name_too_long PROPERTIES TIMEOUT 30)
# The output directory is created only for a valid scene.
sphbasis_cli_script(bake_bad_scene_creates_nothing "nothing-created-ok"
  "d=out_badscene; rm -rf $d && ! \"${_out_b}\" bake ${_out_scenes}/bad/unknown_key.json --out $d 2>/dev/null && ! \"${_out_b}\" bake ${_out_scenes}/no_uvs.json --target texels:16 --out $d 2>/dev/null && ! test -e $d && echo nothing-created-ok")

# Interrupted runs: the signal arrives during the bake (16M rays per vertex); the old file stays,
# no new file appears, the staging is removed, and the run ends by the signal promptly.
sphbasis_script_test(bake output_sigterm "status 143 seconds 0\\.[0-9]+ staging-left 0\nsigterm-ok"
  "d=out_sigterm; rm -rf $d; mkdir $d && echo old > $d/ground.ply && python3 ${_out_interrupt} TERM $d \"${_out_b}\" bake ${_out_scenes}/sphere_over_quad.json --rays 16777216 --out $d && test \"$(cat $d/ground.ply)\" = old && test \"$(ls -A $d)\" = ground.ply && echo sigterm-ok")
sphbasis_script_test(render output_sigint "status 130 seconds 0\\.[0-9]+ staging-left 0\nsigint-ok"
  "d=out_sigint; rm -rf $d; mkdir $d && echo old > $d/report.json && python3 ${_out_interrupt} INT $d \"${_out_b}\" render ${_out_scenes}/render/tiny_sun.json --representations ao --rays 1048576 --out $d && test \"$(cat $d/report.json)\" = old && test -z \"$(ls -A $d | grep -v -e '^report.json$' -e '^cache$')\" && echo sigint-ok")
# A new output directory is removed again when the run is interrupted.
sphbasis_script_test(bake output_sigterm_new_dir "status 143 seconds 0\\.[0-9]+ staging-left 0\nnew-dir-removed-ok"
  "d=out_sigterm_new; rm -rf $d && python3 ${_out_interrupt} TERM $d \"${_out_b}\" bake ${_out_scenes}/sphere_over_quad.json --rays 16777216 --out $d && ! test -e $d && echo new-dir-removed-ok")
# SIGKILL leaves only the staging directory; the next run into the same directory removes it.
sphbasis_script_test(bake output_sigkill_stale "status 137 seconds 0\\.[0-9]+ staging-left 1\nstale-removed-ok"
  "d=out_sigkill; rm -rf $d; mkdir $d && python3 ${_out_interrupt} KILL $d \"${_out_b}\" bake ${_out_scenes}/sphere_over_quad.json --rays 16777216 --out $d && test $(ls -A $d | wc -l) -eq 1 && \"${_out_b}\" bake ${_out_scenes}/lone_sphere.json --rays 16 --out $d 2>/dev/null && test -z \"$(ls -A $d | grep staging)\" && test -s $d/mesh0.ply && test -s $d/bake.json && echo stale-removed-ok")
foreach(_t bake_output_sigterm render_output_sigint bake_output_sigterm_new_dir bake_output_sigkill_stale)
  set_tests_properties(${_t} PROPERTIES TIMEOUT 120)
endforeach()
