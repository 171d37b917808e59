"""When does a seismic result depend on the contact model (issue 23, item 3)? The criterion of
SeismicResponse.beta_sensitive (sloshdyn_seismic: the model's wall force, impact_force, reaches
0.001 m g) against what beta and delta actually change: four records scaled so that the free
wave reaches 0.3 to 1.5 times the freeboard, each run with (beta, delta) = (1, 0.1), (10, 0.1),
(100, 0.1), (10, 1); per record and ratio the spread (max - min)/max of the peak base shear and
overturning moment over the four, and the flag and wall force of the default (10, 0.1). Writes
data/studies/beta_sensitivity.csv. Run from the repository root after a build:
    python data/studies/make_beta_sensitivity.py

beta_sensitivity.csv was made when a tank's loads were the impact model's; since issue 37 they
are contact-free (docs/model.md, "Loads"), and the flag is the opt-in impact model's
(roof_contact = 'impact')."""

import csv
import pathlib
import time

import sloshdyn
from make_beta_study import TANK, records, scaled

HERE = pathlib.Path(__file__).parent
RATIOS = [0.3, 0.45, 0.55, 0.65, 1.0, 1.5]
CONTACTS = [(1.0, 0.1), (10.0, 0.1), (100.0, 0.1), (10.0, 1.0)]
OUT = HERE / "beta_sensitivity.csv"


def spread(values):
    return (max(values) - min(values)) / max(values)


def main():
    rows = []
    start = time.time()
    for name, acceleration in records().items():
        for ratio in RATIOS:
            ground, _ = scaled(acceleration, ratio)
            runs = {}
            for beta, delta in CONTACTS:
                tank = sloshdyn.Tank(**TANK, impact_stiffness=beta, impact_damping=delta,
                                     roof_contact="impact")
                runs[beta, delta] = (tank, sloshdyn.seismic_response(tank, ground))
            tank, default = runs[10.0, 0.1]
            p = default.peak_table
            shears = [r.peak_table["peak_base_shear"] for _, r in runs.values()]
            moments = [r.peak_table["peak_overturning_moment"] for _, r in runs.values()]
            rows.append({"record": name, "free_wave_ratio": ratio,
                         "free_wave_height [m]": p["free_wave_height"],
                         "wall_force_over_mg": p["peak_impact_force"] /
                         (tank.convective_mass * tank.gravity),
                         "beta_sensitive": int(default.beta_sensitive),
                         "base_shear_spread": spread(shears),
                         "overturning_moment_spread": spread(moments)})
            print(rows[-1])
    with open(OUT, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    print(f"{len(rows)} rows in {time.time() - start:.0f} s -> {OUT}")


if __name__ == "__main__":
    main()
