"""Recorders: ``recorder('Node' | 'Element', '-file', name, ...)`` writing the text files OpenSees
writes.

A recorder records at every committed step of an analysis (static or transient), as OpenSees
records at each commit: one line of values separated by spaces, the domain time first with
``-time``, each value printed with ``-precision`` significant digits (6 by default, C++'s
default float format, which is ``%g``). ``-dT`` records only once the time has advanced by ``dT``
since the last record (OpenSees's tolerance of 1e-5 ``dT``). A ``Node`` recorder writes, for each
node in turn, the values of its ``-dof`` list (``disp``, ``vel``, ``accel``, ``reaction``); an
``Element`` recorder, for each element, its ``eleResponse`` of the response named. Files are
written relative to the current directory, created (emptied) when the recorder is defined and
closed by ``wipe``, ``remove('recorders')`` or the end of the program.

``EnvelopeNode`` and ``EnvelopeElement`` keep, for each value, its minimum, maximum and largest
absolute value over the records (the first time each is reached) and write them when closed: three
lines (min, max, absmax), each value preceded by its time with ``-time``, as OpenSees does.
"""

from __future__ import annotations

import atexit
from dataclasses import dataclass, field

from .refusals import refuse

__all__ = ["Recorder", "parse_recorder"]

_NODE_RESPONSES = {"disp": "nodeDisp", "vel": "nodeVel", "accel": "nodeAccel", "reaction": "nodeReaction"}


@dataclass
class Recorder:
    """One recorder: its file, what it records and when."""

    kind: str
    path: str
    tags: list
    response: tuple
    dofs: list = field(default_factory=list)
    time: bool = False
    dT: float = 0.0
    precision: int = 6
    stream: object = None
    next_time: float = None
    envelope: list = None

    def open(self):
        """Create (empty) the file."""
        self.stream = open(self.path, "w")
        atexit.register(self.close)

    def close(self):
        """Close the file (idempotent); an envelope recorder writes its three lines first."""
        if self.stream is not None and not self.stream.closed:
            if self.envelope is not None:
                p = self.precision
                for row in self.envelope:
                    items = [x for pair in row for x in (pair if self.time else pair[1:])]
                    self.stream.write(" ".join(f"{float(x):.{p}g}" for x in items) + "\n")
            self.stream.close()

    def _envelope(self, t, values):
        """Update the minima, maxima and absolute maxima with the values at time ``t``."""
        if self.envelope is None:
            self.envelope = [[(t, x) for x in values], [(t, x) for x in values], [(t, abs(x)) for x in values]]
            return
        lo, hi, ab = self.envelope
        for k, x in enumerate(values):
            if x < lo[k][1]:
                lo[k] = (t, x)
            if x > hi[k][1]:
                hi[k] = (t, x)
            if abs(x) > ab[k][1]:
                ab[k] = (t, abs(x))

    def record(self, session, t):
        """Write the line of the domain time ``t`` (if ``-dT`` lets it)."""
        if self.stream is None or self.stream.closed:
            return
        if self.dT > 0.0:
            if self.next_time is not None and t - self.next_time < -self.dT * 1e-5:
                return
            self.next_time = t + self.dT
        values = [t] if self.time and not self.kind.startswith("Envelope") else []
        if self.kind in ("Node", "EnvelopeNode"):
            command = getattr(session, _NODE_RESPONSES[self.response[0]])
            if self.response[0] == "reaction":
                session.reactions()
            for node in self.tags:
                values.extend(command(node, dof) for dof in self.dofs)
        else:
            for tag in self.tags:
                values.extend(session.eleResponse(tag, *self.response))
        if self.kind.startswith("Envelope"):
            self._envelope(t, [float(x) for x in values])
            return
        p = self.precision
        self.stream.write(" ".join(f"{float(x):.{p}g}" for x in values) + "\n")


def _take_tags(rest):
    tags = []
    while rest and not isinstance(rest[0], str):
        tags.append(int(rest.pop(0)))
    return tags


def parse_recorder(kind, args, domain) -> Recorder:
    """The recorder of ``recorder(kind, *args)``.

    Parameters
    ----------
    kind : str, ``"Node"`` or ``"Element"``
    args : tuple, its options (``-file``, ``-time``, ``-dT``, ``-precision``, ``-node``,
        ``-nodeRange``, ``-dof``, ``-ele``, ``-eleRange``) and the response
    domain : Domain, for the tags named

    Returns
    -------
    Recorder, with its file created
    """
    what = f"recorder({kind!r})"
    if kind not in ("Node", "Element", "EnvelopeNode", "EnvelopeElement"):
        refuse(what, "only the Node, Element, EnvelopeNode and EnvelopeElement recorders are in the subset "
               "(Drift, ... not yet)", "recorder('Node', ...) or recorder('Element', ...), or the queries after "
               "each analyze")
    rest, opts = list(args), {"tags": [], "dofs": [], "time": False, "dT": 0.0, "precision": 6, "path": None}
    response = []
    while rest:
        flag = rest.pop(0)
        if flag in ("-file", "-fileName") and rest:
            opts["path"] = str(rest.pop(0))
        elif flag == "-time":
            opts["time"] = True
        elif flag == "-dT" and rest:
            opts["dT"] = float(rest.pop(0))
        elif flag == "-precision" and rest:
            opts["precision"] = int(rest.pop(0))
        elif flag in ("-node", "-ele", "-eles", "-element") and rest:
            opts["tags"].extend(_take_tags(rest))
        elif flag in ("-nodeRange", "-eleRange") and len(rest) >= 2:
            a, b = int(rest.pop(0)), int(rest.pop(0))
            pool = domain.nodes if flag == "-nodeRange" else domain.elements
            opts["tags"].extend(t for t in pool if a <= t <= b)
        elif flag == "-dof" and rest:
            opts["dofs"].extend(_take_tags(rest))
        elif isinstance(flag, str) and flag.startswith("-") and not response:
            refuse(f"{what} {flag!r}", "the option is not in the subset (files in text only)",
                   "'-file', '-time', '-dT', '-precision', '-node', '-nodeRange', '-dof', '-ele', '-eleRange'")
        else:
            response.append(flag)
    return _checked(what, kind, opts, tuple(response), domain)


def _checked(what, kind, opts, response, domain) -> Recorder:
    if opts["path"] is None:
        refuse(what, "only recorders to a file are in the subset", "'-file', name")
    if not response:
        refuse(what, "the response is missing", "e.g. 'disp' (Node) or 'force' (Element)")
    node = kind in ("Node", "EnvelopeNode")
    pool = domain.nodes if node else domain.elements
    missing = [t for t in opts["tags"] if t not in pool]
    if missing or not opts["tags"]:
        refuse(what, f"{'the ' + kind.lower() + 's ' + str(missing) + ' are not defined' if missing else 'no tags'}",
               "the tags of defined nodes or elements")
    if node:
        if response[0] not in _NODE_RESPONSES or len(response) > 1:
            refuse(f"{what} {response[0]!r}", "the response is not in the subset", "'disp', 'vel', 'accel', 'reaction'")
        if not opts["dofs"] or any(d not in range(1, domain.ndf + 1) for d in opts["dofs"]):
            refuse(what, f"the DOFs {opts['dofs']} must be among 1..{domain.ndf}", "'-dof', 1, 2, ...")
    rec = Recorder(kind, opts["path"], opts["tags"], response, opts["dofs"], opts["time"], opts["dT"],
                   opts["precision"])
    rec.open()
    return rec
