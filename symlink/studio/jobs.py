"""Long work of the studio (a path synthesis) in a worker process: started, polled, cancelled.

:func:`symlink.synthesis.general.synthesize_path` takes no callback and no stop flag, so a search cannot be
interrupted from inside: each job runs in its own process (``spawn``: a fresh interpreter, since the server's
process has threads and SymPy's caches), which ``cancel`` terminates at once.  The worker says what it is
doing (``deriving`` the linkage and its generated code, then ``searching``) and sends its result; a thread of
the server waits for it.  At most :data:`MAX_RUNNING` jobs run at a time and each is stopped after
:data:`TIME_LIMIT` seconds; finished jobs are kept (the last :data:`KEPT`) until polled.
"""
from __future__ import annotations

import multiprocessing
import secrets
import threading
import time
from typing import Any, Callable, Mapping

__all__ = ["Jobs", "MAX_RUNNING", "TIME_LIMIT", "KEPT"]

#: Jobs running at once (each a process doing numerical work on a machine shared with the page).
MAX_RUNNING = 1
#: Seconds a job may run before it is stopped.
TIME_LIMIT = 600.0
#: Finished jobs remembered for polling.
KEPT = 16


def _worker(task: str, request: Mapping[str, Any], connection: Any) -> None:
    """The worker process: the named task on the request, its phases and its result sent on ``connection``."""
    try:
        connection.send(("phase", "deriving"))
        from . import design
        if task != "synthesis":
            raise ValueError(f"no task {task!r}")
        checked = design.synthesis_request(dict(request))
        connection.send(("phase", "searching"))
        connection.send(("done", design.synthesis(checked)))
    except ValueError as error:
        connection.send(("failed", " ".join(str(error).split())[:2000]))
    except Exception as error:  # noqa: BLE001 - a bug: a message for the page, never a traceback
        connection.send(("failed", f"internal error ({type(error).__name__}: {error}); please report it"))
    finally:
        connection.close()


class Jobs:
    """The studio's background jobs by id: :meth:`start`, :meth:`status`, :meth:`cancel`."""

    def __init__(self, max_running: int = MAX_RUNNING, time_limit: float = TIME_LIMIT,
                 clock: Callable[[], float] = time.monotonic) -> None:
        self.max_running, self.time_limit, self.clock = max_running, time_limit, clock
        self.jobs: dict[str, dict[str, Any]] = {}
        self.lock = threading.Lock()
        self.context = multiprocessing.get_context("spawn")

    def running(self) -> list[str]:
        """The ids of the jobs not finished."""
        with self.lock:
            return [key for key, job in self.jobs.items() if job["status"] in ("starting", "deriving", "searching")]

    def start(self, task: str, request: Mapping[str, Any]) -> str:
        """A new job's id; ``ValueError`` when :data:`MAX_RUNNING` jobs already run."""
        if len(self.running()) >= self.max_running:
            raise ValueError("a synthesis is already running: wait for it or cancel it first")
        receiving, sending = self.context.Pipe(duplex=False)
        process = self.context.Process(target=_worker, args=(task, dict(request), sending), daemon=True)
        key = secrets.token_hex(8)
        job = {"id": key, "task": task, "status": "starting", "started": self.clock(), "ended": None,
               "result": None, "error": None, "process": process}
        with self.lock:
            self.jobs[key] = job
            finished = [k for k, j in self.jobs.items() if j["ended"] is not None]
            for old in finished[:-KEPT]:
                del self.jobs[old]
        process.start()
        sending.close()
        watcher = threading.Thread(target=self._watch, args=(job, receiving), daemon=True)
        job["watcher"] = watcher
        watcher.start()
        return key

    def _finish(self, job: dict[str, Any], status: str, result: Any = None, error: str | None = None) -> None:
        with self.lock:
            if job["ended"] is not None:
                return
            job.update(status=status, result=result, error=error, ended=self.clock())

    def _watch(self, job: dict[str, Any], connection: Any) -> None:
        """Wait for the worker's messages until it is done, fails, is cancelled or runs out of time."""
        process = job["process"]
        try:
            while job["ended"] is None:
                if self.clock() - job["started"] > self.time_limit:
                    process.terminate()
                    self._finish(job, "failed", error=f"stopped after {self.time_limit:g} s: ask for fewer starts "
                                                      "or evaluations, or targets a linkage can reach")
                    break
                if not connection.poll(0.2):
                    if not process.is_alive() and not connection.poll(0):
                        self._finish(job, "failed", error="the worker process stopped without an answer")
                    continue
                try:
                    kind, value = connection.recv()
                except (EOFError, OSError):
                    self._finish(job, "failed", error="the worker process stopped without an answer")
                    break
                if kind == "phase":
                    with self.lock:
                        if job["ended"] is None:
                            job["status"] = value
                elif kind == "done":
                    self._finish(job, "done", result=value)
                else:
                    self._finish(job, "failed", error=str(value))
        finally:
            connection.close()
            process.join(5)
            if process.is_alive():
                process.kill()
                process.join(5)

    def status(self, key: str) -> dict[str, Any] | None:
        """The job's status (``starting``, ``deriving``, ``searching``, ``done``, ``failed``, ``cancelled``),
        seconds elapsed, and its result or error; None for no such job."""
        with self.lock:
            job = self.jobs.get(key)
            if job is None:
                return None
            end = job["ended"] if job["ended"] is not None else self.clock()
            return {"id": key, "status": job["status"], "elapsed": end - job["started"], "result": job["result"],
                    "error": job["error"]}

    def cancel(self, key: str) -> dict[str, Any] | None:
        """Stop the job (its process terminated) and say its status; None for no such job."""
        with self.lock:
            job = self.jobs.get(key)
        if job is None:
            return None
        if job["ended"] is None:
            self._finish(job, "cancelled", error="cancelled")
            job["process"].terminate()
        return self.status(key)

    def wait(self, key: str, timeout: float | None = None) -> bool:
        """Wait until the job's worker process is gone and reaped; False when it is still there after ``timeout``.

        Only the job's watcher thread joins (reaps) the process: a second thread joining the same process races it
        for the exit status and can see a reaped process as alive, so callers wait on the watcher instead.
        """
        with self.lock:
            job = self.jobs.get(key)
        if job is None:
            raise ValueError(f"no job {key!r}")
        job["watcher"].join(timeout)
        return not job["watcher"].is_alive() and job["process"].exitcode is not None

    def close(self) -> None:
        """Stop every job still running (the server is stopping)."""
        for key in self.running():
            self.cancel(key)
