#!/usr/bin/env bash
# The tree is formatted by .clang-format: every C++ source and header (engine, cli, tests,
# examples, the GLSL/C++ shared headers, the Python bindings) passes `clang-format --dry-run -Werror`.
# Usage: tests/checks/format_check.sh [CLANG_FORMAT]   (run from anywhere)
set -euo pipefail
cd "$(dirname "$0")/../.."
tool="${1:-clang-format}"
if ! command -v "$tool" > /dev/null; then
  echo "SKIPPED: $tool is not installed (Debian: clang-format)"
  exit 0
fi
mapfile -t files < <(git ls-files 'engine/*.cpp' 'engine/*.h' 'cli/*.cpp' 'cli/*.h' 'tests/*.cpp' 'tests/*.h' \
                                  'examples/*.cpp' 'shaders/shared/*.h' 'python/src/*.cpp' 'python/src/*.h' 2> /dev/null || true)
if [ ${#files[@]} -eq 0 ]; then  # not a git checkout (an exported tree): every source there
  mapfile -t files < <(find engine cli tests examples shaders/shared python/src -name '*.cpp' -o -name '*.h')
fi
"$tool" --dry-run -Werror "${files[@]}"
echo "formatting: ${#files[@]} files as .clang-format has them"
