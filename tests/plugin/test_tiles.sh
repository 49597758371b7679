#!/usr/bin/env bash
# The vectorize algorithm's tiled mode in headless PyQGIS (issue 22).
set -euo pipefail
source "$(dirname "$0")/qgis_env.sh"
"$QGIS_PYTHON" "$PLUGIN_TESTS/test_tiles.py"
