#!/usr/bin/env bash
# Unit tests of the provider: parameters from the JSON usage, exact argument lists (nothing is run).
set -euo pipefail
source "$(dirname "$0")/qgis_env.sh"
"$QGIS_PYTHON" "$PLUGIN_TESTS/test_arguments.py"
