"""The settings of the analyses, one class per namelist group, made from the core's layouts
(`_settings.settings`): fields, defaults and descriptions are the core's, so the namelist and
Python cannot disagree. Value types at the bottom of the package: they import no analysis
(docs/architecture.md, "Python layers")."""

from __future__ import annotations

from . import _core, _tables
from ._settings import settings


@settings("integration")
class Integration:
    """Settings of the integrators (&integration)."""

    @property
    def method_used(self):
        """The method that runs: ``method``, or for 'auto' the one the core picks for rtol
        (rk45 at loose, dop853 at medium, vern9 at tight tolerances; benchmarks/README.md)."""
        return _tables.codes("methods")[
            int(_core.sloshdyn_bridge_simulation.method_used(self.array()))]


@settings("steady")
class Steady:
    """How a steady state is reached and measured (&steady); times in forcing periods
    T = 2 pi/rho."""


@settings("response")
class Continuation:
    """Settings of the branch search and continuation of the slow flow's steady states
    (&response's numbers)."""


@settings("chart")
class Chart:
    """Settings of a stability chart's grid and curves (&chart): the grid has n_x by n_y cells
    (their midpoints); the one-parameter runs in x at n_y values of y seed the curves."""


@settings("shooting")
class Shooting:
    """Settings of the Newton shooting for a periodic orbit."""


@settings("lyapunov")
class Lyapunov:
    """Settings of the Lyapunov exponents (&lyapunov), in forcing periods."""


@settings("design")
class Design:
    """&design: the spectrum the design check uses (a code design spectrum, or
    'ground_motion': the ground motion's) and the codes' factors (docs/namelist.md, &design)."""
