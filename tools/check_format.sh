#!/usr/bin/env bash
# Checks that every C++ source under native/ follows the repository's .clang-format: lists the
# files that drift (with the first lines of their diff) and fails if any does. Fix them with
#   clang-format -i $(git ls-files 'native/*.h' 'native/*.cpp')
# Registered with ctest as `format_check`.
set -euo pipefail
REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$REPO"
command -v clang-format >/dev/null || { echo "clang-format is not installed"; exit 1; }
drift=0
while IFS= read -r -d '' f; do
  if ! clang-format --dry-run -Werror "$f" >/dev/null 2>&1; then
    echo "not formatted: $f"
    diff <(cat "$f") <(clang-format "$f") | head -n 8 || true
    drift=$((drift + 1))
  fi
done < <(find native -name '*.h' -print0 -o -name '*.cpp' -print0)
if [ "$drift" -gt 0 ]; then
  echo "$drift file(s) drift from .clang-format ($(clang-format --version))"
  exit 1
fi
echo "all C++ sources follow .clang-format"
