"""docs/studies.md's cluster recipes run as written (issue 40 item 6): each code block is run
unchanged, with a stand-in for dask-jobqueue's SLURMCluster and dask-kubernetes' KubeCluster
that takes the real class's keywords (checked against the real signature where the package is
installed) and starts local workers in this process, so a missing import, an undefined name or
a keyword the real class does not take fails here. The study's points are those of
steady_state (the independent source)."""

import importlib.util
import inspect
import re
import sys
import types

import pytest

import sloshdyn
from conftest import ROOT

pytest.importorskip("dask.distributed")

#: the keywords of the real classes (dask-jobqueue 0.9.0: SLURMCluster's own, its job's
#: SLURMJob and Job; dask-kubernetes 2026.3.0: operator.KubeCluster), which the stand-ins take
SLURM_KEYWORDS = {
    "n_workers", "job_cls", "loop", "security", "shared_temp_directory", "silence_logs", "name",
    "asynchronous", "dashboard_address", "host", "scheduler_options", "scheduler_cls",
    "interface", "protocol", "config_name", "scheduler", "queue", "project", "account",
    "walltime", "job_cpu", "job_mem", "cores", "memory", "processes", "nanny",
    "death_timeout", "local_directory", "extra", "worker_command", "worker_extra_args",
    "job_extra", "job_extra_directives", "env_extra", "job_script_prologue", "header_skip",
    "job_directives_skip", "log_directory", "shebang", "python", "job_name"}
KUBE_KEYWORDS = {
    "name", "namespace", "image", "n_workers", "resources", "env", "worker_command",
    "port_forward_cluster_ip", "create_mode", "shutdown_on_close", "idle_timeout",
    "resource_timeout", "scheduler_service_type", "custom_cluster_spec",
    "scheduler_forward_port", "jupyter", "loop", "asynchronous", "quiet"}


def recipe(marker):
    """The ```py block of docs/studies.md that contains `marker`."""
    text = (ROOT / "docs" / "studies.md").read_text()
    blocks = [b for b in re.findall(r"```py\n(.*?)```", text, re.S) if marker in b]
    assert len(blocks) == 1, marker
    return blocks[0]


def local_cluster_class(keywords, workers_of):
    """A stand-in cluster class: the real keywords only (others: TypeError, as the real
    class), local workers of one thread in this process; workers_of(kwargs) is the number the
    real cluster starts with; scale(n) or scale(jobs=...) as the real one."""
    from dask.distributed import LocalCluster

    class StandIn(LocalCluster):
        created = []

        def __init__(self, **kwargs):
            unknown = set(kwargs) - keywords
            if unknown:
                raise TypeError(f"unexpected keyword arguments {sorted(unknown)}")
            self.kwargs = kwargs
            super().__init__(n_workers=0, threads_per_worker=1, processes=False,
                             dashboard_address=None)
            StandIn.created.append(self)
            if workers_of(kwargs):
                super().scale(workers_of(kwargs))

        def scale(self, n=None, jobs=0, **_):
            super().scale(n if n is not None else jobs * self.kwargs.get("processes", 1))
    return StandIn


def run_recipe(code, module_name, attribute, stand_in, monkeypatch, tmp_path):
    module = types.ModuleType(module_name)
    setattr(module, attribute, stand_in)
    parent = module_name.split(".")[0]
    if parent != module_name:                    # dask_kubernetes.operator
        monkeypatch.setitem(sys.modules, parent, types.ModuleType(parent))
    monkeypatch.setitem(sys.modules, module_name, module)
    monkeypatch.chdir(tmp_path)
    namespace = {"__name__": "__main__"}
    exec(compile(code, f"docs/studies.md ({attribute} recipe)", "exec"), namespace)
    return namespace


def check_study(namespace, tmp_path):
    ds, p, f, a = (namespace[k] for k in ("ds", "p", "f", "a"))
    assert ds.attrs["points_failed"] == 0 and int((ds.done != 0).sum()) == f.size * a.size
    assert (tmp_path / "map.zarr").is_dir()
    for i, j in [(0, 0), (len(f) // 2, len(a) - 1)]:
        expected = sloshdyn.steady_state(p.replace(rho=float(f[i]), A=float(a[j])))
        assert float(ds.max_x1[i, j]) == expected.max_x1            # bit for bit


def real_keywords(module, cls):
    """The keywords the real class takes (its signature and, for dask-jobqueue, its job's)."""
    real = importlib.import_module(module)
    names = set()
    for c in [getattr(real, cls)] + ([real.slurm.SLURMJob, real.core.Job]
                                     if module == "dask_jobqueue" else []):
        names |= {n for n, p in inspect.signature(c.__init__).parameters.items()
                  if p.kind == p.KEYWORD_ONLY or p.kind == p.POSITIONAL_OR_KEYWORD} - {"self"}
    return names


def test_the_slurm_recipe_runs_as_written(monkeypatch, tmp_path, capsys):
    code = recipe("SLURMCluster")
    if importlib.util.find_spec("dask_jobqueue"):     # the stand-in takes what the real takes
        assert SLURM_KEYWORDS <= real_keywords("dask_jobqueue", "SLURMCluster")
    stand_in = local_cluster_class(SLURM_KEYWORDS, lambda kw: kw.get("n_workers", 0))
    namespace = run_recipe(code, "dask_jobqueue", "SLURMCluster", stand_in, monkeypatch,
                           tmp_path)
    cluster = stand_in.created[-1]
    assert cluster.kwargs["python"] == sys.executable      # the workers run the client's
    assert cluster.status.name == "closed"
    check_study(namespace, tmp_path)
    assert "points computed; 0 failed" in capsys.readouterr().out


def test_the_kubernetes_recipe_runs_as_written(monkeypatch, tmp_path, capsys):
    code = recipe("KubeCluster")
    if importlib.util.find_spec("dask_kubernetes"):
        assert KUBE_KEYWORDS <= real_keywords("dask_kubernetes.operator", "KubeCluster")
    stand_in = local_cluster_class(KUBE_KEYWORDS, lambda kw: kw.get("n_workers", 0))
    namespace = run_recipe(code, "dask_kubernetes.operator", "KubeCluster", stand_in,
                           monkeypatch, tmp_path)
    cluster = stand_in.created[-1]
    assert sloshdyn.__version__ in cluster.kwargs["image"]   # the image of this version
    assert cluster.status.name == "closed"
    check_study(namespace, tmp_path)
    assert "points computed; 0 failed" in capsys.readouterr().out


def test_a_recipe_with_a_keyword_the_real_class_lacks_fails():
    """The stand-in is strict: what the real class would refuse, it refuses."""
    stand_in = local_cluster_class(SLURM_KEYWORDS, lambda kw: 0)
    with pytest.raises(TypeError, match="unexpected keyword arguments"):
        stand_in(cores=8, memory="16GB", partition="x")      # SLURM's word; the class's: queue
