"""A progress bar over the analyses of a study: done, failed, remaining, throughput and ETA.

On a terminal the bar is redrawn in place (twice a second, so the ETA counts down between
completions); elsewhere (a log file, CI) a line is printed every 10 % or every 30 s. The ETA is
the number of analyses left divided by the throughput measured over the recent completions of
this run (not counting analyses done by an earlier run, nor the start-up of the workers), and
is shown only once three analyses have finished.
"""

from __future__ import annotations

import sys
import threading
import time
from collections import deque

FAILED = ("failed", "error", "timeout")


def _clock(seconds: float) -> str:
    if seconds != seconds or seconds == float("inf"):
        return "?"
    seconds = int(round(seconds))
    h, rest = divmod(seconds, 3600)
    m, s = divmod(rest, 60)
    return f"{h}:{m:02d}:{s:02d}" if h else f"{m}:{s:02d}"


class Progress:
    """Counts of a study's analyses, drawn as a bar on ``stream``.

    Parameters
    ----------
    total : int
        Analyses of the study.
    done, failed : int
        Already done by an earlier run (``failed`` of them failed).
    enabled : bool
        False: draw nothing (the counts are kept).
    stream : file, optional
        Default ``sys.stderr``.
    """

    def __init__(self, total: int, done: int = 0, failed: int = 0, *, enabled: bool = True, stream=None,
                 label: str = "analyses"):
        self.total = total
        self.earlier = done
        self.done = done
        self.failed = failed
        self.label = label
        self.stream = stream or sys.stderr
        self.enabled = enabled
        self.tty = enabled and hasattr(self.stream, "isatty") and self.stream.isatty()
        self.window = deque(maxlen=20)
        self.start = time.monotonic()
        self._last_line = -1.0
        self._last_decile = -1
        self._lock = threading.Lock()
        self._stop = threading.Event()
        self._thread = None
        if self.tty:
            self._thread = threading.Thread(target=self._redraw, name="unilateral-progress", daemon=True)
            self._thread.start()
        self._draw(force=True)

    # ------------------------------------------------------------------ counts
    @property
    def remaining(self) -> int:
        return self.total - self.done

    def rate(self) -> float:
        """Analyses per second over the recent completions of this run (nan before 3)."""
        if len(self.window) < 3:
            return float("nan")
        span = self.window[-1] - self.window[0]
        return (len(self.window) - 1) / span if span > 0 else float("nan")

    def eta(self) -> float:
        rate = self.rate()
        if rate != rate or rate <= 0:
            return float("nan")
        since = time.monotonic() - self.window[-1]
        return max(self.remaining / rate - since, 0.0)

    def update(self, result: dict) -> None:
        """Count one finished analysis (its result dict, with ``status``)."""
        with self._lock:
            self.done += 1
            if result.get("status") in FAILED:
                self.failed += 1
            self.window.append(time.monotonic())
        self._draw()

    # ------------------------------------------------------------------ drawing
    def line(self, width: int = 24) -> str:
        fraction = self.done / self.total if self.total else 1.0
        filled = int(round(width * fraction))
        bar = "#" * filled + "-" * (width - filled)
        rate = self.rate()
        speed = f"{rate:.2f}/s" if rate == rate else "-/s"
        earlier = f" ({self.earlier} earlier)" if self.earlier else ""
        return (f"[{bar}] {self.done}/{self.total} {self.label}{earlier}: {self.done - self.failed} ok, "
                f"{self.failed} failed, {self.remaining} left, {speed}, ETA {_clock(self.eta())}")

    def _draw(self, force: bool = False) -> None:
        if not self.enabled:
            return
        with self._lock:
            if self.tty:
                self.stream.write("\r" + self.line() + "\x1b[K")
                self.stream.flush()
                return
            now = time.monotonic()
            decile = int(10 * self.done / self.total) if self.total else 10
            if force or decile != self._last_decile or now - self._last_line > 30 or self.done == self.total:
                self._last_decile, self._last_line = decile, now
                self.stream.write(self.line() + "\n")
                self.stream.flush()

    def _redraw(self) -> None:
        while not self._stop.wait(0.5):
            self._draw()

    def close(self) -> None:
        self._stop.set()
        if self._thread is not None:
            self._thread.join()
        if self.tty:
            self._draw()
            self.stream.write("\n")
            self.stream.flush()
