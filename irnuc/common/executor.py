"""The one executor of everything that runs many independent tasks (sweep points,
syntheses, mutants): worker processes, in-process, or a Dask distributed cluster, behind
the same ``concurrent.futures`` interface.
"""

from __future__ import annotations

import concurrent.futures as cf
import contextlib
import multiprocessing
import threading
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from typing import Any

from irnuc.common.errors import UserError

#: Seconds to wait for a Dask scheduler before giving up with a clear message.
CONNECT_TIMEOUT = 10

#: Memory of one worker process before its work, bytes: a fresh interpreter that has
#: imported numpy, numba and the golden model (measured 161 MiB each, with the
#: forkserver, for 8 workers of ``irnuc sweep``); memory estimates count it per worker.
WORKER_PROCESS_BYTES = 256 * 2**20


class ExecutorError(UserError):
    """The executor asked for cannot be had (a bad worker count, an unreachable cluster)."""


class InlineExecutor(cf.Executor):
    """Runs each task at submit time in the calling thread (workers = 0; debugging)."""

    def submit(self, fn: Callable[..., Any], /, *args: Any, **kwargs: Any) -> cf.Future:
        fut: cf.Future = cf.Future()
        try:
            fut.set_result(fn(*args, **kwargs))
        except BaseException as exc:
            fut.set_exception(exc)
        return fut


@dataclass
class ExecutorHandle:
    """An executor, how to hand it large shared data, and per-task numba threads."""

    executor: cf.Executor
    kind: str  # "process", "inline" or "dask"
    share: Callable[[Any], Any]
    threads: int | None
    description: str


def _mp_context() -> multiprocessing.context.BaseContext:
    # Fresh interpreters (not a fork of a parent whose numba thread pool is running).
    methods = multiprocessing.get_all_start_methods()
    return multiprocessing.get_context("forkserver" if "forkserver" in methods else "spawn")


def _probe(scheduler: str) -> None:
    """Fail at once on a ``tcp://`` scheduler address that refuses connections (Dask itself
    retries for the whole timeout); other addresses are left to Dask."""
    import socket
    from urllib.parse import urlsplit

    if not scheduler.startswith("tcp://"):
        return
    try:
        parts = urlsplit(scheduler)
        host, port = parts.hostname, parts.port
    except ValueError:
        host = port = None
    if not host or port is None:
        raise ExecutorError(f"--scheduler {scheduler}: expected tcp://HOST:PORT")
    try:
        socket.create_connection((host, port), timeout=CONNECT_TIMEOUT).close()
    except OSError as exc:
        raise ExecutorError(f"--scheduler {scheduler}: no Dask scheduler answered "
                            f"({exc.strerror or exc}); start one or run without --scheduler"
                            ) from None


#: Per thread: the niceness the process pools it opens give their workers (and so the tools
#: those run): :func:`background_priority`.
_PRIORITY = threading.local()


@contextlib.contextmanager
def background_priority(nice: int = 10) -> Iterator[None]:
    """Run this thread's work at a lower CPU priority (Linux: the thread's own niceness,
    which the processes it starts inherit, and the workers of the process pools it opens):
    work started beside a phase takes the cores the phase leaves idle, not the phase's."""
    import os

    tid = threading.get_native_id()
    try:
        before = os.getpriority(os.PRIO_PROCESS, tid)
        os.setpriority(os.PRIO_PROCESS, tid, min(19, before + int(nice)))
    except (OSError, AttributeError):  # no per-thread priority here: run as is
        before = None
    _PRIORITY.nice = int(nice)
    try:
        yield
    finally:
        _PRIORITY.nice = 0
        if before is not None:
            try:  # lowering it back may need privileges: the thread then stays nice
                os.setpriority(os.PRIO_PROCESS, tid, before)
            except OSError:
                pass


def start_forkserver() -> None:
    """Start the forkserver that forks every pool's workers, if not running, from the
    calling thread: called by the thread that starts background work before it does, so
    that the server (and every later worker, the phases' too) has that thread's priority,
    not the background's (:func:`background_priority`)."""
    if _mp_context().get_start_method() == "forkserver":
        from multiprocessing import forkserver

        forkserver.ensure_running()


def _die_with(pid: int, nice: int = 0) -> None:
    """Worker initializer: end this worker as soon as the process that opened the pool is
    gone (even killed with SIGKILL). Workers are children of the forkserver, not of that
    process, so its death is not signalled to them; their own children (a Yosys or
    nextpnr run through ``run_child``) then die with them (``PR_SET_PDEATHSIG``). ``nice``:
    this worker's niceness set to it (the opening thread's, :func:`background_priority`)."""
    import os
    import threading
    import time

    if nice:
        try:  # absolute: the opener's thread's niceness (inherited or not by the forkserver)
            os.setpriority(os.PRIO_PROCESS, 0, int(nice))
        except OSError:
            pass

    def watch() -> None:
        while True:
            try:
                os.kill(pid, 0)
            except ProcessLookupError:
                os._exit(1)
            except PermissionError:
                pass
            time.sleep(0.5)

    threading.Thread(target=watch, daemon=True, name="irnuc-die-with-parent").start()


@contextlib.contextmanager
def open_executor(workers: int = 2, scheduler: str | None = None) -> Iterator[ExecutorHandle]:
    """A ``concurrent.futures``-style executor for the sweep points.

    Parameters
    ----------
    workers : int
        Worker processes (default 2, started by forkserver so that they do not inherit a
        running numba thread pool); 0 runs in-process. Ignored with ``scheduler``.
    scheduler : str, optional
        Address of a Dask distributed scheduler (``tcp://host:8786``, or the
        ``scheduler_address`` of a ``LocalCluster``). Needs ``dask[distributed]``.
    """
    if scheduler:
        try:
            from distributed import Client
        except ImportError:
            raise ExecutorError(
                f"--scheduler {scheduler!r} needs Dask distributed, which is not installed; "
                "install it with: pip install 'dask[distributed]' (or run without --scheduler)"
            ) from None
        _probe(scheduler)
        try:
            client = Client(scheduler, timeout=f"{CONNECT_TIMEOUT}s")
        except (OSError, TimeoutError, ValueError) as exc:
            raise ExecutorError(f"--scheduler {scheduler}: no Dask scheduler answered within "
                                f"{CONNECT_TIMEOUT} s ({type(exc).__name__}: {exc})") from None
        try:
            n = len(client.scheduler_info().get("workers", {}))
            yield ExecutorHandle(
                executor=client.get_executor(), kind="dask",
                share=lambda obj: client.scatter(obj, broadcast=True),
                threads=None, description=f"dask {scheduler} ({n} worker(s))")
        finally:
            client.close()
        return
    if not isinstance(workers, int) or workers < 0 or workers > 256:
        raise ExecutorError(f"workers = {workers!r} is outside the allowed range 0..256")
    if workers == 0:
        yield ExecutorHandle(InlineExecutor(), "inline", lambda obj: obj, None, "in-process")
        return
    import os

    nice = (os.getpriority(os.PRIO_PROCESS, threading.get_native_id())
            if getattr(_PRIORITY, "nice", 0) else 0)
    with cf.ProcessPoolExecutor(max_workers=workers, mp_context=_mp_context(),
                                initializer=_die_with, initargs=(os.getpid(), nice)) as ex:
        yield ExecutorHandle(ex, "process", lambda obj: obj, 1, f"{workers} process(es)")


