#!/usr/bin/env bash
# Where the provider finds the program (docs/qgis.md): the Processing setting, then <prefix>/bin of a
# `cmake --install`, then PATH; with none, one message (exact text) in qgis_process.bin's output and a
# placeholder algorithm instead of an empty provider. Also the progress text in qgis_process's
# output: each stage on a line of its own, never glued to the progress ticks ("10patch cleaning").
set -euo pipefail
source "$(dirname "$0")/qgis_env.sh"
: "${URBANVEC_BUILD_DIR:?set URBANVEC_BUILD_DIR to the build folder}"
ini="$HOME/.local/share/QGIS/QGIS3/profiles/default/QGIS/QGIS3.ini"
setting_place='Settings > Options > Processing > Providers > urbanvec > urbanvec program'
export PATH="$(echo "$PATH" | tr ':' '\n' | grep -vx "$(dirname "$URBANVEC")" | paste -sd: -)"
if command -v urbanvec >/dev/null; then fail "an urbanvec program is on PATH: $(command -v urbanvec)"; fi
bare_path="$PATH"

# qgis_process.bin with stdout in $WORK/$1.out and stderr (without PyQt's setapi notice) in $WORK/$1.err.
qp() {
  local name="$1"; shift
  set +e
  qgis_process.bin "$@" > "$WORK/$name.out" 2> "$WORK/$name.raw"
  local status=$?
  set -e
  grep -v -e 'setapi() is deprecated' "$WORK/$name.raw" > "$WORK/$name.err" || true
  [ "$status" -lt 128 ] || { cat "$WORK/$name.err"; fail "qgis_process.bin $* crashed (status $status)"; }
  return "$status"
}
set_program() {  # the Processing setting (the path a user picks in the options dialog); none without argument
  sed -i '/^Configuration\\URBANVEC_PROGRAM=/d' "$ini"  # QGIS rewrites the file: other sections may follow
  if [ $# -eq 0 ]; then return 0; fi
  grep -qx '\[Processing\]' "$ini" || printf '\n[Processing]\n' >> "$ini"
  sed -i "/^\[Processing\]\$/a Configuration\\\\URBANVEC_PROGRAM=$1" "$ini"
}
urbanvec_algorithms() { sed -n 's/^[[:space:]]*\(urbanvec:[^[:space:]]*\).*/\1/p' "$WORK/$1.out" | tr '\n' ' '; }
message() {  # the provider's message when nothing works; arguments: what each place gave
  printf '%s\n' "urbanvec: No usable urbanvec program was found, so the urbanvec provider has no algorithms. Looked in this order:" \
    "  1. the plugin setting ($setting_place): $1" \
    "  2. $2" \
    "  3. PATH ($PATH): $3" \
    "To fix it, set the path of the urbanvec program in $setting_place, or put the folder that holds urbanvec on PATH and restart QGIS."
}
same_text() {  # expected file, actual file, what
  diff -u "$1" "$2" >&2 || fail "$3 differs from the expected text (diff above)"
}
source_plugin="$URBANVEC_SOURCE_DIR/plugin/urbanvec"
not_installed="the install prefix: none, this plugin ($source_plugin) was not installed by cmake --install"
mkdir -p "$WORK/fake"
cp "$PLUGIN_TESTS/fixtures/fake_urbanvec.sh" "$WORK/fake/urbanvec"
chmod +x "$WORK/fake/urbanvec"

# (a) No setting, no install prefix, nothing on PATH: one clear message, a placeholder, no crash.
qp none list || fail "qgis_process.bin list failed without the program: $(cat "$WORK/none.err")"
message 'not set' "$not_installed" 'no urbanvec in its folders' > "$WORK/expected_none.txt"
same_text "$WORK/expected_none.txt" "$WORK/none.err" "the stderr of qgis_process.bin list without a program"
[ "$(urbanvec_algorithms none)" = 'urbanvec:program_not_found ' ] \
  || fail "without a program the provider lists: $(urbanvec_algorithms none)"
grep -qx $'\turbanvec:program_not_found\turbanvec program not found (open for how to fix it)' "$WORK/none.out" \
  || fail "no placeholder line in the toolbox list"
if qp none_run run urbanvec:program_not_found; then fail "running the placeholder succeeded"; fi
grep -qF "$(sed -n 2p "$WORK/expected_none.txt")" "$WORK/none_run.out" "$WORK/none_run.err" \
  || fail "running the placeholder does not show the message: $(cat "$WORK/none_run.out" "$WORK/none_run.err")"
echo "(a) no program: the message, and urbanvec:program_not_found in the list"

# (a) A setting that does not work is named with its reason; so is a program failing --json-usage.
touch "$WORK/not-executable"
set_program "$WORK/not-executable"
qp broken list || fail "qgis_process.bin list failed with a broken setting"
message "$WORK/not-executable is not executable" "$not_installed" 'no urbanvec in its folders' > "$WORK/expected_broken.txt"
same_text "$WORK/expected_broken.txt" "$WORK/broken.err" "the message for a non-executable setting"
mkdir -p "$WORK/failing"
printf '#!/bin/sh\necho "cannot load libgdal.so.32" >&2\nexit 127\n' > "$WORK/failing/urbanvec"
chmod +x "$WORK/failing/urbanvec"
set_program "$WORK/missing/urbanvec"
PATH="$WORK/failing:$bare_path"
qp failing list || fail "qgis_process.bin list failed with a failing program"
message "$WORK/missing/urbanvec does not exist" "$not_installed" \
  "$WORK/failing/urbanvec --json-usage failed (exit status 127): cannot load libgdal.so.32" > "$WORK/expected_failing.txt"
same_text "$WORK/expected_failing.txt" "$WORK/failing.err" "the message for a program failing --json-usage"
PATH="$bare_path"
set_program
echo "(a) a broken setting and a failing program are named with their reason"

# (c) The setting pointing at the program: algorithms listed, nothing reported.
set_program "$URBANVEC"
qp setting list || fail "qgis_process.bin list failed with the setting"
urbanvec_algorithms setting | grep -qw 'urbanvec:vectorize' || fail "the program set in the options was not used"
urbanvec_algorithms setting | grep -qw 'urbanvec:program_not_found' && fail "the placeholder is listed beside the algorithms"
[ ! -s "$WORK/setting.err" ] || fail "something was reported although the setting works: $(cat "$WORK/setting.err")"
# The setting comes before PATH.
PATH="$(dirname "$URBANVEC"):$bare_path"
set_program "$WORK/fake/urbanvec"
qp setting_first list
[ "$(urbanvec_algorithms setting_first)" = 'urbanvec:stages ' ] \
  || fail "the setting did not take precedence over PATH: $(urbanvec_algorithms setting_first)"
PATH="$bare_path"
set_program
echo "(c) the setting: $(urbanvec_algorithms setting | wc -w) algorithms; it comes before PATH"

# (b) Only through the install prefix: `cmake --install` into a temporary prefix, no PATH, no setting.
prefix="$WORK/prefix"
cmake --install "$URBANVEC_BUILD_DIR" --prefix "$prefix" > "$WORK/install.log"
[ -x "$prefix/bin/urbanvec" ] || fail "cmake --install did not install bin/urbanvec"
installed_plugins="$prefix/share/qgis/python/plugins"
[ -f "$installed_plugins/urbanvec/program.py" ] || fail "cmake --install did not put the plugin in share/qgis/python/plugins"
export QGIS_PLUGINPATH="$installed_plugins" PYTHONPATH=  # the installed copy, not the sources
qp prefix list || fail "qgis_process.bin list failed with the installed plugin"
urbanvec_algorithms prefix | grep -qw 'urbanvec:vectorize' || fail "the installed plugin did not find $prefix/bin/urbanvec"
[ ! -s "$WORK/prefix.err" ] || fail "something was reported although the installed program works: $(cat "$WORK/prefix.err")"
# The install prefix comes before PATH, and PATH is used when the installed program does not work.
PATH="$WORK/fake:$bare_path"
qp prefix_first list
urbanvec_algorithms prefix_first | grep -qw 'urbanvec:vectorize' || fail "PATH took precedence over the install prefix"
chmod -x "$prefix/bin/urbanvec"
qp prefix_broken list
[ "$(urbanvec_algorithms prefix_broken)" = 'urbanvec:stages ' ] \
  || fail "PATH was not used when the installed program is not executable: $(urbanvec_algorithms prefix_broken)"
grep -qxF "urbanvec: not using the install prefix $prefix: $prefix/bin/urbanvec is not executable; using $WORK/fake/urbanvec" \
  "$WORK/prefix_broken.err" || fail "the unusable installed program was not reported: $(cat "$WORK/prefix_broken.err")"
PATH="$bare_path"
qp prefix_none list
message 'not set' "the install prefix $prefix: $prefix/bin/urbanvec is not executable" 'no urbanvec in its folders' \
  > "$WORK/expected_prefix_none.txt"
same_text "$WORK/expected_prefix_none.txt" "$WORK/prefix_none.err" "the message naming the install prefix"
chmod +x "$prefix/bin/urbanvec"
# A plugin copied into a profile's plugin folder (or installed with URBANVEC_QGIS_PLUGIN_DIR pointing
# there) still finds the program through the install_paths.py that cmake --install wrote.
mkdir -p "$WORK/profile_plugins"
cp -r "$installed_plugins/urbanvec" "$WORK/profile_plugins/"
grep -qxF "PROGRAM = r'$prefix/bin/urbanvec'" "$WORK/profile_plugins/urbanvec/install_paths.py" \
  || fail "cmake --install did not record the program in install_paths.py"
export QGIS_PLUGINPATH="$WORK/profile_plugins"
qp profile list
urbanvec_algorithms profile | grep -qw 'urbanvec:vectorize' || fail "a plugin moved out of the prefix lost the installed program"
chmod +x "$prefix/bin/urbanvec"
export QGIS_PLUGINPATH="$URBANVEC_SOURCE_DIR/plugin" PYTHONPATH="/usr/share/qgis/python/plugins:$URBANVEC_SOURCE_DIR/plugin"
echo "(b) the install prefix: $(urbanvec_algorithms prefix | wc -w) algorithms; it comes before PATH"

# (d) Progress in qgis_process's output: the stages as words on lines of their own, the percent as ticks.
set_program "$WORK/fake/urbanvec"
qp stages run urbanvec:stages -- OUTPUT="$WORK/stages.txt" || fail "running the fake program failed: $(cat "$WORK/stages.err")"
sed -n '/ stages -progress lines /,/^stages: 4 stages$/p' "$WORK/stages.out" > "$WORK/stages_run.txt"
cat > "$WORK/expected_stages.txt" <<TXT
$WORK/fake/urbanvec stages -progress lines $WORK/stages.txt
raw blocks
0...10
patch cleaning
...20...30
parcels
..
WARNING:	3 roads were too short
.40
road graph
...50...60...70...80...90...100 - done.

done
stages: 4 stages
TXT
same_text "$WORK/expected_stages.txt" "$WORK/stages_run.txt" "the progress shown by qgis_process"
echo "(d) qgis_process shows the stages as words: $(grep -c -x -e 'raw blocks' -e 'patch cleaning' -e parcels -e 'road graph' "$WORK/stages_run.txt") stage lines"
echo "PASS"
