"""The terminal summary of a run: :func:`report` of the summary of :func:`~unilateral.analysis.outputs.write_outputs`.

The key figures (static state, main history, periods, base shear, overturning moment, drift, yield
and slip, energy balance, response spectra), the failed cases with what to try
(:data:`FAILURE_HINT`) and the warnings of an energy balance that is off (:func:`energy_warnings`).
"""

from __future__ import annotations

import numpy as np

from ..io.summary import format_summary

#: What to try when a case fails (printed under its message).
FAILURE_HINT = ("  what to try: a smaller time step (--dt), another LCP solver (--lcp bpp or lemke), or "
                "--method direct; the outputs hold the case up to where it stopped")


def report(result: dict) -> str:
    """The terminal summary of a run: :func:`format_summary`, the main history's extremes and the
    structure's key results (periods, base shear, overturning moment, drift, energy balance)."""
    extra = result.get("extra", {})
    text = format_summary({**result, "extra": {k: v for k, v in extra.items()
                                               if k not in ("figure", "cases", "figure_node", "figure_dof",
                                                            "comparison")}})
    units = result.get("units") or {}
    labels = result.get("case_labels") or {}       # the legend labels of the figures, if not the case names
    fig = extra.get("figure")
    if fig:
        unit = units.get("length", "") if fig["dof"] != "rz" else "rad"
        lines = [f"{fig['dof']} of node {fig['node']} [{unit}]: static {fig['static']:.4g}"]
        width = max(15, *(len(labels.get(name, name)) for name in fig["peak"]))
        for name, peak in fig["peak"].items():
            lines.append(f"  {labels.get(name, name):>{width}}: max {peak:.4g}, min {fig['minimum'][name]:.4g}")
        text += "\n\n" + "\n".join(lines)
    results = result.get("results") or {}
    if results:
        text += "\n\n" + "\n".join(_result_lines(results, units, labels))
    if result.get("spectra"):
        text += "\n" + _spectra_line(result["spectra"], units)
        for direction, each in result["spectra"].get("by_direction", {}).items():     # a 3-D frame's other directions
            if direction != result["spectra"]["direction"]:
                text += "\n" + _spectra_line(each, units)
    for name, case in extra.get("cases", {}).items():
        if not case["success"]:
            text += (f"\n{case_name(name, labels)} case FAILED at t = {case.get('t_reached', float('nan')):.4g} "
                     f"(step {case.get('steps_computed', '?')}): {case['message']}\n{FAILURE_HINT}")
    for warning in result.get("warnings", ()):
        text += f"\nWARNING: {warning}"
    return text


def _spectra_line(spectra: dict, units: dict) -> str:
    """``response spectra (5 % damping, ux): peak Sa 11 m/s^2 at T = 0.58 s (ground), ...`` of the
    ``spectra`` of ``summary.json``: the ground and at most two floors."""
    length, time = units.get("length", ""), units.get("time", "")
    unit = f" {length}/{time}^2" if length and time else ""
    peaks = [("ground", spectra["ground"])] + [(f"node {node}, {case}", peak)
                                               for case, nodes in spectra.get("floors", {}).items()
                                               for node, peak in nodes.items()]
    shown = "; ".join(f"{p['Sa']:.4g}{unit} at T = {p['period']:.3g} {time} ({where})".replace(" )", ")")
                      for where, p in peaks[:3])
    more = f"; {len(peaks) - 3} more in spectra.csv" if len(peaks) > 3 else ""
    return (f"response spectra ({100 * spectra['damping']:g} % damping, {spectra['direction']}): peak Sa "
            f"{shown}{more}")


#: A relative error of the energy balance above this is warned about (terminal and summary.json).
ENERGY_WARNING = 0.02


def case_name(name: str, labels: dict) -> str:
    """A case on the terminal: its key (``unilateral``, ``bilateral``) and its legend label, if other."""
    label = (labels or {}).get(name, name)
    return name if label == name else f"{name} ({label})"


def energy_warnings(results: dict, *, rule=None, dt=None) -> list[str]:
    """Warnings for the cases whose energy balance is off by more than :data:`ENERGY_WARNING`, and
    for those whose rule dissipated more than :data:`NUMERICAL_WARNING` of the input work
    numerically (:func:`numerical_warning`)."""
    out = []
    for case, p in results.items():
        energy = p.get("energy") or {}
        share = energy.get("numerical_share")
        if share is not None and share > NUMERICAL_WARNING:
            out.append(numerical_warning(case, share, rule=rule, dt=dt, period=_first_period(results)))
        error = energy.get("max_relative_error")
        if error is None or not error > ENERGY_WARNING:
            continue
        step = f" (now {dt:g}, e.g. half of it)" if isinstance(dt, (int, float)) else ""
        if energy.get("rule_identity"):
            what = ("the balance is the exact identity of the rule's steps (the rule's own dissipation is a term "
                    "of it), so neither the rule nor the time step explains it: the run did not follow the rule "
                    "(--method event integrates exactly between events; its balance is summed as the trapezoidal "
                    "rule) or its loads were not the samples the balance took")
        elif rule in ("bdf1", "bdf2", "hht"):
            what = (f"the {rule} rule damps numerically at this time step: use --rule trapezoidal (it conserves "
                    f"energy) or a smaller --dt{step}")
        else:
            what = f"the time step is too coarse for the contacts: use a smaller --dt{step}"
        out.append(f"{case} case: the energy balance is off by {100 * error:.2g} % (more than "
                   f"{100 * ENERGY_WARNING:g} %) at t = {energy.get('t_max_relative_error', float('nan')):.4g}; "
                   f"{what}")
    return out


#: A numerical dissipation of the rule above this share of the input work is warned about. On the
#: undamped 3-storey hinge frame of ``tests/test_numerical_dissipation.py`` BDF2's peak base shear
#: and residual drift are off by about ten times the share (docs/theory.md, section 14).
NUMERICAL_WARNING = 1e-3


#: The order at which the advice of :func:`numerical_warning` takes the numerical dissipation to fall.
ADVICE_ORDER = 1.5


def numerical_warning(case: str, share: float, *, rule=None, dt=None, period=None) -> str:
    """The warning of a case whose rule dissipated ``share`` of the input work numerically.

    The advice: the trapezoidal rule (no numerical dissipation), or the time step at which the
    share falls to half the threshold if it falls as ``dt^p``, ``p`` the rule's order but at most
    :data:`ADVICE_ORDER` (fitted for BDF2: 2.27 on the undamped hinge frame, 1.5 on the yielding
    frame on footings and on the pounding frames, where contacts and friction switch; so the
    advice is on the safe side where the order is higher), as a fraction ``T1 / k`` of the first
    period ``period`` when it is known.
    """
    from ..rules import get_rule

    name = rule if isinstance(rule, str) else getattr(rule, "name", "the")
    shown = f"{100 * share:.2g}"
    if float(shown) <= 100 * NUMERICAL_WARNING:         # just above the threshold: one more digit
        shown = f"{100 * share:.3g}"
    head = (f"{case} case: the {name} rule dissipated {shown} % of the input work numerically (more "
            f"than {100 * NUMERICAL_WARNING:g} %): the response is less accurate than the balance's closing says; "
            "use --rule trapezoidal (second order, no numerical dissipation)")
    if not isinstance(dt, (int, float)) or not dt > 0:
        return head + " or a smaller --dt"
    try:
        order = min(get_rule(rule).order if rule is not None else 2, ADVICE_ORDER)
    except (TypeError, ValueError):
        order = ADVICE_ORDER
    target = dt * (0.5 * NUMERICAL_WARNING / share) ** (1.0 / order)
    if isinstance(period, (int, float)) and 0 < period < np.inf:
        k = int(np.ceil(period / target))
        return head + f" or --dt {period / k:.3g} or less (T1/{k}, T1 = {period:.4g}; now {dt:g} = T1/{period / dt:.0f})"
    return head + f" or --dt {target:.3g} or less (now {dt:g})"


def _first_period(results: dict):
    """The first period of the bilateral structure among the cases' peaks, or None."""
    for p in results.values():
        if p.get("periods"):
            return float(p["periods"][0])
    return None


def _shear_is_zero(p: dict) -> bool:
    """No horizontal force reaches the ground (vertical loads only): the base shear is zero at every step."""
    shear, vertical = p["base_shear"], p.get("base_vertical") or {}
    scale = max(abs(vertical.get("max", 0.0)), abs(vertical.get("min", 0.0)), 1e-300)
    return max(abs(shear["max"]), abs(shear["min"])) <= 1e-9 * scale


def _result_lines(results: dict, units: dict, labels=None) -> list[str]:
    force, length, time = (units.get(k, "") for k in ("force", "length", "time"))
    lines = []
    for case, p in results.items():
        if not lines and p.get("periods"):
            periods = ", ".join(f"{T:.4g}" for T in p["periods"][:3])
            lines.append(f"periods of the bilateral structure [{time}]: {periods}")
            for label, values in p.get("frame_periods", {}).items():
                lines.append(f"  {label}, alone (the gaps open): {', '.join(f'{T:.4g}' for T in values)}")
        head = f"{(labels or {}).get(case, case)}:"
        if "base_forces" in p:                                  # a 3-D frame
            parts = []
            for key, b in p["base_forces"].items():
                peak = b["max"] if abs(b["max"]) >= abs(b["min"]) else b["min"]
                unit = force if key.startswith("F") else f"{force} {length}"
                parts.append(f"{key} {peak:.4g} {unit}".rstrip())
            lines.append(f"{head} peak base forces {', '.join(parts)}")
            if p.get("drift_ratio"):
                label, d = max(p["drift_ratio"].items(), key=lambda item: abs(item[1]["value"]))
                lines.append(f"{' ' * len(head)} peak drift ratio {d['value']:.3g} (storey {label}, at a corner) "
                             f"at t = {d['t']:.4g} {time}".rstrip())
            lines += [f"{' ' * len(head)} {line}" for line in _family_lines(p, units)]
            if p.get("energy"):
                lines.append(_energy_line(p["energy"], head, force, length))
            continue
        shear = p["base_shear"]
        peak = shear["max"] if abs(shear["max"]) >= abs(shear["min"]) else shear["min"]
        t_peak = shear["t_max"] if peak == shear["max"] else shear["t_min"]
        mom = p["overturning_moment"]
        mpeak = mom["max"] if abs(mom["max"]) >= abs(mom["min"]) else mom["min"]
        t_m = mom["t_max"] if mpeak == mom["max"] else mom["t_min"]
        if _shear_is_zero(p) and p.get("base_vertical"):
            vert = p["base_vertical"]
            vpeak = vert["max"] if abs(vert["max"]) >= abs(vert["min"]) else vert["min"]
            t_v = vert["t_max"] if vpeak == vert["max"] else vert["t_min"]
            lines.append(f"{head} no base shear (no horizontal force on the ground); peak vertical ground force "
                         f"{vpeak:.4g} {force} at t = {t_v:.4g} {time}; overturning moment {mpeak:.4g} {force} "
                         f"{length} at t = {t_m:.4g} {time}")
        else:
            lines.append(f"{head} peak base shear {peak:.4g} {force} at t = {t_peak:.4g} {time}; "
                         f"overturning moment {mpeak:.4g} {force} {length} at t = {t_m:.4g} {time}")
        for label, b in p.get("frames", {}).items():
            fshear = b["base_shear"]
            fpeak = fshear["max"] if abs(fshear["max"]) >= abs(fshear["min"]) else fshear["min"]
            t_f = fshear["t_max"] if fpeak == fshear["max"] else fshear["t_min"]
            lines.append(f"{' ' * len(head)} {label}: peak base shear {fpeak:.4g} {force} at t = {t_f:.4g} {time}")
        if p.get("drift_ratio"):
            label, d = max(p["drift_ratio"].items(), key=lambda item: abs(item[1]["value"]))
            lines.append(f"{' ' * len(head)} peak drift ratio {d['value']:.3g} (storey {label}) at t = {d['t']:.4g} {time}")
        if p.get("linear_members_note"):
            lines.append(f"{' ' * len(head)} note: {p['linear_members_note']}")
        lines += [f"{' ' * len(head)} {line}" for line in _family_lines(p, units)]
        if p.get("energy"):
            lines.append(_energy_line(p["energy"], head, force, length))
    return lines


def _energy_line(e: dict, head: str, force: str, length: str) -> str:
    """``energy balance: relative error ..., input work ..., dissipated ...`` of a case's peaks ``e``."""
    terms = " + ".join(f"{e[key]:.4g} ({word})" for key, word in DISSIPATED
                       if key in e and (key != "numerical_dissipation" or e[key] > 0))
    return (f"{' ' * len(head)} energy balance: relative error {e['max_relative_error']:.2g}, "
            f"input work {e['input_work']:.4g}, "
            + (f"support work {e['support_work']:.4g}, " if "support_work" in e else "")
            + f"dissipated {terms} [{force} {length}]")


#: The dissipation terms of the energy balance in the terminal summary.
DISSIPATED = (("damping_dissipated", "damping"), ("contact_dissipated", "contact"), ("plastic_work", "plastic"),
              ("friction_work", "friction"), ("numerical_dissipation", "numerical, by the rule"))


def _family_lines(p: dict, units: dict) -> list[str]:
    """The yield and friction lines of a case's peaks ``p``, and then its residual drift."""
    lines = []
    if p.get("yield_elements"):
        lines.append(_yield_line(p["yield_elements"], units))
    if p.get("friction_elements"):
        lines.append(_friction_line(p["friction_elements"], units))
    lines += _footing_lines(p.get("footings") or {}, units)
    drift = p.get("residual_drift")
    if lines and drift:
        lines.append(f"residual drift ratio {100 * drift['ratio']:.2g} % (storey {drift['storey']}) at the last "
                     f"step, t = {drift['t']:.4g} {units.get('time', '')}".rstrip())
        static = p.get("residual_drift_static")
        if static:
            lines.append(f"static residual drift ratio {100 * static['ratio']:.2g} % (storey {static['storey']}), "
                         "plastic deformations frozen, gravity alone")
    return lines


#: At most this many footings get a line of their own in the terminal (all are in summary.json).
FOOTING_LINES = 8


def _footing_lines(footings: dict, units: dict) -> list[str]:
    """``footing A: uplift 0.0012 m at t = 2.4 s, rz 0.0049 rad (final 1e-4), ...`` per footing."""
    L, Fu, T = (units.get(k, "") for k in ("length", "force", "time"))
    lines = []
    for name, f in list(footings.items())[:FOOTING_LINES]:
        lift = f["uplift"]
        parts = [f"uplift {lift['max']:.3g} {L} at t = {lift['t_max']:.4g} {T}".replace("  ", " ")
                 if lift["max"] > 0 else "no uplift"]
        for q in ("rz", "rx", "ry", "slip", "slip_x", "slip_y"):
            if q in f:
                peak = max((f[q]["max"], f[q]["min"]), key=abs)
                unit = "rad" if q.startswith("r") else L
                parts.append(f"{q} {peak:.3g} {unit} (final {f[q]['final']:.3g})".replace("  ", " "))
        parts.append(f"peak pressure {f['peak_pressure']['max']:.4g} {Fu}/{L}^2" if L and Fu
                     else f"peak pressure {f['peak_pressure']['max']:.4g}")
        parts.append(f"least contact (compression) {100 * f['contact_ratio']['min']:.3g} % of the base at t = "
                     f"{f['contact_ratio']['t_min']:.4g} {T}".rstrip())
        lines.append(f"footing {name}: " + ", ".join(parts))
    if len(footings) > FOOTING_LINES:
        lines.append(f"({len(footings) - FOOTING_LINES} more footings in summary.json)")
    return lines


def _yield_line(elements: dict, units: dict) -> str:
    """``yield: 14 of 18 hinges yielded, peak ductility 3.2 (B1.i), ...``."""
    kinds = {e["kind"] for e in elements.values()}
    noun = {"hinge": "hinges", "yield link": "yield links"}.get(kinds.pop(), "") if len(kinds) == 1 else ""
    yielded = sum(e["yielded"] for e in elements.values())
    text = f"yield: {yielded or 'none'} of {len(elements)} {noun or 'yield elements'} yielded"
    if not yielded:
        ratios = {name: e["peak_force_ratio"]["value"] for name, e in elements.items()}
        name = max(ratios, key=ratios.get)
        return text + f", peak force {ratios[name]:.3g} x the yield force ({name})"
    ductile = {name: e["ductility"]["value"] for name, e in elements.items() if "ductility" in e}
    if ductile:
        name = max(ductile, key=ductile.get)
        text += f", peak ductility {ductile[name]:.3g} ({name})"
    rigid = {name: e for name, e in elements.items() if "ductility" not in e}
    if rigid:
        name, e = max(rigid.items(), key=lambda item: abs(item[1]["peak_plastic_deformation"]["value"]))
        word = "rotation" if e["unit"] == "rad" else "deformation"
        text += f", peak plastic {word} {abs(e['peak_plastic_deformation']['value']):.3g} {e['unit']} ({name})"
    work = [e["plastic_work"] for e in elements.values() if e["plastic_work"] is not None]
    if work:
        text += f", plastic work {sum(work):.4g} {units.get('force', '')} {units.get('length', '')}".rstrip()
    return text


def _friction_line(elements: dict, units: dict) -> str:
    """``friction: 2 of 9 friction elements slid, peak slip 0.012 m (F1), ...``."""
    length = units.get("length", "")
    slid = sum(e["slid"] for e in elements.values())
    if not slid:
        return f"friction: none of {len(elements)} friction elements slid"
    name, e = max(elements.items(), key=lambda item: abs(item[1]["peak_slip"]["value"]))
    text = (f"friction: {slid} of {len(elements)} friction elements slid, peak slip "
            f"{abs(e['peak_slip']['value']):.3g} {length} ({name}), total slip "
            f"{sum(e['total_slip'] for e in elements.values()):.3g} {length}")
    work = [e["friction_work"] for e in elements.values() if e["friction_work"] is not None]
    if work:
        text += f", friction work {sum(work):.4g} {units.get('force', '')} {length}".rstrip()
    return text
