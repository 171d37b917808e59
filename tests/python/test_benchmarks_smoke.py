"""The benchmark script still runs (CI runs only its quick mode; timings are not tested)."""

import subprocess
import sys

from conftest import ROOT


def test_benchmark_quick_mode_runs(tmp_path):
    result = subprocess.run([sys.executable, str(ROOT / "benchmarks" / "run.py"), "--quick",
                             "--out", str(tmp_path / "bench.md")],
                            capture_output=True, text=True, timeout=600)
    assert result.returncode == 0, result.stderr[-2000:]
    text = (tmp_path / "bench.md").read_text()
    assert "sloshdyn" in text and "solve_ivp" in text
