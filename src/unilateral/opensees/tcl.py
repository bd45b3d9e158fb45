"""OpenSees Tcl scripts on this library: ``unilateral opensees model.tcl``.

Python's own Tcl interpreter (``tkinter.Tcl()``, no display needed) runs the script; the OpenSees
commands are registered in it as callbacks into a :class:`~.commands.Session` of their own, with
the same subset, results and refusals as :mod:`unilateral.opensees`. The arguments are parsed as
OpenSees's Tcl interpreter parses them:

* every word that reads as an integer is an integer, one that reads as a number a float, any other
  a string (``-mat``, ``Linear``);
* a word that is a Tcl list of numbers (``-values {0.0 0.1 0.3}``, ``-values $accel``) is expanded
  into its numbers;
* ``pattern Plain tag tsTag {load ...}`` evaluates its body after the pattern is defined (the loads
  belong to it); a series given in place of its tag (``pattern Plain 1 Linear {...}``,
  ``-accel "Series -dt 0.01 -filePath a.txt -factor 9.81"``) is defined under a tag of its own;
* a query returns its value to Tcl (``set u [nodeDisp 3 1]``), a list as a Tcl list, ``analyze``
  its code (0: success).

Tcl's own ``load`` (of shared libraries) is replaced by OpenSees's nodal ``load``, its ``exit``
ends the script (and not Python), and a command that is neither Tcl's nor in the subset is
refused by name (:class:`~.refusals.OpenSeesRefused`), as an OpenSees command outside the subset.
"""

from __future__ import annotations

from pathlib import Path

from .commands import Session
from .refusals import OpenSeesRefused, refused_command

__all__ = ["TclSession", "run_tcl", "run_script", "tcl_interpreter"]

_NO_TCL = ("running a Tcl script needs Python's Tcl interpreter (the tkinter module), which is not installed "
           "here: install it (Debian/Ubuntu: apt-get install python3-tk; Fedora: dnf install python3-tkinter; "
           "conda: conda install tk), or run the script as OpenSeesPy with import unilateral.opensees as ops")

#: The series types of OpenSees's inline ``{Series ...}`` specifications and their timeSeries kind.
_INLINE_SERIES = {"Series": "Path", "Path": "Path", "Linear": "Linear", "Constant": "Constant",
                  "Trig": "Trig", "Sine": "Trig"}


class _Exit(Exception):
    """Tcl's ``exit`` in the script."""


def tcl_interpreter():
    """A Tcl interpreter without a display (``tkinter.Tcl()``).

    Raises
    ------
    RuntimeError
        If Python has no Tcl interpreter, with how to install it.
    """
    try:
        import tkinter
    except ImportError:
        raise RuntimeError(_NO_TCL) from None
    try:
        return tkinter.Tcl()
    except Exception as exc:                               # tkinter present, Tcl library missing
        raise RuntimeError(f"{_NO_TCL} ({exc})") from None


def _number(word):
    """An OpenSees argument: int, float or the string itself."""
    try:
        return int(word)
    except ValueError:
        pass
    try:
        return float(word)
    except ValueError:
        return word


class TclSession:
    """One Tcl interpreter with the OpenSees commands of one :class:`~.commands.Session`.

    Parameters
    ----------
    session : Session, optional
        The session the commands act on (a new one by default).
    """

    def __init__(self, session=None):
        self.session = session or Session()
        self.tcl = tcl_interpreter()
        self.error = None
        self._inline = 0
        table = self.session.commands()
        for name, function in table.items():
            self._register(name, function)
        self._register("pattern", self._pattern, raw=True)
        self._register("exit", self._exit, raw=True)
        self._register("unknown", self._unknown, raw=True)

    # ------------------------------------------------------------------ registration
    def _register(self, name, function, raw=False):
        def callback(*words):
            """The OpenSees command ``name`` on the Tcl words."""
            try:
                return _result(function(*(words if raw else self._arguments(words))))
            except (OpenSeesRefused, _Exit) as exc:
                self.error = exc
                raise
            except Exception as exc:                        # a Python error: keep it for the caller
                self.error = exc
                raise
        self.tcl.createcommand(name, callback)

    def _arguments(self, words):
        """The words of a command as OpenSees's Tcl interpreter reads them (numbers, flags, lists)."""
        out = []
        for word in words:
            word = str(word)
            if any(c.isspace() for c in word.strip()):
                items = [_number(w) for w in _split(self.tcl, word)]
                if items and not any(isinstance(x, str) for x in items):
                    out.extend(items)
                    continue
            out.append(_number(word))
        return out

    # ------------------------------------------------------------------ commands with Tcl semantics
    def _series_tag(self, word):
        """The tag of a series given by its tag or inline (``"Series -dt 0.01 -values {...}"``)."""
        value = _number(str(word))
        if not isinstance(value, str):
            return value
        items = [str(w) for w in self.tcl.splitlist(value)]
        if not items or items[0] not in _INLINE_SERIES:
            return value                                    # let the pattern refuse it by name
        self._inline -= 1
        self.session.domain.timeSeries(_INLINE_SERIES[items[0]], self._inline, *self._arguments(items[1:]))
        return self._inline

    def _pattern(self, kind, tag, *words):
        """``pattern Plain tag ts ?-fact f? {body}``, ``pattern UniformExcitation tag dir -accel ts``."""
        words = [str(w) for w in words]
        body = None
        if kind == "Plain" and len(words) >= 2 and not _is_number(words[-1]) and not words[-1].startswith("-"):
            body = words.pop()
        if kind == "Plain" and words:
            words[0] = self._series_tag(words[0])
        for flag in ("-accel", "-disp", "-vel"):
            if flag in words[:-1]:
                at = words.index(flag) + 1
                words[at] = self._series_tag(words[at])
        args = [w if not isinstance(w, str) else _number(w) for w in words]
        self.session.domain.pattern(_number(kind), _number(tag), *args)
        if body is not None:
            self.tcl.eval(body)
        return ""

    def _exit(self, *words):
        raise _Exit()

    def _unknown(self, name, *words):
        refused_command(str(name))(*words)

    # ------------------------------------------------------------------ running
    def source(self, path):
        """Run the Tcl script at ``path`` (relative files, e.g. ``-filePath``, from the current directory).

        Raises
        ------
        OpenSeesRefused
            For a command outside the subset (its message says where in the script).
        RuntimeError
            For a Tcl error of the script itself.
        """
        self.eval(f"source {{{Path(path)}}}")

    def eval(self, text):
        """Evaluate Tcl ``text``; the errors as :meth:`source`. Returns Tcl's result (a string)."""
        import tkinter

        self.error = None
        try:
            return self.tcl.eval(text)
        except tkinter.TclError as exc:
            error, self.error = self.error, None
            if isinstance(error, _Exit):
                return ""
            where = self._where()
            if isinstance(error, OpenSeesRefused):
                raise OpenSeesRefused(error.what, error.why, f"{error.instead} ({where})") from None
            if error is not None:
                raise RuntimeError(f"{type(error).__name__}: {error} ({where})") from error
            raise RuntimeError(f"Tcl error: {exc} ({where})") from None

    def _where(self):
        info = str(self.tcl.eval("set ::errorInfo")).strip().splitlines()
        lines = [line.strip() for line in info if "line" in line]
        return "; ".join(lines[-2:]) if lines else "in the script"


def _split(tcl, word):
    """The elements of a Tcl list, or ``[word]`` if it is not one."""
    import tkinter

    try:
        return tcl.splitlist(word)
    except tkinter.TclError:
        return [word]


def _is_number(word):
    return not isinstance(_number(word), str)


def _result(value):
    """A Python result as Tcl takes it: None -> "", a list -> a tuple (a Tcl list)."""
    if value is None:
        return ""
    if isinstance(value, (list, tuple)):
        return tuple(float(x) if not isinstance(x, int) else x for x in value)
    return value


def run_tcl(path, session=None) -> TclSession:
    """Run the OpenSees Tcl script ``path`` on this library; the :class:`TclSession` it ran in."""
    tcl = TclSession(session)
    tcl.source(path)
    return tcl


def run_script(path) -> None:
    """Run an OpenSees script on this library: Tcl (``.tcl``) or OpenSeesPy (``.py``).

    A Python script runs as it is, its ``openseespy.opensees`` (or ``opensees``) being
    :mod:`unilateral.opensees`.

    Raises
    ------
    OpenSeesRefused
        For a command outside the subset.
    RuntimeError
        For an error of the script, or a Tcl script without a Tcl interpreter.
    """
    import runpy
    import sys
    import types

    path = Path(path)
    if path.suffix.lower() != ".py":
        run_tcl(path)
        return
    from .. import opensees

    package = types.ModuleType("openseespy")
    package.opensees = opensees
    saved = {name: sys.modules.get(name) for name in ("openseespy", "openseespy.opensees", "opensees")}
    sys.modules.update({"openseespy": package, "openseespy.opensees": opensees, "opensees": opensees})
    try:
        runpy.run_path(str(path), run_name="__main__")
    finally:
        for name, module in saved.items():
            if module is None:
                sys.modules.pop(name, None)
            else:
                sys.modules[name] = module
