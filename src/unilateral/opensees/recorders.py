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

The states of the steps of one ``analyze`` are kept and written when it returns, computed as one
block (vectorised over the steps and the nodes or springs, :mod:`.springs`) and formatted at once:
the same numbers and text as one line per step. A recorder of beams, reactions or extension
elements writes its line at each step from the queries (an extension's forces are the reactions
``psi`` of the step, which the kept states do not hold), so its lines are the values the queries
return after each step, as computed when the step is committed.
"""

from __future__ import annotations

import atexit
from dataclasses import dataclass, field

import numpy as np

from .elements import Truss
from .extension_results import accepted, command_name, response_names
from .queries import spring_kind
from .refusals import refuse
from .springs import nodal_block, spring_table, stress_block

__all__ = ["Recorder", "parse_recorder"]

_NODE_RESPONSES = {"disp": "nodeDisp", "vel": "nodeVel", "accel": "nodeAccel", "reaction": "nodeReaction"}
#: The state (in a pending step ``(t, built, plan, u, ud, udd, v)``) a Node recorder's response reads.
_NODE_STATE = {"disp": 3, "vel": 4, "accel": 5}
#: A block holds at most this many state entries (steps x DOFs) before it is written.
BLOCK_ENTRIES = 2_000_000


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
    pending: list = field(default_factory=list)
    plan: tuple = None

    def open(self):
        """Create (empty) the file."""
        self.stream = open(self.path, "w")
        atexit.register(self.close)

    def close(self):
        """Close the file (idempotent); an envelope recorder writes its three lines first."""
        if self.stream is not None and not self.stream.closed:
            self.flush()
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

    def _due(self, t) -> bool:
        """Whether ``-dT`` lets the recorder record at time ``t`` (and, if so, when it records next)."""
        if self.dT > 0.0:
            if self.next_time is not None and t - self.next_time < -self.dT * 1e-5:
                return False
            self.next_time = t + self.dT
        return True

    def commit(self, session, t):
        """Record the state the analysis committed at time ``t``: kept for the block written by
        :meth:`flush` if its values can be computed as a block, else written now (:meth:`record`)."""
        if self.stream is None or self.stream.closed:
            return
        a = session.analysis
        b = a.built
        if b is None or a.built_version != session.domain.version:     # (record() of a model not built)
            self.flush()
            self.record(session, t)
            return
        if self.plan is None or self.plan[0] is not b:
            self.plan = (b, _block_plan(self, b, session.domain))
        plan = self.plan[1]
        if plan is None:
            self.flush()
            self.record(session, t)
            return
        if self._due(t):
            self.pending.append((t, b, plan, a.u, a.ud, a.udd, a.v))
            if len(self.pending) * max(b.model.n, 1) >= BLOCK_ENTRIES:
                self.flush()

    def flush(self):
        """Write the lines (or update the envelope) of the steps kept by :meth:`commit`."""
        pending, self.pending = self.pending, []
        start = 0
        while start < len(pending):
            b = pending[start][1]
            stop = start + 1
            while stop < len(pending) and pending[stop][1] is b:
                stop += 1
            self._write_block(pending[start:stop])
            start = stop

    def _write_block(self, steps):
        """The values (S, columns) of the steps ``steps`` of one built model, written or enveloped."""
        t = np.array([step[0] for step in steps], dtype=float)
        values = _block_values(self, steps)
        if self.kind.startswith("Envelope"):
            self._envelope_block(t, values)
            return
        if self.time:
            values = np.column_stack([t, values])
        _write_lines(self.stream, values, self.precision)

    def _envelope_block(self, t, values):
        """:meth:`_envelope` of each row of ``values`` (S, columns) at the times ``t`` (S,), at once."""
        if np.isnan(values).any():
            for time, row in zip(t.tolist(), values.tolist()):
                self._envelope(time, row)
            return
        if self.envelope is None:
            self._envelope(float(t[0]), values[0].tolist())
            t, values = t[1:], values[1:]
            if not t.size:
                return
        columns = np.arange(values.shape[1])
        magnitude = np.abs(values)
        for store, X, pick, better in ((self.envelope[0], values, np.argmin, np.less),
                                       (self.envelope[1], values, np.argmax, np.greater),
                                       (self.envelope[2], magnitude, np.argmax, np.greater)):
            first = pick(X, axis=0)                      # the first step reaching the block's extreme
            best = X[first, columns]
            old = np.array([x for _, x in store])
            for k in np.flatnonzero(better(best, old)):
                store[k] = (float(t[first[k]]), float(best[k]))

    def record(self, session, t):
        """Write the line of the domain time ``t`` (if ``-dT`` lets it) from the queries."""
        if self.stream is None or self.stream.closed:
            return
        if not self._due(t):
            return
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


def _write_lines(stream, values, precision, rows=2048):
    """Write ``values`` (S, columns) as S lines of ``%.{precision}g`` values separated by spaces
    (Python's ``format(x, '.{precision}g')``, the text of one line per step)."""
    line = " ".join([f"%.{int(precision)}g"] * values.shape[1]) + "\n"
    for start in range(0, values.shape[0], rows):
        block = values[start:start + rows]
        stream.write((line * block.shape[0]) % tuple(block.ravel().tolist()))


def _block_plan(rec, b, domain):
    """How the values of ``rec`` are read from a block of states of the built model ``b``:
    ``("node", state, indices)`` or ``("springs", table, indices, force)``; None if they are not
    (reactions, beams, a truss's inertia in its force, a response not in the subset: the queries
    then write, or refuse, each line)."""
    if rec.kind in ("Node", "EnvelopeNode"):
        which = rec.response[0]
        if which not in _NODE_STATE:
            return None
        return ("node", _NODE_STATE[which], np.array([b.row[node] + dof - 1 for node in rec.tags for dof in rec.dofs],
                                                     dtype=np.int64))
    name = rec.response[0] if rec.response else None
    kinds = []
    for tag in rec.tags:
        e = domain.elements.get(tag)
        kind = spring_kind(e, name) if tag in b.springs else None
        if kind is None or (kind == "force" and isinstance(e, Truss) and e.rho):
            return None
        kinds.append((tag, kind))
    table = spring_table(b, domain)
    nf, force = 2 * b.ndf, any(kind == "force" for _, kind in kinds)
    offset = {"e": 0, "f": table.n, "force": 2 * table.n}
    index = []
    for tag, kind in kinds:
        if kind == "force":
            at = offset["force"] + nf * table.elements[tag]
            index.extend(range(at, at + nf))
        else:
            index.extend(offset[kind] + k for k in range(table.columns[tag].start, table.columns[tag].stop))
    return ("springs", table, np.array(index, dtype=np.int64), force)


def _block_values(rec, steps) -> np.ndarray:
    """The values (S, columns) of ``rec`` at the pending ``steps`` of one built model."""
    b, plan = steps[0][1], steps[0][2]
    if plan[0] == "node":
        return nodal_block(b, [step[plan[1]] for step in steps])[:, plan[2]]
    _, table, index, force = plan
    u = np.array([step[3] for step in steps])
    springs = table.state(nodal_block(b, u), nodal_block(b, [step[4] for step in steps]),
                          stress_block(b, u, np.array([step[6] for step in steps])))
    parts = [springs["e"], springs["f"]]
    if force:
        parts.append(springs["force"].reshape(len(steps), -1))
    return np.concatenate(parts, axis=1)[:, index]


def _check_extensions(what, tags, response, domain):
    """Refuse a response that an extension element among ``tags`` does not answer, naming its
    command, the response and the valid ones."""
    for tag in tags:
        e = domain.extensions.get(tag) if tag not in domain.elements else None
        if e is None:
            continue
        command = command_name(e)
        if len(response) > 1 or not accepted(e, response[0]):
            refuse(f"{what} of {command}({tag}) {' '.join(map(repr, response))}",
                   f"the response is not one of a {command}'s", ", ".join(map(repr, response_names(e))))


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
            pool = list(domain.nodes) if flag == "-nodeRange" else [*domain.elements, *domain.extensions]
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
    pool = domain.nodes if node else {**domain.elements, **domain.extensions}
    missing = [t for t in opts["tags"] if t not in pool]
    if missing or not opts["tags"]:
        refuse(what, f"{'the ' + kind.lower() + 's ' + str(missing) + ' are not defined' if missing else 'no tags'}",
               "the tags of defined nodes or elements")
    if node:
        if response[0] not in _NODE_RESPONSES or len(response) > 1:
            refuse(f"{what} {response[0]!r}", "the response is not in the subset", "'disp', 'vel', 'accel', 'reaction'")
        if not opts["dofs"] or any(d not in range(1, domain.ndf + 1) for d in opts["dofs"]):
            refuse(what, f"the DOFs {opts['dofs']} must be among 1..{domain.ndf}", "'-dof', 1, 2, ...")
    else:
        _check_extensions(what, opts["tags"], response, domain)
    rec = Recorder(kind, opts["path"], opts["tags"], response, opts["dofs"], opts["time"], opts["dT"],
                   opts["precision"])
    rec.open()
    return rec
