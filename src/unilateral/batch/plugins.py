"""Dask worker plugins of the batch runner (imported only when a study runs on Dask)."""

from __future__ import annotations

import signal
import threading

from distributed.diagnostics.plugin import WorkerPlugin


class IgnoreInterrupts(WorkerPlugin):
    """The worker process ignores SIGINT: Ctrl-C on a terminal reaches the whole process group, and
    the process that runs the study handles it (cancels the tasks, closes the cluster)."""

    name = "unilateral-ignore-sigint"

    def setup(self, worker):
        if threading.current_thread() is threading.main_thread():
            signal.signal(signal.SIGINT, signal.SIG_IGN)
