"""Which methods take rigid contacts (``H = 0`` rows in the force form, :mod:`unilateral.structure.rigid`).

``moreau-jean`` (:class:`~unilateral.methods.MoreauJean`) takes models whose every unknown is a
rigid contact, with Newton's impact law at the velocity level (impacts located within the step).
``direct`` takes them with every rule (the condensed LCP on ``P W0 = (1 - alpha) F^T D_eff^-1 F``),
but the impact is then position-level and only BDF1 gives a law of impact (perfectly plastic);
the other rules are run with a warning (:func:`rule_warning`).
``cq`` and ``modal`` take them where ``K`` (the structure without its rigid contacts) is positive
definite; a free or rocking body (``K`` singular or indefinite) puts poles of
``Lambda(s) = -F^T D(s)^-1 F`` at ``s = 0`` or ``s > 0``, whose convolution weights grow without
bound. ``event`` never: it has no impact law.
"""

from __future__ import annotations

import numpy as np

from ..model import check_definite, remembered


def rigid_contacts(model) -> list:
    """Names of the rigid contacts of a matrix ``model``: unknowns of a dual-form contact family
    (:class:`~unilateral.constraints.RigidContact`, :class:`~unilateral.constraints.SoilContact`)
    whose ``H(s)`` has a zero diagonal (no compliance). Empty for other problems."""
    if getattr(model, "kind", None) != "matrices" or not any(f.dual_form for f in model.families):
        return []
    H, H_v = np.asarray(model.H), None if model.H_v is None else np.asarray(model.H_v)
    out = []
    for family in model.families:
        if family.dual_form:
            out += [int(i) for i in family.indices if H[i, i] == 0 and (H_v is None or H_v[i, i] == 0)]
    return [model.constraint_names[i] for i in sorted(out)]


def refusal(model, method) -> str | None:
    """None if ``method`` (``"cq"``, ``"modal"``, ``"event"`` or ``"direct"``) solves ``model``'s rigid
    contacts, else why not (friction on rigid contacts: ``moreau-jean`` only)."""
    names = rigid_contacts(model)
    if not names:
        return None
    listed = ", ".join(map(repr, names[:5])) + (", ..." if len(names) > 5 else "")
    rubbing = [model.constraint_names[int(i)] for f in model.families if f.impact_law
               for i, mu in zip(f.indices, f.mu) if mu > 0]
    if rubbing:
        return (f"method={method!r}: the rigid contact(s) {', '.join(map(repr, rubbing[:5]))} have friction (mu > 0), "
                "which only method='moreau-jean' takes (Coulomb's law on the tangential impulses)")
    if method == "direct":
        return None
    if method == "event":
        return (f"method='event' integrates the motion between contact changes exactly and has no impact law: "
                f"the rigid contact(s) {listed} (H = 0) close with a velocity, which needs a jump of the velocity; "
                "use method='moreau-jean' (Newton's impact law) or method='direct'")
    reason = remembered(model, ("K definite",), lambda: _definite(model.K))
    if reason is None:
        return None
    return (f"method={method!r}: the structure without its rigid contact(s) {listed} is not stable by itself "
            f"({reason}: a free or rocking body), so Lambda(s) = -F^T D(s)^-1 F has poles at s = 0 or s > 0 "
            "whose convolution weights grow without bound; use method='moreau-jean' (Newton's impact law, rigid contacts "
            "only) or method='direct'")


def _definite(K) -> str | None:
    try:
        check_definite("K", K, strict=True)
    except ValueError as exc:
        return str(exc)
    d = K.diagonal() if hasattr(K, "tocsr") else np.diag(K)
    return None if np.all(d > 0) else "K has a zero or negative diagonal entry"


#: Why a rule does not give an impact law when it holds a rigid contact at the position level.
_RULE_FLAWS = {
    "trapezoidal": "the trapezoidal rule's velocity u'_n = 2 (u_n - u_{n-1}) / dt - u'_{n-1} reverses the "
                   "velocity of a contact held at zero opening (an elastic bounce, then chatter)",
    "bdf2": "BDF2 spreads an impact over a few steps of partial bounce and flight (impacts after the first "
            "do not follow Newton's or Housner's law)",
}


def rule_warning(model, method, rule) -> str | None:
    """None, or a warning when ``method`` (a name) holds the rigid contacts of ``model`` at the
    position level with a ``rule`` that gives no law of impact (every rule but BDF1: the
    trapezoidal rule bounces, BDF2 chatters; measured in ``docs/rocking.md``)."""
    if method == "moreau-jean" or getattr(rule, "name", rule) == "bdf1":
        return None
    names = rigid_contacts(model)
    if not names:
        return None
    name = getattr(rule, "name", str(rule))
    flaw = _RULE_FLAWS.get(name, f"rule={name!r} holds them at the position level with no law of impact")
    return (f"rigid contact(s) {', '.join(map(repr, names[:4]))}{', ...' if len(names) > 4 else ''} with "
            f"method={method!r} and rule={name!r}: {flaw}; for Newton's impact law use method='moreau-jean' "
            "(rigid contacts only), or rule='bdf1' (perfectly plastic impacts, first order)")
