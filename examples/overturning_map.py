"""The overturning map of a rigid block under a one-sine pulse (``method="moreau-jean"``).

What it shows
-------------
A free-standing rigid block (width 2b = 0.5 m, height 2h = 2.5 m: b/h = 0.2, alpha = 0.197 rad,
p = sqrt(3 g / (4 R)) = 2.40 rad/s; kN, m, s) on a base shaken by one full sine cycle
``a_g(t) = a_p sin(omega_p t)``, ``0 <= t <= 2 pi / omega_p``, its base held horizontally (no
slip), Housner's impact at each corner (``restitution = 0``: r = 1 - 2 m b^2 / I0 = 0.942). Each
point of the map is one run of ``method="moreau-jean"`` (Newton's law at the velocity level, the
impacts located within the step), classified as

* ``rest``: no corner lifts;  ``rocks``: it rocks and comes back;
* ``overturns (no impact)``: the tilt passes b/h before any impact (Zhang & Makris' mode 2);
* ``overturns (after impacts)``: after one or more impacts (their mode 1);

over the pulse frequency ``omega_p / p`` and the amplitude ``a_p / (g tan alpha)``. The tilt of the
linearised rocking (``docs/rocking.md``) overturns where it passes b/h, the unstable equilibrium
(the run is stopped there).

What to compare with (Zhang & Makris 2001, "Rocking response of free-standing blocks under
cycloidal pulses", their one-sine pulse map): no corner lifts below ``a_p = g tan alpha`` (the
closed form that the tests check, tests/test_moreau_jean.py); the amplitude needed to overturn
grows with ``omega_p / p`` (a short pulse needs a larger acceleration); at the higher frequencies
two regions of overturning, mode 1 (after an impact) at the lower amplitudes and mode 2 (no
impact) at the higher ones, with a region of no overturning between them. The map printed and
drawn (``docs/overturning.png``) shows these features; their computed boundaries are those of the
linearised equations and are not compared point by point.

What it prints
--------------
The map as a table of letters (``.`` rest, ``r`` rocks, ``1`` mode 1, ``2`` mode 2), the smallest
overturning amplitude at each frequency, and the number of runs.
``--quick``: a 3 x 3 map, no figure.

Run: ``python examples/overturning_map.py`` (a minute or two).
"""

import math
import sys
from pathlib import Path

import numpy as np

import unilateral as ul
from unilateral.analysis.rigid import one_sine_pulse
from unilateral.loads import LoadHistory
from unilateral.structure import Frame2D, rigid

LETTERS = {"rest": ".", "rocks": "r", "mode 1": "1", "mode 2": "2"}


def build():
    """The block: ``(structure, model, block)``."""
    fr = Frame2D()
    fr.node("centre", 0.0, 1.25)
    block = fr.rigid_block("block", "centre", width=0.5, height=2.5, mass=1.0)
    structure = fr.build()
    return structure, structure.to_model(), block


def classify(structure, model, block, frequency, amplitude, dt=2e-3, after=3.0) -> str:
    """One run: ``"rest"``, ``"rocks"``, ``"mode 1"`` or ``"mode 2"`` (see the module)."""
    wp = frequency * block.p
    a_g = one_sine_pulse(amplitude * block.uplift_acceleration, wp)
    load = LoadHistory(structure.gravity(block.g), [rigid.ground_motion(structure, a_g)])
    sim = ul.Simulation(model, load, dt=dt, t_end=2 * math.pi / wp + after, method="moreau-jean",
                        rule="trapezoidal")
    limit = block.b / block.h
    row = np.asarray(structure.dofs.T[structure.dofs.full_index(block.base, "rz")].todense()).ravel()
    lifted = False
    while sim.status == "running":
        sim.advance(min(50, sim.N - sim.n))
        theta = row @ sim.state.u
        lifted = lifted or bool(np.max(-sim.state.psi) > 1e-12)
        if abs(theta) > limit:
            impacts = sim.solution().stats["impacts"]
            return "mode 1" if impacts else "mode 2"
    assert sim.status == "finished", sim.message
    return "rocks" if lifted else "rest"


def overturning_map(frequencies, amplitudes):
    """``{(frequency, amplitude): class}`` over the grid."""
    structure, model, block = build()
    return {(f, a): classify(structure, model, block, f, a) for f in frequencies for a in amplitudes}


def figure(result, frequencies, amplitudes, path):
    """The map (``path``, PNG)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    styles = {"rest": ("lightgray", "s", "no uplift"), "rocks": ("tab:blue", "o", "rocks, no overturning"),
              "mode 1": ("tab:red", "^", "overturns after impacts (mode 1)"),
              "mode 2": ("black", "v", "overturns without impact (mode 2)")}
    fig, ax = plt.subplots(figsize=(7, 5.6))
    for kind, (colour, marker, label) in styles.items():
        pts = [(f, a) for (f, a), c in result.items() if c == kind]
        if pts:
            ax.scatter(*zip(*pts), c=colour, marker=marker, s=28, label=label)
    ax.axhline(1.0, color="gray", lw=1, ls="--")
    ax.text(frequencies[-1], 0.75, "uplift: a_p = g tan(alpha)", fontsize=8, color="gray", ha="right")
    ax.set_xlabel("pulse frequency omega_p / p")
    ax.set_ylabel("pulse amplitude a_p / (g tan alpha)")
    ax.set_title("Rigid block (b/h = 0.2) under a one-sine pulse: overturning map (moreau-jean)")
    ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=2)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main(quick=False):
    if quick:
        frequencies, amplitudes = [2.0, 4.0, 8.0], [0.9, 3.0, 8.0]
    else:
        frequencies = [1.0, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0]
        amplitudes = [0.9, 1.2, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 10.0, 12.0]
    result = overturning_map(frequencies, amplitudes)
    print("a_p/(g tan alpha) \\ omega_p/p: " + " ".join(f"{f:>4g}" for f in frequencies))
    for a in reversed(amplitudes):
        print(f"{a:>31g}: " + " ".join(f"{LETTERS[result[(f, a)]]:>4}" for f in frequencies))
    for f in frequencies:
        over = [a for a in amplitudes if result[(f, a)].startswith("mode")]
        print(f"omega_p/p = {f:g}: smallest overturning amplitude on the grid "
              f"{min(over) if over else 'none'}; no uplift below 1: "
              f"{all(result[(f, a)] == 'rest' for a in amplitudes if a < 1)}")
    print(f"{len(result)} runs (. rest, r rocks, 1 overturns after impacts, 2 overturns without impact)")
    if not quick:
        path = Path(__file__).resolve().parents[1] / "docs" / "overturning.png"
        figure(result, frequencies, amplitudes, path)
        print(f"figure: {path}")
    return result


if __name__ == "__main__":
    main(quick="--quick" in sys.argv[1:])
