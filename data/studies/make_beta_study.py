"""The contact model as a documented choice (issue 23, item 3): the pendulum model's peak impact
force, base shear and overturning moment of a tank against the wall stiffness beta over decades
(and the wall dissipation delta), for four records whose free wave clearly exceeds the
freeboard, beside the roof verdict (judged on the free wave, the same for every beta) and the
roof loads of the free wave (sloshdyn_roof). Writes data/studies/beta_study.csv. Run from the
repository root after a build:  python data/studies/make_beta_study.py

beta_study.csv was made when a tank's loads were the impact model's; since issue 37 the
loads are contact-free (docs/model.md, "Loads") and only the impact force (roof_contact =
'impact') still depends on beta and delta."""

import csv
import pathlib
import time

import numpy as np

import sloshdyn

HERE = pathlib.Path(__file__).parent
#: the issue's tank: 10 m across, 6 m of water, 1.0 m freeboard, on 2 Hz supports
TANK = dict(radius=5.0, liquid_depth=6.0, freeboard=1.0, liquid_density=1000.0, tank_mass=5.0e4,
            support_frequency=2.0)
BETAS = [1.0, 10.0, 100.0, 1000.0, 10000.0]
DELTAS = [0.01, 0.1, 1.0]
#: the free wave's height over the freeboard each record is scaled to
RATIO = 1.5
OUT = HERE / "beta_study.csv"


def records():
    """Four records (dt = 0.01 s, m/s^2): the example noise record, a burst at the sloshing
    frequency, a chirp through it, a decaying pulse train (tests/python/test_roof_and_peaks
    uses them too)."""
    f = 1 / sloshdyn.Tank(**TANK).sloshing_period
    t = np.arange(0, 25, 0.01)
    kt = sloshdyn.GroundMotion.from_file(HERE.parent / "examples" / "records" / "synthetic_kt.AT2")
    return {"synthetic_kt": kt.acceleration,
            "burst": np.sin(2 * np.pi * f * t) * np.exp(-((t - 8) / 4) ** 2),
            "chirp": np.sin(2 * np.pi * (0.5 * f + 0.04 * f * t) * t) * np.minimum(1, t / 3)
            * np.maximum(0, 1 - t / 25),
            "pulses": np.sin(2 * np.pi * 2.5 * f * t) * np.exp(-t / 5)}


def scaled(acceleration, ratio=RATIO):
    """The record scaled so that the free wave's height is `ratio` x the freeboard (the free
    wave is nearly linear in the scale; one correction step), and the scale."""
    scale = 1.0
    for _ in range(2):
        ground = sloshdyn.GroundMotion(dt=0.01, acceleration=acceleration * scale,
                                       units="m/s^2")
        run = sloshdyn.seismic_response(sloshdyn.Tank(**TANK), ground)
        scale *= ratio * TANK["freeboard"] / run.peak_table["free_wave_height"]
    return sloshdyn.GroundMotion(dt=0.01, acceleration=acceleration * scale,
                                 units="m/s^2"), scale


def main():
    rows = []
    start = time.time()
    for name, acceleration in records().items():
        ground, scale = scaled(acceleration)
        for delta in DELTAS:
            for beta in BETAS:
                tank = sloshdyn.Tank(**TANK, impact_stiffness=beta, impact_damping=delta,
                                     roof_contact="impact")
                run = sloshdyn.seismic_response(tank, ground)
                p = run.peak_table
                rows.append([name, scale, np.max(np.abs(ground.acceleration)), delta, beta,
                             p["peak_impact_force"], p["peak_base_shear"],
                             p["peak_overturning_moment"], p["peak_wave_height"],
                             np.max(np.abs(run.x1)), p["roof_reached"], p["first_roof_time"],
                             p["free_wave_height"], p["roof_uplift_force"],
                             p["confined_convective_mass"]])
                print(f"{name:13s} delta {delta:5g} beta {beta:7g}: impact "
                      f"{p['peak_impact_force'] / 1e6:9.4g} MN, shear "
                      f"{p['peak_base_shear'] / 1e6:9.4g} MN, moment "
                      f"{p['peak_overturning_moment'] / 1e6:9.4g} MN m, max|x1| "
                      f"{rows[-1][9]:.4g} ({time.time() - start:.0f} s)", flush=True)
    with open(OUT, "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["record", "scale", "pga [m/s^2]", "delta", "beta",
                         "peak_impact_force [N]", "peak_base_shear [N]",
                         "peak_overturning_moment [N m]", "peak_wave_height [m]", "max_x1",
                         "roof_reached", "first_roof_time [s]", "free_wave_height [m]",
                         "roof_uplift_force [N]", "confined_convective_mass [kg]"])
        writer.writerows(rows)
    print(f"wrote {len(rows)} rows to {OUT}")


if __name__ == "__main__":
    main()
