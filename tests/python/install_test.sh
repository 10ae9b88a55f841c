#!/usr/bin/env bash
# The README's Python install, as a newcomer runs it: its ```shell block (a virtual environment with Debian's site
# packages, then pip install --no-build-isolation of the project) in a scratch HOME, then its ```python example with
# that environment's interpreter, from outside the project (so that the installed package is the one imported).
# The project is copied first (working tree and .git, without build folders and study stores), so that pip's in-tree
# build leaves nothing in the repository. About 5 minutes: pip builds the core with CMake.
# Needs SRC (the source tree) in the environment.
set -euo pipefail
scratch=$(mktemp -d); trap 'rm -rf "$scratch"' EXIT
mkdir "$scratch/home" "$scratch/project"
tar -C "$SRC" --exclude=./build --exclude='./build-*' --exclude='./results/*/store' --exclude='./python/*.egg-info' \
    -cf - . | tar -C "$scratch/project" -xf -
section=$(awk '/^## Python$/ { inside = 1; next } /^## / { inside = 0 } inside' "$SRC/README.md")
install=$(echo "$section" | awk '/^```shell$/ { inside = 1; next } /^```$/ { inside = 0; next } inside')
example=$(echo "$section" | awk '/^```python$/ { inside = 1; next } /^```$/ { inside = 0; next } inside')
[ -n "$install" ] && [ -n "$example" ] || { echo "FAIL: README.md's Python section lost its shell or python block"; exit 1; }
export HOME="$scratch/home" BEAMID_HOME="$scratch/project" CMAKE_BUILD_PARALLEL_LEVEL="${CMAKE_BUILD_PARALLEL_LEVEL:-2}"
(cd "$scratch/home" && bash -euo pipefail -c "$install") >"$scratch/install.log" 2>&1 || {
  tail -40 "$scratch/install.log"; echo "FAIL: the README's install lines"; exit 1; }
echo "$example" >"$scratch/example.py"
out=$(cd "$scratch/home" && "$HOME/beamid-env/bin/python" "$scratch/example.py")
echo "$out"
# The example imported the installed package, not a build folder's, and its fit recovered the preset's EI and rho
# from the fitted model's own noise-free record (a start 5 % off; LM's tolerance leaves 1e-6 relative at most).
where=$(cd "$scratch/home" && "$HOME/beamid-env/bin/python" -c 'import beamid; print(beamid.__file__)')
case "$where" in "$HOME/beamid-env/"*) ;; *) echo "FAIL: imported $where, not the environment's package"; exit 1;; esac
# The installed package carries its type information (PEP 561: py.typed and the generated stubs).
for f in py.typed __init__.pyi; do
  [ -f "$(dirname "$where")/$f" ] || { echo "FAIL: the installed package has no $f"; exit 1; }
done
"$HOME/beamid-env/bin/python" - "$out" <<'PY'
import sys, ast
import beamid
line = next(l for l in sys.argv[1].splitlines() if l.startswith("{'EI'"))
estimates = ast.literal_eval(line.split("}")[0] + "}")
truth = beamid.beam("thick-steel")
ei, rho = truth["EI"], truth["rho"]
assert abs(estimates["EI"] / ei - 1) < 1e-6 and abs(estimates["rho"] / rho - 1) < 1e-6, estimates
print("python install: the README's install lines and example ran; EI and rho recovered to 1e-6")
PY
