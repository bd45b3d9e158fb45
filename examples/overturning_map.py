"""The overturning map of a rigid block under a one-sine pulse (``method="moreau-jean"``).

What it shows
-------------
A free-standing rigid block (width 2b = 0.5 m, height 2h = 2.5 m: b/h = 0.2, alpha = 0.197 rad,
Housner's p = sqrt(3 g / (4 R)) = 2.40 rad/s, the linearised ``RigidBlock.p = sqrt(W h / I0)``
= 2.379 rad/s; kN, m, s) on a base shaken by one full sine cycle ``a_g(t) = a_p sin(omega_p t)``,
``0 <= t <= 2 pi / omega_p``, its base held horizontally (no slip), Housner's impact at each corner
(``restitution = 0``: r = 1 - 2 m b^2 / I0 = 0.942). Each point of the map is one run of
``method="moreau-jean"`` (Newton's law at the velocity level, the impacts located within the
step), classified as

* ``rest``: no corner lifts;  ``rocks``: it rocks and does not overturn;
* ``overturns (no impact)``: it overturns before any impact (Zhang & Makris' mode 2);
* ``overturns (after impacts)``: after one or more impacts (their mode 1);

over the pulse frequency ``omega_p / p`` (``p = RigidBlock.p``) and the amplitude
``a_p / (g tan alpha)``. The block overturns when, the pulse over, the tilt of the linearised
rocking (``docs/rocking.md``) is past b/h, the unstable equilibrium, and growing (or it reaches
pi/2); while the base still moves, a block past b/h can be pulled back by the pulse and survive.
Taking the first passing of b/h as the overturn (``classify(criterion="tilt")``, this example's
former rule) misses the region of no overturning between the two modes: the cause of the
discrepancy with Zhang & Makris measured in ``docs/rocking.md`` with
``unilateral.analysis.rocking_reference``.

What to compare with (Zhang & Makris 2001, "Rocking response of free-standing blocks under
cycloidal pulses", their one-sine pulse map): no corner lifts below ``a_p = g tan alpha`` (the
closed form that the tests check, tests/test_moreau_jean.py); the amplitude needed to overturn
grows with ``omega_p / p`` (a short pulse needs a larger acceleration); at the higher frequencies
two regions of overturning, mode 1 (after an impact) at the lower amplitudes and mode 2 (no
impact) at the higher ones, with a region of no overturning between them. The map printed and
drawn (``docs/overturning.png``) shows these features; its boundaries are those of the linearised
equations, equal to the reference's (``tests/test_rocking_reference.py``).

What it prints
--------------
The map as a table of letters (``.`` rest, ``r`` rocks, ``1`` mode 1, ``2`` mode 2), the smallest
overturning amplitude and the amplitudes of no overturning above it (the safe region) at each
frequency, and the number of runs. ``--quick``: a 3 x 3 map, no figure. ``--tilt``: the former
criterion (the first passing of b/h overturns). ``--phase``: Zhang & Makris' pulse
``a_p sin(omega_p t + psi)``, ``sin(psi) = g tan(alpha) / a_p`` (the block lifts at ``t = 0``).
The figure is written for the default map only.

Run: ``python examples/overturning_map.py`` (a few minutes).
"""

import math
import sys
from pathlib import Path

import numpy as np

import unilateral as ul
from unilateral.analysis.rigid import one_sine_pulse, rocking_onset_phase
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


def classify(structure, model, block, frequency, amplitude, *, dt=2e-3, after=3.0, criterion="free",
             phase=False) -> str:
    """One run: ``"rest"``, ``"rocks"``, ``"mode 1"`` or ``"mode 2"`` (see the module).

    ``criterion="free"`` (default): the block overturns when, the pulse over, its tilt is past
    ``b / h`` and growing (the linearised free rocking then grows without bound), or when the tilt
    reaches ``pi / 2``; while the base moves a block past ``b / h`` can be pulled back. After the
    pulse a block whose energy is below the unstable equilibrium's cannot overturn any more: the run
    stops there (``rocks``). ``criterion="tilt"``: the first passing of ``b / h``, even during the
    pulse, is taken as the overturn (this example's former rule: it misses the safe region).
    ``phase``: Zhang & Makris' pulse, ``a_p sin(omega_p t + psi)`` with ``sin(psi) = g tan(alpha) / a_p``
    (``rocking_onset_phase``: the block lifts at ``t = 0``).
    """
    wp = frequency * block.p
    a_p = amplitude * block.uplift_acceleration
    psi = rocking_onset_phase(a_p, block.uplift_acceleration) if phase and amplitude >= 1 else 0.0
    load = LoadHistory(structure.gravity(block.g), [rigid.ground_motion(structure, one_sine_pulse(a_p, wp, psi=psi))])
    pulse_end = 2 * math.pi / wp
    sim = ul.Simulation(model, load, dt=dt, t_end=pulse_end + after, method="moreau-jean", rule="trapezoidal")
    limit, p2 = block.b / block.h, block.p ** 2
    row = np.asarray(structure.dofs.T[structure.dofs.full_index(block.base, "rz")].todense()).ravel()
    lifted = False
    overturned = lambda: "mode 1" if sim.solution().stats["impacts"] else "mode 2"
    while sim.status == "running":
        sim.advance(min(25, sim.N - sim.n))
        state = sim.state
        theta, omega = float(row @ state.u), float(row @ state.udot)
        lifted = lifted or bool(np.max(-state.psi) > 1e-12)
        if abs(theta) > (limit if criterion == "tilt" else math.pi / 2):
            return overturned()
        if criterion == "free" and state.t >= pulse_end:
            if abs(theta) > limit and theta * omega > 0:
                return overturned()
            side = math.copysign(1.0, theta) if theta else 1.0
            if abs(theta) < limit and omega ** 2 < p2 * (theta - side * limit) ** 2:
                break                                           # below the equilibrium's energy
    assert sim.status in ("finished", "running"), sim.message
    return "rocks" if lifted else "rest"


def overturning_map(frequencies, amplitudes, *, criterion="free", phase=False):
    """``{(frequency, amplitude): class}`` over the grid (:func:`classify`'s options)."""
    structure, model, block = build()
    return {(f, a): classify(structure, model, block, f, a, criterion=criterion, phase=phase)
            for f in frequencies for a in amplitudes}


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
    ax.text(frequencies[-1], 0.45, "uplift: a_p = g tan(alpha)", fontsize=8, color="gray", ha="right")
    ax.set_ylim(0.0, None)
    ax.set_xlabel("pulse frequency omega_p / p")
    ax.set_ylabel("pulse amplitude a_p / (g tan alpha)")
    ax.set_title("Rigid block (b/h = 0.2) under a one-sine pulse: overturning map (moreau-jean)", fontsize=10)
    ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=2)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main(quick=False, criterion="free", phase=False):
    if quick:
        frequencies, amplitudes = [2.0, 4.0, 8.0], [0.9, 3.0, 8.0]
    else:
        frequencies = [1.0, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0]
        amplitudes = [0.9, 1.25, *np.arange(1.5, 10.01, 0.5).tolist(), 11.0, 12.0, 13.0, 14.0]
    result = overturning_map(frequencies, amplitudes, criterion=criterion, phase=phase)
    print(f"criterion {criterion!r}, pulse " + ("a_p sin(omega_p t + psi)" if phase else "a_p sin(omega_p t)"))
    print("a_p/(g tan alpha) \\ omega_p/p: " + " ".join(f"{f:>4g}" for f in frequencies))
    for a in reversed(amplitudes):
        print(f"{a:>31g}: " + " ".join(f"{LETTERS[result[(f, a)]]:>4}" for f in frequencies))
    for f in frequencies:
        over = [a for a in amplitudes if result[(f, a)].startswith("mode")]
        safe = [a for a in amplitudes if over and a > min(over) and result[(f, a)] == "rocks"]
        print(f"omega_p/p = {f:g}: smallest overturning amplitude on the grid "
              f"{min(over) if over else 'none'}; no overturning above it at {safe or 'none'}; no uplift below 1: "
              f"{all(result[(f, a)] == 'rest' for a in amplitudes if a < 1)}")
    print(f"{len(result)} runs (. rest, r rocks, 1 overturns after impacts, 2 overturns without impact)")
    if not quick and criterion == "free" and not phase:
        path = Path(__file__).resolve().parents[1] / "docs" / "overturning.png"
        figure(result, frequencies, amplitudes, path)
        print(f"figure: {path}")
    return result


if __name__ == "__main__":
    args = sys.argv[1:]
    main(quick="--quick" in args, criterion="tilt" if "--tilt" in args else "free", phase="--phase" in args)
