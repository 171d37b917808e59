"""Packaging (issue 29): the version is set in one place, meson.build's project(), and both front
doors print it; `pip install sloshdyn` is the core, and a missing extra (plot, studies) is a
sloshdyn error naming the extra that pyproject.toml says installs the missing package.
The wheel itself is checked by .ci/wheel_check.sh (`bash .ci/dev wheel`)."""

import re
import subprocess
import sys
import sysconfig
import tomllib
from pathlib import Path

import pytest

import sloshdyn
from conftest import ROOT
from sloshdyn._shipped import EXAMPLES, NAMELIST_REFERENCE

PROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
#: the project version as meson.build's project() sets it
VERSION = re.search(r"^project\([^)]*?\bversion: '([^']+)'", (ROOT / "meson.build").read_text(),
                    re.M | re.S).group(1)


def test_the_version_is_set_once_in_meson_build():
    assert "version" not in PROJECT and "version" in PROJECT["dynamic"]
    assert sloshdyn.__version__ == VERSION


@pytest.mark.parametrize("command", ["sloshdyn", "sloshdyn-py"])
def test_both_front_doors_print_the_version(command):
    path = Path(sysconfig.get_path("scripts")) / command
    out = subprocess.run([str(path), "--version"], capture_output=True, text=True, timeout=60)
    assert (out.returncode, out.stdout.strip()) == (0, f"sloshdyn {VERSION}")


def run_without(modules, code):
    """Run Python code in a fresh interpreter where importing `modules` fails."""
    block = "import sys\n" + "".join(f"sys.modules[{m!r}] = None\n" for m in modules)
    return subprocess.run([sys.executable, "-c", block + code], capture_output=True,
                          text=True, timeout=120, cwd=ROOT / "tests")


EXTRAS = {"plot": ["matplotlib"], "studies": ["dask", "distributed", "xarray", "zarr", "scipy"]}


def test_the_core_runs_without_any_extra():
    """import sloshdyn and the core analyses need none of the extras' packages."""
    out = run_without(sum(EXTRAS.values(), []), "\n".join([
        "import sloshdyn",
        "p = sloshdyn.Parameters(s1=1.5, mu1=0.5, kappa=1.804897259, theta0=0.785, A=0.00075)",
        "sloshdyn.simulate(p, t_end=10.0); sloshdyn.equilibria(p)",
        "assert not {'matplotlib', 'dask', 'xarray', 'zarr', 'scipy'} & set(m for m in "
        "sys.modules if sys.modules[m] is not None), 'an extra was imported'"]))
    assert out.returncode == 0, out.stderr


STORE = "str(__import__('pathlib').Path(__import__('tempfile').mkdtemp()) / 's.zarr')"


@pytest.mark.parametrize("extra, module, call", [
    ("plot", "matplotlib", "sloshdyn.plotting"),
    ("studies", "dask", f"sloshdyn.response_map(p, [0.5], [1e-3], {STORE})"),
    ("studies", "xarray", f"sloshdyn.basins(p, (-1, 1), (-1, 1), n=2, store={STORE})"),
    ("studies", "zarr", f"sloshdyn.response_map(p, [0.5], [1e-3], {STORE})"),
    ("studies", "scipy", "sloshdyn.fit_fragility([1.0, 2.0], [0, 1])"),
    ("pdf", "weasyprint",
     "__import__('sloshdyn.report_pdf').report_pdf.write_pdf('<p/>', 'x.pdf')"),
])
def test_a_missing_extra_is_an_error_naming_it(extra, module, call):
    """The error is a SloshdynError and an ImportError, and the extra it names installs the
    missing package (pyproject.toml's optional dependencies)."""
    assert any(req.startswith(module) or req.startswith(f"{module}[")
               for req in PROJECT["optional-dependencies"][extra])
    out = run_without([module], "\n".join([
        "import sloshdyn",
        "p = sloshdyn.Parameters(s1=1.5, mu1=0.5, kappa=1.804897259, theta0=0.785, A=0.00075,"
        "                        rho=0.51)",
        "try:",
        f"    {call}",
        "except ImportError as exc:",
        "    assert isinstance(exc, sloshdyn.SloshdynError), type(exc)",
        "    print(exc)",
        "else:",
        "    raise SystemExit('no error')"]))
    assert out.returncode == 0, out.stderr
    assert f"{module} is not installed" in out.stdout
    assert f"pip install 'sloshdyn[{extra}]'" in out.stdout


def test_sloshdyn_py_without_matplotlib_names_the_plot_extra():
    """Every command of sloshdyn-py draws figures: without matplotlib, an error, no traceback."""
    out = run_without(["matplotlib"], "from sloshdyn.__main__ import main\n"
                                      "raise SystemExit(main(['--version']))")
    assert out.returncode == 3     # a SloshdynError without a status: the input/setup code
    assert out.stderr.strip() == ("sloshdyn-py: error: matplotlib is not installed; it comes "
                                  "with the 'plot' extra: pip install 'sloshdyn[plot]' (the "
                                  "namelist reference, without it: "
                                  f"{NAMELIST_REFERENCE})")


def test_the_package_ships_the_examples_and_the_namelist_reference(exe, tmp_path):
    """Issue 44 item 10: the wheel held no example input and --help pointed to
    docs/namelist.md, which a wheel user does not have. The installed package holds every
    input of data/examples with its records and docs/namelist.md, byte for byte;
    `sloshdyn-py examples DIR` copies them out (never over a file), and a copied example that
    reads a record runs where it was copied; `sloshdyn-py --help` names the installed
    reference, the executable's --help says how to find it."""
    shipped = sorted(p.relative_to(ROOT / "data" / "examples")
                     for p in (ROOT / "data" / "examples").rglob("*")
                     if p.suffix in (".nml", ".AT2"))
    assert len(shipped) > 20
    for name in shipped:
        assert (EXAMPLES / name).read_bytes() == (ROOT / "data" / "examples" / name).read_bytes()
    assert NAMELIST_REFERENCE.read_bytes() == (ROOT / "docs" / "namelist.md").read_bytes()
    scripts = Path(sysconfig.get_path("scripts"))
    out = subprocess.run([str(scripts / "sloshdyn-py"), "examples", "ex"], cwd=tmp_path,
                         capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    assert sorted(p.relative_to(tmp_path / "ex") for p in (tmp_path / "ex").rglob("*")
                  if p.is_file()) == shipped
    run = subprocess.run([exe, "ex/tank_seismic.nml"], cwd=tmp_path, capture_output=True,
                         text=True, timeout=300)
    assert run.returncode == 0, run.stderr
    again = subprocess.run([str(scripts / "sloshdyn-py"), "examples", "ex"], cwd=tmp_path,
                           capture_output=True, text=True, timeout=120)
    assert again.returncode == 5 and "already there; nothing copied" in again.stderr
    helped = subprocess.run([str(scripts / "sloshdyn-py"), "--help"], capture_output=True,
                            text=True, timeout=120)
    assert str(NAMELIST_REFERENCE) in helped.stdout.splitlines()[-2].split()  # whole, unwrapped
    usage = subprocess.run([exe, "--help"], capture_output=True, text=True, timeout=60).stdout
    assert "docs/namelist.md" not in usage and "sloshdyn-py --help prints" in usage
    assert "sloshdyn-py examples DIR" in usage


def test_a_wheel_is_built_for_every_supported_cpython_and_the_readme_says_the_floor():
    """Issue 44 item 13: the wheel was built for the interpreter that built it only (cp311;
    pip refuses it on 3.12) while requires-python is >= 3.10. .ci/wheel_matrix.sh (`bash .ci/dev
    wheels`) builds and runs one for every minor version from requires-python's floor to 3.13,
    each checked for its cpXY tag and the manylinux_2_35 floor; the README states the floor."""
    floor = re.fullmatch(r">=\s*3\.(\d+)", PROJECT["requires-python"]).group(1)
    supported = [f"3.{m}" for m in range(int(floor), 14)]
    script = (ROOT / ".ci" / "wheel_matrix.sh").read_text()
    built = re.search(r"versions=\$\{\*:-([\d. ]+)\}", script).group(1).split()
    assert built == supported
    assert "manylinux_2_35_x86_64" in script and 'tag=cp${v/./}' in script
    assert "wheels)" in (ROOT / ".ci" / "dev").read_text() or \
        "wheel_matrix.sh" in (ROOT / ".ci" / "dev").read_text()
    readme = " ".join((ROOT / "README.md").read_text().split())
    assert "manylinux_2_35_x86_64" in readme and "glibc ≥ 2.35" in readme
    assert "3.10, 3.11, 3.12 and 3.13" in readme and "bash .ci/dev wheels" in readme
