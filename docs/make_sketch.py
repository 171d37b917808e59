"""Draw the two sketches of docs/model.md, beside this file:

- model_sketch.png: the equivalent mechanical model as sloshdyn implements it (a tank on two
  parallel rods over a moving base, the sloshing pendulum inside, the wall angle theta0, the
  freeboard up to the roof);
- tank_loads_sketch.png: a tank in SI units and its loads (heights from the tank bottom, the
  wave at the wall against the freeboard, the masses and the forces that accelerate them, the
  base shear and the overturning moment).

Run from anywhere:  python docs/make_sketch.py   (needs matplotlib)
The drawings are schematic: the lengths are not to scale, the angles are exaggerated.
"""

import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Arc, Circle, FancyArrowPatch, Polygon, Rectangle  # noqa: E402

OUT = Path(__file__).with_name("model_sketch.png")
OUT_LOADS = Path(__file__).with_name("tank_loads_sketch.png")

# geometry of the drawing (drawing units, not to scale)
PHI = math.radians(14)      # rod angle, drawn positive: the tank is displaced toward +x
THETA = math.radians(22)    # pendulum angle, drawn positive: the mass m is toward +x
THETA0 = math.radians(40)   # wall angle
BASE_Y = 0.45               # top of the moving base
ROD_L = 2.7                 # L
PIVOTS_X = (1.2, 6.6)       # rod pivots on the base
TANK_H = 5.5                # tank wall height
LIQUID_H = 3.9              # h
D1 = 0.55                   # d1: hinge below the free surface
PEND_L = 2.3                # l
D0 = 3.2                    # d0: m0 below the free surface
WALL_RAY = 2.9              # length of the drawn rays theta = +-theta0

BLUE, RED, GREY, GREEN = "#1f5fa8", "#c0392b", "#555555", "#1e8449"


def dimension(ax, p, q, text, offset=(0, 0), color="black", text_offset=(0, 0), **kw):
    """A double-headed dimension arrow from p to q (shifted by offset) with its label."""
    p = (p[0] + offset[0], p[1] + offset[1])
    q = (q[0] + offset[0], q[1] + offset[1])
    ax.add_patch(FancyArrowPatch(p, q, arrowstyle="<|-|>", mutation_scale=11, color=color,
                                 lw=1.1, shrinkA=0, shrinkB=0))
    mid = ((p[0] + q[0]) / 2 + text_offset[0], (p[1] + q[1]) / 2 + text_offset[1])
    ax.text(*mid, text, color=color, ha="center", va="center", fontsize=13,
            bbox=dict(fc="white", ec="none", pad=0.5), **kw)


def angle_arc(ax, centre, radius, start_deg, end_deg, text, text_at, color):
    """An arc from start_deg to end_deg (counter-clockwise, degrees) with an arrow head at its end
    and a label."""
    lo, hi = sorted((start_deg, end_deg))
    ax.add_patch(Arc(centre, 2 * radius, 2 * radius, theta1=lo, theta2=hi, color=color, lw=1.3))
    end = math.radians(end_deg)
    tip = (centre[0] + radius * math.cos(end), centre[1] + radius * math.sin(end))
    sign = 1 if end_deg > start_deg else -1
    before = math.radians(end_deg - sign * 6)
    tail = (centre[0] + radius * math.cos(before), centre[1] + radius * math.sin(before))
    ax.add_patch(FancyArrowPatch(tail, tip, arrowstyle="-|>", mutation_scale=12, color=color,
                                 lw=1.3, shrinkA=0, shrinkB=0))
    ax.text(*text_at, text, color=color, fontsize=13, ha="center", va="center")


def spring(ax, centre, color=GREY):
    """A small spiral: the torsional spring k and damper c at a rod pivot."""
    ts = [i / 60 for i in range(61)]
    xs = [centre[0] + (0.06 + 0.16 * t) * math.cos(5 * math.pi * t) for t in ts]
    ys = [centre[1] + (0.06 + 0.16 * t) * math.sin(5 * math.pi * t) for t in ts]
    ax.plot(xs, ys, color=color, lw=1.1)


def gravity_and_x(ax, g_x):
    """The arrows of gravity (at x = g_x, top right) and of +x (top left)."""
    ax.add_patch(FancyArrowPatch((g_x, 9.2), (g_x, 8.3), arrowstyle="-|>", mutation_scale=14,
                                 color="black", lw=1.5))
    ax.text(g_x + 0.15, 8.75, "g", fontsize=14, va="center")
    ax.add_patch(FancyArrowPatch((-0.4, 9.0), (0.6, 9.0), arrowstyle="-|>", mutation_scale=14,
                                 color="black", lw=1.5))
    ax.text(0.75, 9.0, "+x", fontsize=14, va="center")


def finish(fig, ax, notes, xlim, ylim, out):
    """The notes under the drawing, the limits, and the PNG written to out."""
    ax.text(-0.6, -1.0, notes, fontsize=12.5, va="top", family="DejaVu Sans")
    ax.set_xlim(*xlim)
    ax.set_ylim(*ylim)
    fig.tight_layout()
    fig.savefig(out, dpi=100)
    plt.close(fig)
    print(f"wrote {out}")


def main():
    fig, ax = plt.subplots(figsize=(12, 9.6))
    ax.set_aspect("equal")
    ax.axis("off")

    # ground (fixed) and the base, which moves horizontally by u(t)
    ax.plot([-0.6, 8.6], [0, 0], color="black", lw=1.2)
    for x in [i * 0.35 - 0.6 for i in range(27)]:
        ax.plot([x, x - 0.22], [0, -0.22], color="black", lw=0.8)
    ax.add_patch(Rectangle((0.9, 0.05), 5.4, BASE_Y - 0.05, fc="#d5d5d5", ec="black", lw=1.2))
    for x in (1.3, 5.9):
        ax.add_patch(Circle((x, 0.025 + 0.0), 0.025, fc="black"))
    ax.plot([0.9, 0.9], [-0.55, 0.05], color=GREY, lw=1, ls=":")
    ax.add_patch(FancyArrowPatch((0.9, -0.45), (2.1, -0.45), arrowstyle="-|>", mutation_scale=14,
                                 color=RED, lw=1.6))
    ax.text(2.25, -0.45, "u(t): base displacement (+ toward +x)", color=RED, fontsize=13,
            va="center")
    ax.text(3.6, 0.25, "base", fontsize=12, ha="center", va="center", color=GREY)

    # the rods (parallel: the tank translates without rotating)
    tops = []
    for x in PIVOTS_X:
        pivot = (x, BASE_Y)
        top = (x + ROD_L * math.sin(PHI), BASE_Y + ROD_L * math.cos(PHI))
        tops.append(top)
        ax.plot([pivot[0], top[0]], [pivot[1], top[1]], color="black", lw=3)
        ax.add_patch(Circle(pivot, 0.07, fc="white", ec="black", lw=1.3, zorder=5))
        ax.add_patch(Circle(top, 0.07, fc="white", ec="black", lw=1.3, zorder=5))
        spring(ax, pivot)
    ax.text(PIVOTS_X[1] + 0.3, BASE_Y + 0.1, "k, c (torsional spring\nand damper at each pivot)",
            fontsize=12, color=GREY, va="bottom")
    # phi from the vertical at the left pivot
    left = (PIVOTS_X[0], BASE_Y)
    ax.plot([left[0], left[0]], [left[1], left[1] + 2.3], color=GREY, ls="--", lw=1)
    angle_arc(ax, left, 1.55, 90, 90 - math.degrees(PHI), "φ", (left[0] + 0.2, left[1] + 1.85),
              BLUE)
    dimension(ax, left, tops[0], "L", offset=(-0.32, 0.08), text_offset=(-0.22, 0))

    # the tank: upright, carried at the rod tops
    tank_x0, tank_y0 = tops[0][0] - 0.2, tops[0][1]
    tank_w = tops[1][0] - tops[0][0] + 0.4
    axis_x = tank_x0 + tank_w / 2
    surface_y = tank_y0 + LIQUID_H
    ax.add_patch(Rectangle((tank_x0, tank_y0), tank_w, LIQUID_H, fc="#d6eaf8", ec="none"))
    ax.add_patch(Rectangle((tank_x0, tank_y0), tank_w, TANK_H, fc="none", ec="black", lw=2.2))
    ax.plot([tank_x0, tank_x0 + tank_w], [surface_y, surface_y], color=BLUE, ls="--", lw=1.6)
    ax.text(tank_x0 + tank_w + 0.95, surface_y, "undisturbed\nfree surface", color=BLUE,
            fontsize=12, va="center")
    ax.text(tank_x0 + 0.6, tank_y0 + TANK_H + 0.08, "roof", fontsize=12, ha="center",
            va="bottom")
    ax.text(tank_x0 + 0.15, tank_y0 + TANK_H - 0.3,
            "tank: total mass M\n(container + liquid)", fontsize=13, va="top")
    ax.plot([axis_x, axis_x], [tank_y0 - 0.1, tank_y0 + TANK_H + 0.15], color=GREY, lw=0.9,
            ls="-.")
    ax.text(axis_x, tank_y0 + TANK_H + 0.25, "tank axis (vertical)", fontsize=12, ha="center",
            color=GREY)
    dimension(ax, (axis_x, tank_y0 + TANK_H - 0.95), (tank_x0 + tank_w, tank_y0 + TANK_H - 0.95),
              "R", text_offset=(0, 0.2))
    dimension(ax, (tank_x0 + tank_w, tank_y0), (tank_x0 + tank_w, surface_y), "h",
              offset=(0.45, 0), text_offset=(0.22, 0))
    ax.plot([tank_x0 + tank_w, tank_x0 + tank_w + 0.6], [tank_y0, tank_y0], color=GREY, lw=0.8)
    ax.plot([tank_x0 + tank_w, tank_x0 + tank_w + 0.6], [surface_y, surface_y], color=GREY,
            lw=0.8)
    dimension(ax, (tank_x0 + tank_w, surface_y), (tank_x0 + tank_w, tank_y0 + TANK_H),
              "f", offset=(0.45, 0), text_offset=(0.22, 0))
    ax.plot([tank_x0 + tank_w, tank_x0 + tank_w + 0.6], [tank_y0 + TANK_H, tank_y0 + TANK_H],
            color=GREY, lw=0.8)

    # the sloshing pendulum
    hinge = (axis_x, surface_y - D1)
    bob = (hinge[0] + PEND_L * math.sin(THETA), hinge[1] - PEND_L * math.cos(THETA))
    for sign in (1, -1):   # where it meets the walls, theta = +-theta0
        end = (hinge[0] + sign * WALL_RAY * math.sin(THETA0),
               hinge[1] - WALL_RAY * math.cos(THETA0))
        ax.plot([hinge[0], end[0]], [hinge[1], end[1]], color=RED, ls=":", lw=1.6)
        ax.text(end[0], end[1] - 0.12, "θ = +θ0" if sign > 0 else "θ = −θ0", color=RED,
                fontsize=12.5, va="top", ha="center")
    ax.plot([hinge[0], bob[0]], [hinge[1], bob[1]], color="black", lw=2)
    ax.add_patch(Circle(hinge, 0.06, fc="black", zorder=6))
    ax.add_patch(Circle(bob, 0.2, fc=BLUE, ec="black", lw=1.2, zorder=6))
    ax.text(bob[0] + 0.28, bob[1] - 0.1, "m", fontsize=15, va="center")
    angle_arc(ax, hinge, 1.2, -90, -90 + math.degrees(THETA), "θ",
              (hinge[0] + 0.28, hinge[1] - 1.45), BLUE)
    angle_arc(ax, hinge, 1.0, -90, -90 - math.degrees(THETA0), "θ0",
              (hinge[0] - 0.38, hinge[1] - 1.25), RED)
    normal = (math.cos(THETA), math.sin(THETA))   # perpendicular to the pendulum, toward +x
    dimension(ax, hinge, bob, "l", offset=(0.45 * normal[0], 0.45 * normal[1]),
              text_offset=(0.22 * normal[0], 0.22 * normal[1]))

    # d1 and d0, both measured downward from the free surface
    x_d1 = axis_x - 1.0
    dimension(ax, (x_d1, surface_y), (x_d1, hinge[1]), "", color=GREEN)
    ax.text(x_d1 - 0.12, (surface_y + hinge[1]) / 2, "d1", color=GREEN, fontsize=13, ha="right",
            va="center")
    ax.plot([x_d1 - 0.1, axis_x], [hinge[1], hinge[1]], color=GREEN, lw=0.8, ls=":")
    m0_y = surface_y - D0
    ax.add_patch(Rectangle((axis_x - 0.17, m0_y - 0.17), 0.34, 0.34, fc="#7f8c8d", ec="black",
                           zorder=6))
    ax.text(axis_x + 0.3, m0_y - 0.05, "m0", fontsize=14, va="center")
    x_d0 = axis_x - 2.6
    dimension(ax, (x_d0, surface_y), (x_d0, m0_y), "", color=GREEN)
    ax.text(x_d0 + 0.12, (surface_y + m0_y) / 2 + 0.4, "d0", color=GREEN, fontsize=13,
            ha="left", va="center")
    ax.plot([x_d0 - 0.1, axis_x - 0.17], [m0_y, m0_y], color=GREEN, lw=0.8, ls=":")

    gravity_and_x(ax, 9.9)

    notes = ("Signs: u, φ and θ are positive when the base, the tank and the mass m move toward +x.\n"
             "φ: rod angle from the vertical (the rods stand up from the base; the tank stays upright).\n"
             "θ: pendulum angle from the tank axis; the pendulum meets the walls at θ = ±θ0.\n"
             "m: sloshing mass on the pendulum of length l; m0: the liquid that moves with the tank.\n"
             "d1, d0: distances below the undisturbed free surface (hinge of the pendulum, mass m0).\n"
             "f: freeboard, the undisturbed free surface to the roof; with a tank in SI units\n"
             "θ0 is where the linear wave at the wall reaches the roof (docs/model.md).\n"
             "Schematic: lengths not to scale, angles exaggerated.")
    finish(fig, ax, notes, (-0.8, 10.6), (-3.3, 9.6), OUT)


def force(ax, start, length, text, color=RED):
    """A horizontal force arrow toward +x from start, labelled at its head."""
    ax.add_patch(FancyArrowPatch(start, (start[0] + length, start[1]), arrowstyle="-|>",
                                 mutation_scale=14, color=color, lw=1.8, shrinkA=0, shrinkB=0,
                                 zorder=7))
    ax.text(start[0] + length + 0.1, start[1], text, color=color, fontsize=12.5, va="center")


def loads():
    """tank_loads_sketch.png: the SI quantities of docs/model.md, "A tank in SI units" and
    "Loads"."""
    fig, ax = plt.subplots(figsize=(12, 9.6))
    ax.set_aspect("equal")
    ax.axis("off")
    bottom, x0, width = 1.7, 2.0, 5.0        # tank bottom (z = 0), left wall, diameter 2R
    depth, freeboard, wave = 4.2, 1.2, 0.6   # h, f, eta (drawn), not to scale
    h_c, h_0, h_s = 3.55, 1.5, (depth + freeboard) / 2   # heights above the bottom (drawn)

    # ground, base and the supports (rods with torsional springs, as in model_sketch.png)
    ax.plot([-0.6, 9.6], [0, 0], color="black", lw=1.2)
    for x in [i * 0.35 - 0.6 for i in range(30)]:
        ax.plot([x, x - 0.22], [0, -0.22], color="black", lw=0.8)
    ax.add_patch(Rectangle((x0 - 0.1, 0.05), width + 0.2, 0.35, fc="#d5d5d5", ec="black", lw=1.2))
    ax.add_patch(FancyArrowPatch((x0 - 0.1, -0.5), (x0 + 1.1, -0.5), arrowstyle="-|>",
                                 mutation_scale=14, color=RED, lw=1.6))
    ax.text(x0 + 1.25, -0.5, "u''(t): ground acceleration (+ toward +x)", color=RED, fontsize=12.5,
            va="center")
    drift = 0.25                          # L sin(phi), drawn
    for x in (x0 + 0.3, x0 + width - 0.3):
        ax.plot([x, x + drift], [0.4, bottom], color="black", lw=3)
        ax.add_patch(Circle((x, 0.4), 0.07, fc="white", ec="black", lw=1.3, zorder=5))
        ax.add_patch(Circle((x + drift, bottom), 0.07, fc="white", ec="black", lw=1.3, zorder=5))
        spring(ax, (x, 0.4))
    ax.text(x0 + width + 0.35, 0.75, "supports: rods of length L with k and c\n(or the frequency "
            "f_s and damping ratio ζ_s)", fontsize=11.5, color=GREY, va="center")
    dimension(ax, (x0 + 0.3, 0.75), (x0 + 0.3 + drift, 0.75), "", color=BLUE)
    ax.text(x0 + 0.15, 0.75, "tank drift L sin φ", color=BLUE, fontsize=12, ha="right",
            va="center")

    # the tank, moved by the drift; the liquid with its surface tilted by the first mode
    x0 += drift
    axis_x = x0 + width / 2
    surface, roof, right = bottom + depth, bottom + depth + freeboard, x0 + width
    ax.add_patch(Polygon([(x0, bottom), (right, bottom), (right, surface + wave),
                          (x0, surface - wave)], fc="#d6eaf8", ec="none"))
    ax.plot([x0, right], [surface - wave, surface + wave], color=BLUE, lw=1.6)
    ax.plot([x0, right], [surface, surface], color=BLUE, ls="--", lw=1.2)
    ax.add_patch(Rectangle((x0, bottom), width, depth + freeboard, fc="none", ec="black", lw=2.4))
    ax.text(axis_x, roof + 0.12, "roof", fontsize=12, ha="center", va="bottom")
    ax.plot([axis_x, axis_x], [bottom - 0.15, roof + 0.05], color=GREY, lw=0.9, ls="-.")
    ax.text(x0 + 0.12, surface + 0.08, "first-mode wave", color=BLUE, fontsize=11, va="bottom")
    ax.text(x0 + 0.12, roof - 0.12, "m_shell: shell and roof\nm0: rigid liquid\n"
            "m: sloshing liquid", fontsize=11.5, va="top")

    # the bottom reference
    ax.plot([x0 - 1.9, right + 0.6], [bottom, bottom], color=GREEN, lw=1.0, ls=":")
    ax.text(x0 - 1.95, bottom - 0.12, "z = 0: tank bottom\n(heights from here)", color=GREEN,
            fontsize=11.5, ha="left", va="top")

    # heights on the right: h, f, and the wave at the +x wall
    for y in (surface, roof):
        ax.plot([right, right + 0.95], [y, y], color=GREY, lw=0.8)
    ax.plot([right, right + 0.5], [surface + wave] * 2, color=GREY, lw=0.8)
    dimension(ax, (right, bottom), (right, surface), "h", offset=(0.75, 0), text_offset=(0.22, 0))
    dimension(ax, (right, surface), (right, roof), "f", offset=(0.75, 0), text_offset=(0.22, 0))
    dimension(ax, (right, surface), (right, surface + wave), "", offset=(0.3, 0), color=BLUE)
    ax.text(right + 0.15, roof + 0.3, "η: wave height at the +x wall, 2R sin θ/(ξ² − 1);\n"
            "the roof is reached when η = f, i.e. |x1| = 1", color=BLUE, fontsize=11.5,
            va="bottom")
    ax.text(right + 0.38, surface + wave / 2, "η", color=BLUE, fontsize=12.5, va="center")

    # heights on the left: h0, (h + f)/2, h_c; each mass and the force that accelerates it
    for k, (height, label) in enumerate([(h_0, "h0"), (h_s, "(h + f)/2"), (h_c, "h_c")]):
        x = x0 - 0.3 - 0.5 * k
        ax.plot([x - 0.1, x0], [bottom + height] * 2, color=GREEN, lw=0.8, ls=":")
        dimension(ax, (x, bottom), (x, bottom + height), "", color=GREEN)
        ax.text(x - 0.08, bottom + height - 0.35, label, color=GREEN, fontsize=12.5, ha="right",
                va="center", bbox=dict(fc="white", ec="none", pad=0.3))
    ax.add_patch(Rectangle((axis_x - 0.17, bottom + h_0 - 0.17), 0.34, 0.34, fc="#7f8c8d",
                           ec="black", zorder=6))
    force(ax, (axis_x + 0.2, bottom + h_0), 0.8, "m0 a_t")
    ax.add_patch(Polygon([(axis_x - 0.2, bottom + h_s - 0.17), (axis_x + 0.2, bottom + h_s - 0.17),
                          (axis_x, bottom + h_s + 0.2)], fc="#f5cba7", ec="black", zorder=6))
    force(ax, (axis_x + 0.22, bottom + h_s), 0.8, "m_shell a_t")
    sloshed = 0.45                        # l sin(theta), drawn
    ax.add_patch(Circle((axis_x + sloshed, bottom + h_c), 0.2, fc=BLUE, ec="black", lw=1.2,
                        zorder=6))
    dimension(ax, (axis_x, bottom + h_c + 0.38), (axis_x + sloshed, bottom + h_c + 0.38), "",
              color=BLUE)
    ax.text(axis_x - 0.1, bottom + h_c + 0.38, "l sin θ", color=BLUE, fontsize=12, ha="right",
            va="center")
    force(ax, (axis_x + sloshed + 0.22, bottom + h_c), 0.8, "m a_m")

    # the base shear (at the supports) and the overturning moment about the bottom centre
    force(ax, (axis_x - 1.2, 0.85), 0.8, "V: base shear", color="black")
    # clockwise here: the sense in which forces toward +x above the bottom turn the tank
    ax.add_patch(Arc((axis_x, bottom), 0.9, 0.9, theta1=200, theta2=340, color="black", lw=1.5))
    ax.add_patch(FancyArrowPatch((axis_x - 0.36, bottom - 0.27), (axis_x - 0.44, bottom - 0.1),
                                 arrowstyle="-|>", mutation_scale=12, color="black", lw=1.5))
    ax.text(axis_x + 0.6, bottom - 0.3, "overturning\nmoment", fontsize=11.5, va="center")

    gravity_and_x(ax, 10.6)

    notes = ("a_t, a_m: accelerations toward +x of the tank and of the sloshing mass, "
             "ground included.\n"
             "Base shear V = (M − m) a_t + m a_m: the rate of the horizontal momentum of tank and "
             "liquid.\n"
             "Overturning moment = (m0 h0 + m_shell (h + f)/2) a_t + m h_c a_m about the centre "
             "of the\n"
             "tank bottom: the wall pressures and the shell's inertia (the base pressure is not "
             "included).\n"
             "Schematic: lengths not to scale; h_c and h0 are heights of force resultants, not "
             "of the pendulum.")
    finish(fig, ax, notes, (-0.8, 11.6), (-2.9, 9.6), OUT_LOADS)


if __name__ == "__main__":
    main()
    loads()
