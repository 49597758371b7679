# Sourced by the plugin tests: an isolated, headless QGIS profile with the urbanvec plugin enabled.
# Needs URBANVEC (the built program) and URBANVEC_SOURCE_DIR (the repository root) from ctest.
: "${URBANVEC:?set URBANVEC to the built urbanvec program}"
: "${URBANVEC_SOURCE_DIR:?set URBANVEC_SOURCE_DIR to the repository root}"
URBANVEC="$(readlink -f "$URBANVEC")"
PLUGIN_TESTS="$URBANVEC_SOURCE_DIR/tests/plugin"
WORK="$(mktemp -d "${TMPDIR:-/tmp}/urbanvec-plugin-test.XXXXXX")"
trap 'rm -rf "$WORK"' EXIT
export HOME="$WORK/home"
export XDG_RUNTIME_DIR="$WORK/runtime"
mkdir -p "$HOME/.local/share/QGIS/QGIS3/profiles/default/QGIS" "$XDG_RUNTIME_DIR"
chmod 700 "$XDG_RUNTIME_DIR"
cat > "$HOME/.local/share/QGIS/QGIS3/profiles/default/QGIS/QGIS3.ini" <<INI
[PythonPlugins]
urbanvec=true
INI
export QGIS_PLUGINPATH="$URBANVEC_SOURCE_DIR/plugin"
export QT_QPA_PLATFORM=offscreen
export PYTHONDONTWRITEBYTECODE=1
# The Python that has PyQGIS (Debian's), whatever python3 comes first on PATH.
QGIS_PYTHON=/usr/bin/python3
# The plugin finds the program on PATH unless a test sets the Processing setting.
export PATH="$(dirname "$URBANVEC"):$PATH"
export PYTHONPATH="/usr/share/qgis/python/plugins:$URBANVEC_SOURCE_DIR/plugin${PYTHONPATH:+:$PYTHONPATH}"

fail() {
  echo "FAIL: $*" >&2
  exit 1
}
