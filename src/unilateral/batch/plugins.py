"""Dask worker plugins of the batch runner (imported only when a study runs on Dask)."""

from __future__ import annotations

import logging
import signal
import threading

from distributed.diagnostics.plugin import WorkerPlugin


class IgnoreInterrupts(WorkerPlugin):
    """The worker process ignores SIGINT: Ctrl-C on a terminal reaches the whole process group, and
    the process that runs the study handles it (cancels the tasks, closes the cluster).

    When that process closes the scheduler before a worker has stopped (on a loaded machine the
    closing can outlast its timeouts), the worker's next heartbeat fails and Dask logs it with a
    traceback; the study itself has ended as it should, so those records are dropped.
    """

    name = "unilateral-ignore-sigint"

    def setup(self, worker):
        if threading.current_thread() is threading.main_thread():
            signal.signal(signal.SIGINT, signal.SIG_IGN)
        logging.getLogger("distributed.worker").addFilter(_heartbeat_after_close)


def _heartbeat_after_close(record) -> bool:
    """False for the record of a heartbeat that failed because the scheduler is gone."""
    return not record.getMessage().startswith("Failed to communicate with scheduler during heartbeat")
