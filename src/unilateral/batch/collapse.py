"""Collapse is not non-convergence: a structure that collapsed against an analysis that failed.

A study records per analysis ``status`` (``failed``: the LCP of a step failed, ``error``,
``timeout``) and, apart from it, ``collapse`` (1 or 0) with ``collapse_reason``:

* a limit of ``[collapse]`` exceeded: ``quantity`` (a quantity column, e.g. a drift ratio or a base
  rotation) above ``limit`` (of a failed analysis, the peak over the steps it computed);
* a mechanism under gravity (``mechanism = true``, the default): at the last step computed, the
  static tangent ``K_t = K - F_a H_aa^-1 F_a^T`` of the model (``K`` with the geometric stiffness of
  P-Delta) over the yield and slip unknowns ``a`` that flow there (``v`` increasing, ``psi = 0``) is
  not positive definite (its smallest eigenvalue ``<= 1e-9 ||K||_inf``): the frame cannot carry its
  gravity load in that state.

IDA curves flatten at collapse (drawn to the right edge at the collapse intensity) and mark failures
with another symbol; fragility curves count a collapse as an exceedance of every limit state and
leave failures out (a failure is no evidence of either); with ``[collapse]`` a ``collapse``
fragility is fitted too. Published IDA studies have counted non-convergence as collapse: this
package never does.
"""

from __future__ import annotations

import math

import numpy as np

from ..modelfile.errors import did_you_mean, value_problem

MECHANISM_TOL = 1e-9
"""A tangent whose smallest eigenvalue is at most this times ``||K||_inf`` (a bound of the largest
eigenvalue of ``K``) is singular or indefinite: a mechanism."""
MECHANISM_MAX_N = 1000
"""The mechanism check takes the eigenvalues of a dense ``n x n`` tangent (a fraction of a second at
1000), only when some yield or slip unknown flows at the last step: not checked above this size."""


def mechanism(model, sol) -> str:
    """Why the last computed state of ``sol`` is a mechanism of ``model`` (``""``: it is not).

    Parameters
    ----------
    model : Model
        The reduced problem (``K``, ``F``, ``H``, its step law's ``kinds``); another model (a footing
        on a soil medium) is not checked.
    sol : Solution
        Its ``v`` and ``psi`` (N+1, m); the last two steps say which unknowns flow.
    """
    kinds = getattr(getattr(model, "law", None), "kinds", None)
    if kinds is None or not all(hasattr(model, a) for a in ("K", "F", "H")) or sol.v is None or len(sol.v) < 2:
        return ""
    if model.n > MECHANISM_MAX_N:
        return ""
    v, psi = np.asarray(sol.v, float), np.asarray(sol.psi, float)
    scale = max(float(np.max(np.abs(psi))) if psi.size else 0.0, 1e-300)
    flowing = [i for i, kind in enumerate(kinds) if kind in ("yield", "friction")
               and v[-1, i] > v[-2, i] and psi[-1, i] >= -1e-8 * scale]
    if not flowing:
        return ""
    K = model.K.toarray() if hasattr(model.K, "toarray") else np.asarray(model.K, float)
    F = model.F.toarray() if hasattr(model.F, "toarray") else np.asarray(model.F, float)
    Fa, Haa = F[:, flowing], np.asarray(model.H, float)[np.ix_(flowing, flowing)]
    try:
        tangent = K - Fa @ np.linalg.solve(Haa, Fa.T)
    except np.linalg.LinAlgError:                       # rigid unknowns (H_aa singular): not decided here
        return ""
    tangent = 0.5 * (tangent + tangent.T)
    lowest = float(np.linalg.eigvalsh(tangent)[0])
    norm = float(np.max(np.abs(K).sum(axis=1)))
    if lowest > MECHANISM_TOL * norm:
        return ""
    names = [sol.constraint_names[i] for i in flowing] if getattr(sol, "constraint_names", None) else flowing
    return (f"a mechanism under gravity at t = {float(sol.t[-1]):.4g}: the static tangent with "
            f"{', '.join(map(str, names))} flowing is not positive definite (smallest eigenvalue {lowest:.3g}, "
            f"||K||_inf {norm:.3g})")


def collapse_of(result: dict | None, collapse) -> tuple[int, str]:
    """``(collapse, reason)`` of one analysis' ``result`` under the study's ``[collapse]`` table
    (None: only mechanisms count; a result without a solution: ``(0, "")``, pending ``(-1, "")``)."""
    if result is None:
        return -1, ""
    reasons = []
    if collapse is not None and collapse.quantity is not None:
        values = result.get("values_computed") or result.get("values") or {}
        value = values.get(collapse.quantity)
        if value is not None and math.isfinite(value) and value > collapse.limit:
            reasons.append(f"{collapse.quantity} = {value:.4g} > {collapse.limit:g} (collapse.limit)")
    if (collapse is None or collapse.mechanism) and result.get("mechanism"):
        reasons.append(result["mechanism"])
    return int(bool(reasons)), "; ".join(reasons)


def collapse_problems(doc, columns: list) -> list[str]:
    """``[collapse]`` keys that do not fit the study: a quantity that is not a column, a limit
    without a quantity (or the other way round)."""
    collapse = doc.collapse
    if collapse is None:
        return []
    if (collapse.quantity is None) != (collapse.limit is None):
        given = "quantity" if collapse.quantity is not None else "limit"
        missing = "limit" if given == "quantity" else "quantity"
        return [f"collapse.{missing}: missing key (collapse.{given} is given: a collapse limit is a quantity "
                "and the value above which the structure has collapsed)"]
    if collapse.quantity is not None and collapse.quantity not in columns:
        return [value_problem(("collapse", "quantity"), collapse.quantity, f"no such quantity (valid: "
                              f"{', '.join(columns)})") + did_you_mean(collapse.quantity, columns)]
    return []


def collapse_limit_states(doc) -> list:
    """``[LimitState("collapse", quantity "collapse", threshold 0.5)]`` with ``[collapse]`` (its
    fragility curve: the column ``collapse`` is 1 or 0), else ``[]``."""
    if doc.collapse is None:
        return []
    from .schema import LimitState

    return [LimitState(name="collapse", quantity="collapse", threshold=0.5)]
