"""The key figures of a run: a JSON-ready dict and a compact table for the terminal."""

from __future__ import annotations

import numpy as np

from ..result import Solution
from .atomic import to_jsonable

#: Kinds of the unknowns that are multipliers (plastic deformations, slips), not contacts.
RATE_KINDS = ("yield", "friction")


def summary(sol: Solution, *, units: dict | None = None, extra: dict | None = None,
            key_dofs: list | None = None, kinds=None) -> dict:
    """Key figures of a solution, in plain JSON types.

    Parameters
    ----------
    sol : Solution
    units : dict, optional
        Units of the base quantities, e.g. ``{"length": "m", "force": "kN", "time": "s"}``;
        recorded under ``"units"`` and shown by :func:`format_summary`.
    extra : dict, optional
        Anything else worth keeping with the figures (model data, load case), under ``"extra"``.
    key_dofs : list of str, optional
        The DOFs :func:`format_summary` prints (``"static_shown"``); default: at most
        :data:`SHOWN_DOFS` DOFs with the largest static displacements (``static`` keeps all).
    kinds : sequence of str, optional
        The kind of each constraint unknown (``"soil"``, ``"gap"``, ``"contact"``, ...,
        ``"yield"``, ``"friction"``); plastic multipliers and slips (``"yield"``,
        ``"friction"``) are left out of ``constraints``: they are no uplift and their ``psi`` is no
        contact force. Default: every unknown is a contact.

    Returns
    -------
    dict
        ``success``, ``message``, ``method``, ``rule`` (and ``rule_note`` when the rule was asked
        for by another name, see :func:`unilateral.rules.alias_note`), ``lcp_solver``, ``steps`` (steps computed),
        ``dt``, ``t_end``, ``run_time`` (seconds), ``max_lcp_error``, ``contact_changes``,
        ``units``, ``static`` (DOF name to the displacement at t = 0; empty without
        displacements), ``constraints`` (name to ``max_v``, ``t_max_v``: the peak uplift or gap
        opening and its time; ``min_psi``, ``t_min_psi``: the peak compressive reaction and its
        time; contacts only, see ``kinds``) and ``extra``. Statistics the run did not record are
        None.
    """
    stats = sol.stats
    t = np.asarray(sol.t)
    kinds = ["contact"] * len(sol.constraint_names) if kinds is None else kinds
    note = {"rule_note": stats["rule_note"]} if stats.get("rule_note") else {}
    return to_jsonable({
        "success": sol.success,
        "message": sol.message,
        "method": stats.get("method"),
        "rule": stats.get("rule"),
        **note,
        "lcp_solver": stats.get("lcp_solver"),
        "steps": len(t) - 1,
        "dt": stats.get("dt"),
        "t_end": t[-1],
        "run_time": stats.get("time", {}).get("total"),
        "max_lcp_error": stats.get("max_lcp_error"),
        "contact_changes": stats.get("contact_changes"),
        "units": dict(units or {}),
        "static": {} if sol.u is None else dict(zip(sol.dof_names, np.asarray(sol.u)[0])),
        "constraints": {name: _peaks(t, v, psi) for name, v, psi, kind
                        in zip(sol.constraint_names, np.asarray(sol.v).T, np.asarray(sol.psi).T, kinds)
                        if kind not in RATE_KINDS},
        "static_shown": _shown(sol, key_dofs),
        "extra": dict(extra or {}),
    })


#: At most this many DOFs are printed with their static displacement.
SHOWN_DOFS = 6


def _shown(sol: Solution, key_dofs) -> list:
    if sol.u is None or not len(sol.u):
        return []
    if key_dofs is not None:
        return list(key_dofs)[:SHOWN_DOFS]
    u0 = np.abs(np.asarray(sol.u)[0])
    if not u0.any():
        return []
    order = np.argsort(-u0, kind="stable")
    keep = [k for k in order[:SHOWN_DOFS] if u0[k] > 1e-9 * u0.max()]
    return [sol.dof_names[k] for k in sorted(keep)]


def format_summary(summary_dict: dict) -> str:
    """A compact human-readable table of a :func:`summary` for the terminal."""
    s = summary_dict
    units = s["units"]
    length, force, time = (units.get(key, "") for key in ("length", "force", "time"))
    in_time = f" {time}" if time else ""
    status = "success" if s["success"] else "FAILED"
    lines = [
        f"{status}: {s['message']}",
        f"method {s['method']}, rule {s['rule']}, LCP solver {s['lcp_solver']}; {s['steps']} steps of "
        f"dt = {_number(s['dt'])}{in_time} to t = {_number(s['t_end'])}{in_time}",
        *([f"note: {s['rule_note']}"] if s.get("rule_note") else []),
        f"run time {_number(s['run_time'])} s, max LCP error {_number(s['max_lcp_error'])}, "
        f"contact changes {_number(s['contact_changes'])}",
    ]
    shown = s.get("static_shown", list(s["static"]))
    if shown:
        hidden = len(s["static"]) - len(shown)
        lines += ["", *_table(["DOF", "u(t=0)"], [[name, _number(s["static"][name])] for name in shown])]
        if hidden > 0:
            lines.append(f"({hidden} more DOFs in summary.json and displacements.csv)")
    if s["constraints"]:
        lines += ["", *_table(
            ["constraint", _label("max v", length), _label("at t", time), _label("min psi", force),
             _label("at t", time)],
            [[name, _number(p["max_v"]), _number(p["t_max_v"]), _number(p["min_psi"]), _number(p["t_min_psi"])]
             for name, p in s["constraints"].items()])]
    if s["extra"]:
        lines += ["", *(f"{key}: {value}" for key, value in s["extra"].items())]
    return "\n".join(lines)


def _peaks(t: np.ndarray, v: np.ndarray, psi: np.ndarray) -> dict:
    i, j = np.argmax(v), np.argmin(psi)
    return {"max_v": v[i], "t_max_v": t[i], "min_psi": psi[j], "t_min_psi": t[j]}


def _number(x) -> str:
    if x is None:
        return "n/a"
    return f"{x:.4g}" if isinstance(x, float) else str(x)


def _label(text: str, unit: str) -> str:
    return f"{text} [{unit}]" if unit else text


def _table(header: list[str], rows: list[list[str]]) -> list[str]:
    """Lines of a table: first column left-aligned, the others right-aligned."""
    widths = [max(len(row[k]) for row in [header, *rows]) for k in range(len(header))]

    def line(row):
        return "  ".join([row[0].ljust(widths[0])] + [cell.rjust(w) for cell, w in zip(row[1:], widths[1:])])

    return [line(header), "  ".join("-" * w for w in widths), *map(line, rows)]
