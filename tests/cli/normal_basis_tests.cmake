# Tests of `sphbasis normal-basis` (label "cli"). Included by tests/CMakeLists.txt after
# cli_tests.cmake, whose helpers sphbasis_cli_test / sphbasis_cli_script / sphbasis_cli_fails it
# uses.

# The table: M = 4 and M = 6 rows. The unclamped columns match the values printed in Sloan,
# Lehtinen and Kautz (SIGGRAPH 2005 course): 93.9 / 96.4 and 98.7 / 99.3 within 0.11.
sphbasis_cli_test(normal_basis_table
                  "M  clamped/uniform  clamped/cosine  unclamped/uniform  unclamped/cosine\n.*\n  4 +98\\.35 +99\\.11 +93\\.92 +96\\.29\n.*\n  6 +99\\.99 +100\\.00 +98\\.64 +99\\.24\n.*\n  9 +100\\.00 +100\\.00 +100\\.00 +100\\.00\n"
                  normal-basis)
# JSON: the documented layout, bands^2 numbers per list, monotone, 100 at the end.
sphbasis_cli_script(normal_basis_json "json-ok"
                    "\"$<TARGET_FILE:sphbasis_cli>\" normal-basis --json nb_test.json >/dev/null && python3 -c \"import json; d = json.load(open('nb_test.json')); assert list(d) == ['clamped', 'unclamped']; assert all(list(d[k]) == ['uniform', 'cosine'] for k in d); v = [d[k][w] for k in d for w in d[k]]; assert all(len(x) == 9 and all(a <= b for a, b in zip(x, x[1:])) and abs(x[-1] - 100) < 1e-12 for x in v); assert abs(d['unclamped']['uniform'][3] - 93.9) < 0.15 and abs(d['unclamped']['cosine'][5] - 99.3) < 0.15; print('json-ok')\"")
sphbasis_cli_script(normal_basis_json_bands2 "json2-ok"
                    "\"$<TARGET_FILE:sphbasis_cli>\" normal-basis --bands 2 --json nb_test2.json >/dev/null && python3 -c \"import json; d = json.load(open('nb_test2.json')); assert all(len(d[k][w]) == 4 for k in d for w in d[k]); print('json2-ok')\"")
sphbasis_cli_test(normal_basis_bands1 "  1 +100\\.00 +100\\.00 +100\\.00 +100\\.00\n" normal-basis --bands 1)
sphbasis_cli_test(normal_basis_help "Usage: sphbasis normal-basis.*--bands N.*--json" normal-basis --help)

# Bad options exit non-zero with a message.
sphbasis_cli_fails(normal_basis_zero_bands normal-basis --bands 0)
sphbasis_cli_fails(normal_basis_many_bands normal-basis --bands 9)
sphbasis_cli_fails(normal_basis_bad_bands normal-basis --bands x)
sphbasis_cli_fails(normal_basis_positional normal-basis 3)
sphbasis_cli_fails(normal_basis_unwritable normal-basis --json /nonexistent-dir/x.json)
sphbasis_cli_test(normal_basis_bands_message "--bands: expected 1 <= N <= 8, got 9" normal-basis --bands 9)
