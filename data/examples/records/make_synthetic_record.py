"""Write synthetic_kt.AT2, the example ground-motion record: NOT a recorded earthquake; and
synthetic_kt_y.AT2, its second horizontal component (the same process, another seed, peak 0.25 g;
tank_two_components.nml).

A stationary Kanai-Tajimi ground acceleration (white noise through a soil filter, ground
frequency 2.5 Hz, damping 0.6) with a Clough-Penzien high-pass (0.25 Hz, damping 0.6) and the
Jennings-Housner-Tsai envelope (rise 2 s, strong motion to 10 s, exponential decay), 30 s at
0.01 s, scaled to a peak of 0.30 g, written in the PEER NGA .AT2 layout (values in g, five per
line). The filters are integrated exactly for a piecewise-constant input (scipy.signal.lsim
with zero-order hold is not used, to keep this to numpy). The seed fixes every digit.

    python data/examples/records/make_synthetic_record.py
"""

from pathlib import Path

import numpy as np

DT, DURATION, PGA_G, SEED = 0.01, 30.0, 0.30, 20261123
PGA_G_Y, SEED_Y = 0.25, 20261124


def second_order_filter(excitation, omega, zeta, dt):
    """Displacement and velocity of x'' + 2 zeta omega x' + omega^2 x = -excitation, exact
    for excitation held constant over each step (state transition by the matrix exponential)."""
    a = np.array([[0.0, 1.0], [-omega**2, -2 * zeta * omega]])
    eigenvalues, vectors = np.linalg.eig(a)
    transition = (vectors @ np.diag(np.exp(eigenvalues * dt)) @ np.linalg.inv(vectors)).real
    forcing = np.linalg.solve(a, (transition - np.eye(2)) @ np.array([0.0, -1.0]))
    state = np.zeros(2)
    out = np.empty((len(excitation), 2))
    for i, u in enumerate(excitation):
        out[i] = state
        state = transition @ state + forcing * u
    return out[:, 0], out[:, 1]


def write_record(name, seed, pga_g):
    rng = np.random.default_rng(seed)
    n = int(round(DURATION / DT)) + 1
    t = DT * np.arange(n)
    noise = rng.standard_normal(n) / np.sqrt(DT)
    # Kanai-Tajimi: the absolute acceleration of the soil oscillator
    wg, zg = 2 * np.pi * 2.5, 0.6
    x, v = second_order_filter(noise, wg, zg, DT)
    kanai_tajimi = -(2 * zg * wg * v + wg**2 * x)
    # Clough-Penzien: remove the long periods that would make the ground drift
    wf, zf = 2 * np.pi * 0.25, 0.6
    xf, vf = second_order_filter(-kanai_tajimi, wf, zf, DT)
    accel = wf**2 * xf + 2 * zf * wf * vf
    envelope = np.where(t < 2, (t / 2) ** 2, np.where(t < 10, 1.0, np.exp(-0.3 * (t - 10))))
    accel *= envelope
    accel *= pga_g / np.max(np.abs(accel))
    lines = ["SYNTHETIC RECORD (not an earthquake): Kanai-Tajimi/Clough-Penzien noise",
             f"written by make_synthetic_record.py, seed {seed}; sloshdyn example data",
             "ACCELERATION TIME SERIES IN UNITS OF G",
             f"NPTS= {n:7d}, DT= {DT:.4f} SEC"]
    for k in range(0, n, 5):
        lines.append("".join(f"{value:15.7E}" for value in accel[k:k + 5]))
    path = Path(__file__).with_name(name)
    path.write_text("\n".join(lines) + "\n")
    print(f"{path}: {n} samples, dt = {DT} s, peak {pga_g} g")


def main():
    write_record("synthetic_kt.AT2", SEED, PGA_G)
    write_record("synthetic_kt_y.AT2", SEED_Y, PGA_G_Y)


if __name__ == "__main__":
    main()
