#!/usr/bin/env bash
# Runs the provider's algorithms in headless PyQGIS: progress, cancel, errors, program lookup, styles.
set -euo pipefail
source "$(dirname "$0")/qgis_env.sh"
"$QGIS_PYTHON" "$PLUGIN_TESTS/test_run.py"
