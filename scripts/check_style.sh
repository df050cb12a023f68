#!/usr/bin/env bash
# The project's enforced style, one language per call (ctest: style.cpp, style.python):
#   cpp      the C++ of src/, postproc/, reference/, bench/ and tests/ as .clang-format formats it
#   python   the Python of scripts/, studies/, bench/ and tests/ clean under flake8 (.flake8)
# Exit status 1 with the files or lines at fault.
set -euo pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
cd "$top"

need() {
  command -v "$1" >/dev/null || { echo "$1 not found: scripts/setup.sh installs it"; exit 1; }
}

case "${1:-}" in
  cpp)
    need clang-format
    unformatted=()
    while IFS= read -r -d '' file; do
      clang-format --dry-run --Werror "$file" >/dev/null 2>&1 || unformatted+=("$file")
    done < <(find src postproc reference bench tests \( -name '*.cpp' -o -name '*.h' \) -print0 | sort -z)
    if [ ${#unformatted[@]} -gt 0 ]; then
      echo "not formatted as .clang-format says (clang-format -i FILE): ${unformatted[*]}"
      exit 1
    fi
    ;;
  python)
    need flake8
    flake8 scripts studies bench tests
    ;;
  *)
    echo "usage: scripts/check_style.sh cpp|python"
    exit 2
    ;;
esac
