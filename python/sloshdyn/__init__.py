"""sloshdyn: liquid sloshing in a partially filled tank on elastic rods under horizontal ground
excitation, by the equivalent mechanical model of Farid & Gendelman (a pendulum that hits the
tank walls through a high-power smooth potential). Numerics run in the Fortran core.
"""

from ._errors import (CapacityError, ConvergenceError, FileError, InputError, IntegrationError,
                      LapackError, SingularMatrixError, SloshdynError)
from ._version import __version__
# value types (they import no analysis)
from .parameters import Parameters, TankPendulum, tank_pendulum
from .options import Chart, Continuation, Integration, Lyapunov, Shooting, Steady
from .ground import DesignSpectrum, GroundMotion, Spectrum, acceleration_factor
from .tank import DesignCodes, Tank
# analyses
from .model import (Equilibria, Equilibrium, EquilibriumAngles, LinearModes, Motion, equilibria,
                    equilibrium_angles, equations_of_motion, frequency_ratio, kappa_for_detuning,
                    linear_modes)
from .simulation import (AmplitudeSpectrum, Ensemble, Simulation, SteadyState, Sweep,
                         amplitude_sweep, beat_period, frequency_sweep, poincare_section,
                         simulate, simulate_ensemble, spectrum, steady_state, sweep_values)
from .asymptotics import (FrequencyResponse, ModalCoefficients, SlowFlowCycle, SpecialPoint,
                          frequency_response, modal_coefficients, nonresonant_amplitudes,
                          slow_flow_cycle)
from .periodic import (Criticality, LyapunovExponent, PeriodicBranch, PeriodicOrbit,
                       PeriodicSpecialPoint,
                       lyapunov_exponent, periodic_orbit, periodic_response)
from .research import (CycleSpecialPoint, LyapunovSpectrum, SlowFlowCycles, lyapunov_spectrum,
                       slow_flow_cycles)
from .charts import Codim2Point, Curve, StabilityChart, stability_chart
from .seismic import (HarmonicSweep, SeismicResponse, SeismicTimes, harmonic_sweep,
                      seismic_defaults, seismic_response)
from .pressure import SeismicPressures, WallPressure, seismic_pressures, wall_pressure
from .design import DesignCheck, design_check
from .structure import TankStructure
from . import spatial  # the spatial model and swirl (issue 26): sloshdyn.spatial.*
from . import export  # branches, curves and studies to xarray and CSV (issue 42): sloshdyn.export.*
from .studies import (FragilityFit, basins, fit_fragility, fragility_study, impact_parameters,
                      response_map)
# the namelist input, and the calc sheet that runs it
from .namelist import Input, read_namelist
from .report import CalcSheet, design_report

__all__ = [
    "CapacityError", "ConvergenceError", "Equilibria", "Equilibrium", "EquilibriumAngles",
    "FileError", "Input",
    "InputError", "IntegrationError", "LapackError", "LinearModes", "Motion", "Parameters",
    "SingularMatrixError", "SloshdynError", "TankPendulum", "equilibria", "equilibrium_angles",
    "equations_of_motion", "frequency_ratio", "kappa_for_detuning", "linear_modes",
    "read_namelist", "tank_pendulum",
    "AmplitudeSpectrum", "Integration", "Simulation", "Steady", "SteadyState", "Sweep", "amplitude_sweep",
    "beat_period", "frequency_sweep", "poincare_section", "simulate", "spectrum", "steady_state",
    "sweep_values", "Ensemble", "simulate_ensemble",
    "ModalCoefficients", "modal_coefficients", "Continuation", "FrequencyResponse", "SpecialPoint", "frequency_response",
    "nonresonant_amplitudes", "SlowFlowCycle", "slow_flow_cycle", "PeriodicBranch",
    "PeriodicOrbit", "PeriodicSpecialPoint", "Criticality", "Lyapunov", "LyapunovExponent",
    "Shooting",
    "lyapunov_exponent", "periodic_orbit", "periodic_response",
    "DesignCodes", "GroundMotion", "HarmonicSweep", "SeismicResponse", "SeismicTimes",
    "DesignSpectrum", "DesignCheck", "design_check", "TankStructure",
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
        import importlib    # the plot extra: loaded on first use
        return importlib.import_module(f".{name}", __name__)
    raise AttributeError(f"module 'sloshdyn' has no attribute {name!r}")
