#!/usr/bin/env bash
# Checks that every C++ file in the repository is as clang-format (the root .clang-format)
# writes it; lists the files that are not. `scripts/check_format.sh --fix` rewrites them.
# Exit status: 0 formatted, 1 files to format, 77 not a git checkout (nothing to list).
set -uo pipefail
cd "$(dirname "$0")/.."
format=$(command -v clang-format || command -v clang-format-14) || {
  echo "check_format: clang-format not found (scripts/install_deps.sh installs it)" >&2
  exit 1
}
git rev-parse --is-inside-work-tree >/dev/null 2>&1 || { echo "check_format: not a git checkout"; exit 77; }
mapfile -t files < <(git ls-files '*.cc' '*.h')
if [[ ${1:-} == --fix ]]; then
  "$format" -i "${files[@]}"
  exit 0
fi
bad=$("$format" --dry-run --Werror "${files[@]}" 2>&1 | sed -n 's/^\([^:]*\):[0-9]*:[0-9]*: error:.*/\1/p' | sort -u)
if [[ -n $bad ]]; then
  echo "check_format: not clang-formatted (scripts/check_format.sh --fix):"
  echo "$bad"
  exit 1
fi
echo "check_format: ${#files[@]} files formatted"
