"""Parameter studies on Dask: response maps in (forcing frequency, amplitude), basins of
attraction, the impact parameters of the paper's continuation, and fragility studies with the
lognormal fragility fit. Each study is cut into tasks of many points; each task calls the
Fortran core once (steady states, shooting and the classification stay there; the bridge
releases the GIL, so threads run at once). Results come back as an xarray Dataset whose
dimensions are the study's axes, with units and descriptions in the attributes, and are written
to a Zarr store as tasks finish: rerunning the same study on the same store resumes it
(finished points are not recomputed), a store made by other settings is refused.

The engine is in `engine` (a study is a `Plan` that `run_plan` runs), its store in `store`, its
cluster and workers in `cluster`; each kind of study is a
module: `response`, `basins`, `impact`, `fragility`; `points` holds what the studies of steady
states share. Dask, xarray and Zarr are imported on first use, so `import sloshdyn` stays light.
"""

from .basins import basins
from .cluster import GRACE_TIME, WORKER_KIND
from .engine import (MAX_POINTS_PER_TASK, MIN_POINTS_PER_TASK, TASKS_PER_WORKER,
                     auto_points_per_task, run_plan)
from .fragility import FragilityFit, fit_fragility, fragility_study
from .impact import FIG15_ORDER, FIG16_CLOSE_TO_UNITY, impact_parameters, paper_statements
from .points import MOTION_CODES, MOTIONS
from .response import response_map

__all__ = ["FIG15_ORDER", "FIG16_CLOSE_TO_UNITY", "FragilityFit", "GRACE_TIME",
           "MAX_POINTS_PER_TASK",
           "MIN_POINTS_PER_TASK", "MOTIONS", "MOTION_CODES", "TASKS_PER_WORKER", "WORKER_KIND",
           "auto_points_per_task", "basins", "fit_fragility", "fragility_study",
           "impact_parameters", "paper_statements", "response_map", "run_plan"]
