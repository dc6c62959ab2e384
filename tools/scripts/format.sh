#!/bin/bash
# Formats the C++ sources with clang-format and the repository's .clang-format.
#   tools/scripts/format.sh           rewrite every tracked .cpp/.hpp in place
#   tools/scripts/format.sh --check   change nothing; list the files that would change, exit 1 if any
#   tools/scripts/format.sh [--check] FILE...   only these files
# clang-format comes from Debian's clang-format package (tools/scripts/install-deps.sh).
set -euo pipefail
cd "$(dirname "$0")/../.."

check=0
if [[ "${1:-}" == "--check" ]]; then
  check=1
  shift
fi
if ! command -v clang-format >/dev/null; then
  echo "format.sh: clang-format not found (apt-get install clang-format)" >&2
  exit 2
fi

if [[ $# -gt 0 ]]; then
  files=("$@")
else
  # Tracked files that are still there (a file deleted but not yet committed is skipped).
  mapfile -t files < <(git ls-files '*.cpp' '*.hpp' '*.h' | while read -r f; do [[ -f $f ]] && echo "$f"; done)
fi

if [[ $check -eq 0 ]]; then
  clang-format -i "${files[@]}"
  exit 0
fi

unformatted=0
for f in "${files[@]}"; do
  if ! clang-format "$f" | cmp -s - "$f"; then
    echo "$f"
    unformatted=$((unformatted + 1))
  fi
done
if [[ $unformatted -gt 0 ]]; then
  echo "format.sh: $unformatted file(s) differ from .clang-format (run tools/scripts/format.sh)" >&2
  exit 1
fi
