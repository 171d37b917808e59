"""A fingerprint (SHA-256) of single-path results, to compare two builds bit for bit (issue 43:
the ensemble's refactoring of the integrator must leave every single run's bits alone).

    python benchmarks/same_bits.py                          # this build
    PYTHONPATH=/tmp/main-site python benchmarks/same_bits.py  # another (pip install --target)

Covers: simulate (rk45, dop853, vern9, auto at rtol 1e-6, 1e-9, 1e-12; the Fig 14 case and
impacts at A = 2; outputs inside steps, i.e. dense output; the work counts), frequency sweeps
and steady states (the points of the studies) for each method, a periodic orbit and a
Lyapunov exponent. Equal fingerprints: equal bits."""

import hashlib
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import sloshdyn                             # noqa: E402
from peers import fig14_parameters          # noqa: E402

digest = hashlib.sha256()


def add(x):
    digest.update(np.ascontiguousarray(np.asarray(x, dtype=float)).tobytes())


def floats(result):
    return [v for v in vars(result).values() if isinstance(v, float)]


p = fig14_parameters()
for method in ("rk45", "dop853", "vern9", None):
    for rtol in (1e-6, 1e-9, 1e-12):
        for q, y0, t_end in ((p, (0.01, 0, 0.01, 0), 600.0), (p.replace(A=2.0, rho=0.513),
                                                                (0, 0, 0, 0), 300.0)):
            kw = dict(rtol=rtol, atol=rtol * 1e-3, **({"method": method} if method else {}))
            r = sloshdyn.simulate(q, t_end, y0, n_out=377, integration=sloshdyn.Integration(**kw))
            add(r.y), add([r.n_rhs, r.n_accepted, r.n_rejected, r.tau_reached])
quick = sloshdyn.Steady(transient_periods=300, settle_tol=0, window_periods=30)
for method in ("rk45", "dop853", "vern9"):
    integration = sloshdyn.Integration(rtol=1e-9, atol=1e-12, method=method)
    sweep = sloshdyn.frequency_sweep(p, np.linspace(0.50, 0.52, 6), steady=quick,
                                     integration=integration)
    add(sweep.values), [add(sweep.column(c)) for c in ("max_x1", "max_u1", "max_x2")]
    st = sloshdyn.steady_state(p.replace(rho=0.513, A=0.2), steady=quick,
                               integration=integration)
    add([st.max_x1, st.max_u2, st.spread]), add(st.poincare)
add(floats(sloshdyn.periodic_orbit(p.replace(rho=0.513))))
add(floats(sloshdyn.lyapunov_exponent(p.replace(rho=0.513))))
print(digest.hexdigest())
