#!/usr/bin/env bash
# Set-up (idempotent) and the whole test suite.
set -euo pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
"$top/scripts/setup.sh"
ctest --test-dir "${BUILD_DIR:-$top/build}" -j "$(nproc)" --output-on-failure --timeout 600
