"""sloshdyn: liquid sloshing in a partially filled tank on elastic rods under horizontal ground
excitation, by the equivalent mechanical model of Farid & Gendelman (a pendulum that hits the
tank walls through a high-power smooth potential). Numerics run in the Fortran core.
"""

from .asymptotics import (Continuation, FrequencyResponse, ModalCoefficients, SlowFlowCycle,
                          SpecialPoint, frequency_response, modal_coefficients,
                          nonresonant_amplitudes, slow_flow_cycle)
from ._errors import (CapacityError, ConvergenceError, FileError, InputError, IntegrationError,
                      LapackError, SingularMatrixError, SloshdynError)
from .model import (Equilibria, Equilibrium, EquilibriumAngles, LinearModes, Motion, equilibria,
                    equilibrium_angles, equations_of_motion, frequency_ratio, kappa_for_detuning,
                    linear_modes)
from .periodic import (Lyapunov, LyapunovExponent, PeriodicBranch, PeriodicOrbit,
                       PeriodicSpecialPoint, Shooting, lyapunov_exponent, periodic_orbit,
                       periodic_response)
from .research import (CycleSpecialPoint, LyapunovSpectrum, SlowFlowCycles, lyapunov_spectrum,
                       slow_flow_cycles)
from .parameters import Input, Parameters, TankPendulum, read_namelist, tank_pendulum
from .charts import Chart, Codim2Point, Curve, StabilityChart, stability_chart
from .seismic import (DesignCodes, GroundMotion, HarmonicSweep, SeismicResponse, SeismicTimes,
                      Spectrum, Tank, acceleration_factor, harmonic_sweep, seismic_defaults,
                      seismic_response)
from .design import DesignCheck, DesignSpectrum, design_check
from .studies import (FragilityFit, basins, fit_fragility, fragility_study, impact_parameters,
                      response_map)
from .simulation import (AmplitudeSpectrum, Integration, Simulation, Steady, SteadyState, Sweep,
                         amplitude_sweep, beat_period, frequency_sweep, poincare_section, simulate, spectrum,
                         steady_state, sweep_values)
from .pressure import SeismicPressures, WallPressure, seismic_pressures, wall_pressure
from . import spatial  # noqa: E402  the spatial model and swirl (issue 26): sloshdyn.spatial.*
from .report import CalcSheet, design_report  # noqa: E402  the calc sheet (issue 25)

from importlib.metadata import version as _installed_version  # noqa: E402

#: the version set once, in meson.build's project() (installed with the package's metadata)
__version__ = _installed_version(__name__)

__all__ = [
    "CapacityError", "ConvergenceError", "Equilibria", "Equilibrium", "EquilibriumAngles",
    "FileError", "Input",
    "InputError", "IntegrationError", "LapackError", "LinearModes", "Motion", "Parameters",
    "SingularMatrixError", "SloshdynError", "TankPendulum", "equilibria", "equilibrium_angles",
    "equations_of_motion", "frequency_ratio", "kappa_for_detuning", "linear_modes",
    "read_namelist", "tank_pendulum",
    "AmplitudeSpectrum", "Integration", "Simulation", "Steady", "SteadyState", "Sweep", "amplitude_sweep",
    "beat_period", "frequency_sweep", "poincare_section", "simulate", "spectrum", "steady_state",
    "sweep_values",
    "ModalCoefficients", "modal_coefficients", "Continuation", "FrequencyResponse", "SpecialPoint", "frequency_response",
    "nonresonant_amplitudes", "SlowFlowCycle", "slow_flow_cycle", "PeriodicBranch",
    "PeriodicOrbit", "PeriodicSpecialPoint", "Lyapunov", "LyapunovExponent", "Shooting",
    "lyapunov_exponent", "periodic_orbit", "periodic_response",
    "DesignCodes", "GroundMotion", "HarmonicSweep", "SeismicResponse", "SeismicTimes",
    "DesignSpectrum", "DesignCheck", "design_check",
    "Spectrum", "Tank",
    "acceleration_factor", "harmonic_sweep", "seismic_defaults", "seismic_response",
    "Chart", "Codim2Point", "Curve", "StabilityChart", "stability_chart",
    "FragilityFit", "basins", "fit_fragility", "fragility_study", "impact_parameters",
    "response_map",
    "LyapunovSpectrum", "lyapunov_spectrum", "CycleSpecialPoint", "SlowFlowCycles",
    "slow_flow_cycles",
    "WallPressure", "wall_pressure", "SeismicPressures", "seismic_pressures",
    "CalcSheet", "design_report",
]


def __getattr__(name):
    """plotting, figures, reference and cli load matplotlib and friends: import them on use."""
    if name in ("plotting", "figures", "reference", "cli"):
        import importlib
        return importlib.import_module(f".{name}", __name__)
    raise AttributeError(f"module 'sloshdyn' has no attribute {name!r}")
