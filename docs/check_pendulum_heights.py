"""Check, by linear potential flow, the heights that docs/model.md ("Loads") and docs/errata.md
(eq 2 d1, eq 3) state for the first sloshing mode of an upright circular cylinder.

Run from anywhere:  python docs/check_pendulum_heights.py   (needs numpy and scipy)
It prints the numbers quoted in docs/errata.md and stops with an AssertionError if one of the
stated relations fails.

The flow (tank frame, z up from the tank bottom, r and angle a about the axis, x = r cos a):
the rigid-body part X'' x plus the first antisymmetric mode q(t) psi with
psi = J1(xi r/R) cos(a) cosh(xi z/R)/cosh(xi h/R), xi the first root of J1'. The linear
dynamic pressure is p = -rho (X'' x + q'' psi), the mode obeys q'' + omega^2 q = -c1 X'' with c1
the coefficient of J1(xi r/R) in the expansion of r, and the free surface rises by
eta = q (xi/R) tanh(xi h/R) J1(xi r/R) cos(a). Every force and moment below is a numerical
integral (scipy.integrate.quad) of p over the wall r = R or the bottom z = 0; nothing is taken
from the closed forms that are then compared.
"""

import math

import numpy as np
from scipy import integrate, special

XI = special.jnp_zeros(1, 1)[0]   # 1.8411837813..., the first root of J1'
RHO = 1000.0                      # kg/m^3 (every height is independent of it)
TANKS = [(5.0, 6.0), (1.0, 1.0), (1.0, 0.3), (1.0, 3.0), (10.0, 5.0)]   # (R, h) [m]


def quad(f, a, b):
    return integrate.quad(f, a, b, epsabs=0, epsrel=1e-13, limit=200)[0]


def first_mode(R, h, xi=XI):
    """Forces [N] and moments [N m] on the liquid per unit X'' [m/s^2] and per unit q'' of the
    wall (r = R) and of the bottom (z = 0), about the horizontal axis through the centre of
    the bottom perpendicular to x; and the mode's coupling c1 [m]."""
    x = xi * h / R
    J1 = special.jv(1, xi)
    shape = lambda z: J1 * math.cosh(xi * z / R) / math.cosh(x)     # psi at the wall, a = 0
    cos2 = math.pi                                                  # int_0^2pi cos^2 a da
    wall = {"force_X": RHO * R * cos2 * quad(lambda z: R, 0, h),
            "moment_X": RHO * R * cos2 * quad(lambda z: R * z, 0, h),
            "force_q": RHO * R * cos2 * quad(shape, 0, h),
            "moment_q": RHO * R * cos2 * quad(lambda z: shape(z) * z, 0, h)}
    # the bottom pushes up on the liquid with p; its moment about that axis is -x p dA
    bottom = {"moment_X": RHO * cos2 * quad(lambda r: r**3, 0, R),
              "moment_q": RHO * cos2 * quad(lambda r: r**2 * special.jv(1, xi * r / R), 0, R)
              / math.cosh(x)}
    c1 = quad(lambda r: r * special.jv(1, xi * r / R) * r, 0, R) / \
        quad(lambda r: special.jv(1, xi * r / R)**2 * r, 0, R)
    return wall, bottom, c1


def heights(R, h):
    """Everything docs/errata.md quotes for one tank, from the integrals of first_mode."""
    wall, bottom, c1 = first_mode(R, h)
    x = XI * h / R
    m_F = RHO * math.pi * R**2 * h
    # the pendulum: its momentum m l theta' is the mode's, force_q q', and its equation
    # theta'' + (g/l) theta = -X''/l is the mode's: m = c1 force_q, l = g/omega^2
    m = c1 * wall["force_q"]
    l = R / XI / math.tanh(x)
    h_c = wall["moment_q"] / wall["force_q"]                         # wall pressures only
    h_c_total = (wall["moment_q"] + bottom["moment_q"]) / wall["force_q"]   # wall and bottom
    wave = (XI / R) * math.tanh(x) * special.jv(1, XI) * m * l / wall["force_q"]   # eta/theta
    m0 = m_F - m
    h0 = (wall["moment_X"] - m * h_c) / m0      # sloshdyn's impulsive height
    # eq (2) and (3) as printed (xi rounded to 1.84), depths below the free surface
    l_2 = R / 1.84 / math.tanh(1.84 * h / R)
    m_2 = m_F * R / (2.2 * h) * math.tanh(1.84 * h / R)
    d1_printed = R / 3.68 / math.sinh(3.68 * h / R)
    m0_2 = m_F - m_2
    d0_printed = m_F / m0_2 * (h / 2 - R**2 / (2 * h)) - (d1_printed + l_2) * m_2 / m0_2
    first_moment_eq3 = m0_2 * (h - d0_printed) + m_2 * (h - d1_printed - l_2)
    return {
        "m_F [kg]": m_F, "m [kg]": m, "m eq (2) [kg]": m_2, "l [m]": l, "l eq (2) [m]": l_2,
        "wall force per X'' / m_F": wall["force_X"] / m_F,
        "wall moment per X'' / m_F [m]": wall["moment_X"] / m_F,
        "bottom moment per X'' / m_F [m]": bottom["moment_X"] / m_F,
        "R^2/(4h) [m]": R**2 / (4 * h),
        "wave per theta [m]": wave, "2R/(xi^2 - 1) [m]": 2 * R / (XI**2 - 1),
        "h_c (wall) [m]": h_c, "h - (R/xi) tanh(x/2) [m]": h - R / XI * math.tanh(x / 2),
        "h_c' (wall + bottom) [m]": h_c_total,
        "h_c + (R/xi) csch x [m]": h - R / XI * math.tanh(x / 2) + R / XI / math.sinh(x),
        "h0 [m]": h0, "m0 h0 + m h_c - m_F h/2 [kg m]": m0 * h0 + m * h_c - m_F * h / 2,
        "h_c + l [m]": h_c + l, "h + (R/xi) csch x [m]": h + R / XI / math.sinh(x),
        "(R/1.84) csch(1.84 h/R) [m]": R / 1.84 / math.sinh(1.84 * h / R),
        "d1 printed, (R/3.68) csch(3.68 h/R) [m]": d1_printed,
        "eq (3): sum m_i z_i / m_F - h/2 [m]": first_moment_eq3 / m_F - h / 2,
        "R^2/(2h) [m]": R**2 / (2 * h),
    }


def close(a, b, rtol):
    return abs(a - b) <= rtol * max(abs(a), abs(b))


def main():
    for R, h in TANKS:
        v = heights(R, h)
        print(f"R = {R:g} m, h = {h:g} m")
        for name, value in v.items():
            print(f"  {name:42s} {value:.10g}")
        # exact relations (to the quadrature's accuracy)
        assert close(v["wall force per X'' / m_F"], 1.0, 1e-12)
        assert close(v["wall moment per X'' / m_F [m]"], h / 2, 1e-12)
        assert close(v["bottom moment per X'' / m_F [m]"], v["R^2/(4h) [m]"], 1e-12)
        assert close(v["wave per theta [m]"], v["2R/(xi^2 - 1) [m]"], 1e-10)
        assert close(v["h_c (wall) [m]"], v["h - (R/xi) tanh(x/2) [m]"], 1e-10)
        assert close(v["h_c' (wall + bottom) [m]"], v["h_c + (R/xi) csch x [m]"], 1e-10)
        assert close(v["h_c + l [m]"], v["h + (R/xi) csch x [m]"], 1e-10)
        assert abs(v["m0 h0 + m h_c - m_F h/2 [kg m]"]) <= 1e-9 * v["m_F [kg]"] * h
        assert close(v["eq (3): sum m_i z_i / m_F - h/2 [m]"], v["R^2/(2h) [m]"], 1e-10)
        # eq (2)'s l and m round xi to 1.84 and 2/(xi (xi^2 - 1)) to 1/2.2: within 0.2 %
        assert close(v["m [kg]"], v["m eq (2) [kg]"], 2e-3)
        assert close(v["l [m]"], v["l eq (2) [m]"], 2e-3)
    check_dynamic()


def check_dynamic():
    """In time: under a ground acceleration X''(t), the first mode's wall moment (integrated
    pressures) equals m0 h0 a_t + m h_c a_m at every time, and the pendulum hinge force m a_m at
    h_c + l gives that plus m l a_m."""
    R, h, g = 5.0, 6.0, 9.80665
    wall, bottom, c1 = first_mode(R, h)
    omega2 = g * XI / R * math.tanh(XI * h / R)
    m = c1 * wall["force_q"]
    l = g / omega2
    m_F = RHO * math.pi * R**2 * h
    h_c = wall["moment_q"] / wall["force_q"]
    h0 = (wall["moment_X"] - m * h_c) / (m_F - m)
    xdd = lambda t: 0.3 * math.sin(1.3 * t) + 0.2 * math.sin(2.9 * t + 0.4)   # m/s^2
    sol = integrate.solve_ivp(lambda t, y: [y[1], -omega2 * y[0] - c1 * xdd(t)], (0, 30),
                              [0, 0], rtol=1e-11, atol=1e-14, dense_output=True)
    worst, hinge_gap = 0.0, 0.0
    for t in np.linspace(1, 30, 59):
        q = sol.sol(t)[0]
        qdd = -omega2 * q - c1 * xdd(t)
        moment_wall = wall["moment_X"] * xdd(t) + wall["moment_q"] * qdd
        theta_dd = wall["force_q"] * qdd / (m * l)      # m l theta = force_q q
        a_m = xdd(t) + l * theta_dd
        loads = (m_F - m) * h0 * xdd(t) + m * h_c * a_m
        worst = max(worst, abs(moment_wall - loads) / abs(wall["moment_X"] * 0.5))
        hinge = (m_F - m) * h0 * xdd(t) + m * (h_c + l) * a_m
        hinge_gap = max(hinge_gap, abs(hinge - loads - m * l * a_m))
    print(f"dynamic check (R = 5 m, h = 6 m): max |wall moment - (m0 h0 a_t + m h_c a_m)| "
          f"relative {worst:.2e}; hinge-force moment minus that minus m l a_m: {hinge_gap:.2e} N m")
    assert worst < 1e-10 and hinge_gap < 1e-6


if __name__ == "__main__":
    main()
