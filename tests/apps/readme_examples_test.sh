#!/usr/bin/env bash
# Runs every ```sh block of README.md, in order, in one shell, as a newcomer would type them: from the repository,
# then in the scratch folder the first block makes. `make` lines are left out (the test runs the binary it was given)
# and the program's folder is put on PATH. Fails on the first failing command, and when an example leaves anything
# in the repository.
# Needs BEAMID (the binary) and SRC (the source tree) in the environment.
set -euo pipefail
script=$(mktemp); trap 'rm -f "$script"' EXIT
{
  echo 'set -euo pipefail'
  echo "cd \"$SRC\""
  awk '/^```sh$/ { inside = 1; next } /^```$/ { inside = 0; next } inside && !/^make / { print }' "$SRC/README.md"
} >"$script"
# The binary under test, not whatever build/beamid is: put its folder first on PATH after the README's export.
sed -i "/^export BEAMID_HOME=/a export PATH=\"$(dirname "$BEAMID"):\$PATH\"" "$script"
before=$(cd "$SRC" && find . -path ./build -prune -o -path './build-*' -prune -o -path ./.git -prune -o -print | sort)
bash "$script" >/dev/null
after=$(cd "$SRC" && find . -path ./build -prune -o -path './build-*' -prune -o -path ./.git -prune -o -print | sort)
if [ "$before" != "$after" ]; then
  echo "FAIL: the README examples left files in the repository:"
  diff <(echo "$before") <(echo "$after") || true
  exit 1
fi
echo "readme examples: $(grep -c '^```sh$' "$SRC/README.md") blocks ran"
