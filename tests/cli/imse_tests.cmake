# Tests of `sphbasis imse` (label "cli"). Included by tests/CMakeLists.txt after cli_tests.cmake,
# whose helpers sphbasis_cli_test / sphbasis_cli_script / sphbasis_cli_fails it uses.

# A small paper run: prints the table with its seed; SH 9 spans the signal exactly.
sphbasis_cli_test(imse_paper_small "protocol paper: 200 signals, seed 7.*\nsh +9 +0 \\(<1e-13\\)"
                  imse --signals 200 --seed 7)
sphbasis_cli_test(imse_paper_closed_form "closed form vs sample mean: largest \\|mean - expected\\| = [0-4]\\.[0-9]+ standard errors\n"
                  imse --protocol=paper --signals 2000)
# Files: JSON with the documented schema, CSV and Markdown.
sphbasis_cli_script(imse_files "files-ok"
                    "\"$<TARGET_FILE:sphbasis_cli>\" imse --signals 50 --seed 3 --json imse_test.json --csv imse_test.csv --md imse_test.md >/dev/null && grep -q '\"protocol\":\"paper\",\"signals\":50,\"seed\":3' imse_test.json && grep -q '{\"basis\":\"sh\",\"coeffs\":4,\"imse\":' imse_test.json && grep -q 'bytes_per_texel_rgb8\":12' imse_test.json && grep -q '^paper,hl2,3,' imse_test.csv && grep -q '^| hbasis | 6 |' imse_test.md && echo files-ok")
# Same seed, same numbers: two runs write identical CSV apart from the timing columns.
sphbasis_cli_script(imse_stable "stable-ok"
                    "b=\"$<TARGET_FILE:sphbasis_cli>\"; $b imse --signals 100 --seed 9 --csv s1.csv >/dev/null && $b imse --signals 100 --seed 9 --csv s2.csv >/dev/null && cut -d, -f1-8 s1.csv > s1.cut && cut -d, -f1-8 s2.csv > s2.cut && cmp s1.cut s2.cut && echo stable-ok")
# The hdri protocol on a few signals (needs OpenEXR and data/envmaps).
sphbasis_cli_test(imse_hdri_small "protocol hdri: 16 signals, seed 1" imse --protocol hdri --signals 16)

# Bad options exit non-zero with a message.
sphbasis_cli_fails(imse_bad_protocol imse --protocol nope)
sphbasis_cli_fails(imse_bad_signals imse --signals abc)
sphbasis_cli_fails(imse_zero_signals imse --signals 0)
sphbasis_cli_fails(imse_one_signal imse --signals 1)
sphbasis_cli_fails(imse_negative_seed imse --seed -3)
sphbasis_cli_fails(imse_unknown_option imse --bogus 1)
sphbasis_cli_fails(imse_missing_value imse --signals)
sphbasis_cli_fails(imse_positional imse paper)
sphbasis_cli_fails(imse_twice imse --seed 1 --seed 2)
sphbasis_cli_fails(imse_unwritable imse --signals 10 --json /nonexistent-dir/x.json)
sphbasis_cli_test(imse_bad_protocol_message "expected paper, hdri or all" imse --protocol nope)

# Limits said before any work: the hdri protocol keeps 804 bytes per signal (at most 1000000).
sphbasis_cli_test(imse_hdri_signals_limit "^sphbasis imse: --signals: expected N <= 1000000 for --protocol hdri \\(the hdri protocol keeps 804 bytes per signal"
                  imse --protocol hdri --signals 10000000)
sphbasis_cli_test(imse_signals_limit "--signals: expected 2 <= N <= 10000000 \\(80 bytes of memory per signal"
                  imse --signals 10000001)
# Two signals cannot judge the closed form: said so, no false alarm.
sphbasis_cli_test(imse_two_signals "closed form vs sample mean: not judged with 2 signals"
                  imse --protocol paper --signals 2)
set_tests_properties(cli_imse_two_signals PROPERTIES FAIL_REGULAR_EXPRESSION "WARNING")
# Rounding-level IMSE (SH 9, 16, 25 span the paper signal) is 0 in CSV and JSON as in the
# table: no negative closed form (the fitted rows have none: an empty field).
sphbasis_cli_script(imse_rounding_zero "rounding-ok"
                    "\"$<TARGET_FILE:sphbasis_cli>\" imse --signals 20 --seed 5 --csv imse_round.csv --json imse_round.json >/dev/null && grep -q '^paper,sh,16,0,[^,]*,0,' imse_round.csv && grep -q '^paper,sh,25,0,[^,]*,0,' imse_round.csv && awk -F, 'NR > 1 && ($4 < 0 || ($6 != \"\" && $6 < 0)) { bad = 1 } END { if (!bad) print \"rounding-ok\" }' imse_round.csv && ! grep -q '\"imse\":-\\|\"expected\":-' imse_round.json")

# The plot (tools/plot/plot_imse.py, python3-matplotlib from scripts/setup): --check fails if a
# label overlaps another label, covers a marker or leaves its panel. On a real run of both
# protocols (rows of equal IMSE and near-equal cost share a label), and on 40 rows crowded into
# one spot (and one far away, so the 40 are close on screen), where no placement can be free:
# the check must refuse it.
set(_plot_imse ${CMAKE_CURRENT_SOURCE_DIR}/../tools/plot/plot_imse.py)
# The label check runs on the committed JSON of the run behind README's figure
# (tests/data/imse_readme_run.json): label places follow the measured ns, which a live run on a
# loaded machine moves (a live run's crowding was seen to differ run to run); a live run is
# plotted too, without the check.
sphbasis_cli_script(imse_plot_labels "plot_imse.py: [0-9]+ labels, none overlaps a label or a marker"
                    "/usr/bin/python3 ${_plot_imse} --check ${PROJECT_SOURCE_DIR}/tests/data/imse_readme_run.json imse_plot_readme.png && test -s imse_plot_readme.png && \"$<TARGET_FILE:sphbasis_cli>\" imse --protocol all --signals 16 --json imse_plot.json >/dev/null && /usr/bin/python3 ${_plot_imse} imse_plot.json imse_plot.png && test -s imse_plot.png")
sphbasis_cli_script(imse_plot_crowded "crowded-refused"
                    "/usr/bin/python3 -c \"import json; rows = [dict(basis='sh', coeffs=i, imse=1e-2 * (1 + 0.02 * i), eval_ns=5 + 0.01 * i, stderr=0) for i in range(40)] + [dict(basis='zernike', coeffs=3, imse=0.1, eval_ns=20, stderr=0)]; json.dump(dict(protocol='paper', signals=10, seed=1, rows=rows), open('imse_crowd.json', 'w'))\" && ! /usr/bin/python3 ${_plot_imse} --check imse_crowd.json imse_crowd.png 2>/dev/null && echo crowded-refused")
# README's "Which basis?" table is the one tools/plot/imse_readme_table.py makes of the committed
# run behind it (tests/data/imse_readme_run.json), so its numbers trace to that run; the tool
# refuses a file that is not such a run.
set(_imse_table ${CMAKE_CURRENT_SOURCE_DIR}/../tools/plot/imse_readme_table.py)
sphbasis_cli_script(imse_readme_table "checked the table of [^\n]*README.md[^\n]*\nbad-run-refused"
                    "/usr/bin/python3 ${_imse_table} ${PROJECT_SOURCE_DIR}/tests/data/imse_readme_run.json --check ${PROJECT_SOURCE_DIR}/README.md && ! /usr/bin/python3 ${_imse_table} ${PROJECT_SOURCE_DIR}/tests/data/render_summary_fixture.json 2>/dev/null && echo bad-run-refused")
