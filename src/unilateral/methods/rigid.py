"""Which methods take rigid contacts (``H = 0`` rows in the force form, :mod:`unilateral.structure.rigid`).

``direct`` takes them with every rule (the condensed LCP on ``P W0 = (1 - alpha) F^T D_eff^-1 F``).
``cq`` and ``modal`` take them where ``K`` (the structure without its rigid contacts) is positive
definite; a free or rocking body (``K`` singular or indefinite) puts poles of
``Lambda(s) = -F^T D(s)^-1 F`` at ``s = 0`` or ``s > 0``, whose convolution weights grow without
bound. ``event`` never: it has no impact law.
"""

from __future__ import annotations

import numpy as np

from ..constraints import SoilContact
from ..model import check_definite, remembered


def rigid_contacts(model) -> list:
    """Names of the rigid contacts of a matrix ``model``: unknowns of a dual-form contact family
    (:class:`~unilateral.constraints.RigidContact`, :class:`~unilateral.constraints.SoilContact`)
    whose ``H(s)`` has a zero diagonal (no compliance). Empty for other problems."""
    if getattr(model, "kind", None) != "matrices":
        return []
    H, H_v = np.asarray(model.H), None if model.H_v is None else np.asarray(model.H_v)
    out = []
    for family in model.families:
        if isinstance(family, SoilContact):
            out += [int(i) for i in family.indices if H[i, i] == 0 and (H_v is None or H_v[i, i] == 0)]
    return [model.constraint_names[i] for i in sorted(out)]


def refusal(model, method) -> str | None:
    """None if ``method`` (``"cq"``, ``"modal"`` or ``"event"``) solves ``model``'s rigid contacts,
    else why not."""
    names = rigid_contacts(model)
    if not names:
        return None
    listed = ", ".join(map(repr, names[:5])) + (", ..." if len(names) > 5 else "")
    if method == "event":
        return (f"method='event' integrates the motion between contact changes exactly and has no impact law: "
                f"the rigid contact(s) {listed} (H = 0) close with a velocity, which needs a jump of the velocity; "
                "use method='direct'")
    reason = remembered(model, ("K definite",), lambda: _definite(model.K))
    if reason is None:
        return None
    return (f"method={method!r}: the structure without its rigid contact(s) {listed} is not stable by itself "
            f"({reason}: a free or rocking body), so Lambda(s) = -F^T D(s)^-1 F has poles at s = 0 or s > 0 "
            "whose convolution weights grow without bound; use method='direct'")


def _definite(K) -> str | None:
    try:
        check_definite("K", K, strict=True)
    except ValueError as exc:
        return str(exc)
    d = K.diagonal() if hasattr(K, "tocsr") else np.diag(K)
    return None if np.all(d > 0) else "K has a zero or negative diagonal entry"
