"""Sweeps from Python: the command line's sweep files, run on any
``concurrent.futures.Executor`` (a Dask ``Client.get_executor()``, mpi4py's
``MPIPoolExecutor``, the standard library's ``ProcessPoolExecutor``, Ray through
``pirqa.executors.RayExecutor``) or in this process on threads. pirqa schedules nothing itself:
it cuts the pending cases into batches, submits one task per batch, and stores each batch's rows
as it comes back, in the same files the command line writes.

Determinism: a case's id is its index in the sweep's fixed enumeration (wall, then motion, then
friction sample), its friction samples a pure function of the sweep's seed and the case, and
its rows the same wherever it runs; so the results never depend on the executor, the number of
workers, the batch size or the threads. Only timing.csv (CPU times) is measured.
"""

from __future__ import annotations

import os
import sys
import tempfile
from concurrent.futures import Executor, FIRST_EXCEPTION, wait
from pathlib import Path
from typing import Callable

from . import _pirqa

#: Largest batch: a task of a few hundred small cases costs a fraction of a second, far more
#: than a task's overhead on any engine, and still spreads over many workers.
MAX_BATCH = 500

#: Blocks x cases per task that auto batching aims at: 5-block cases go 500 to a task, walls of
#: 5,000 blocks and more one case per task.
BATCH_BLOCKS = 5000

#: Auto batching cuts a sweep into at least this many tasks (when it has that many cases), so
#: that every worker of a cluster gets some.
MIN_TASKS = 64


def auto_batch_size(cases: int, max_blocks: int) -> int:
    """Cases per task: hundreds of small cases, one large wall."""
    by_cost = max(1, min(MAX_BATCH, BATCH_BLOCKS // max(max_blocks, 1)))
    spread = max(1, -(-cases // MIN_TASKS))
    return min(by_cost, spread)


def _run_batch(path: str, fingerprint: str, ids: list[int]) -> tuple[str, str, str]:
    """A task: runs the cases ``ids`` in the worker; plain strings back (they pickle)."""
    return _pirqa.run_batch(path, fingerprint, ids)


def _read_table(path: Path, text: tuple[str, ...] = ()):
    """A table a sweep wrote, as a pandas DataFrame keyed by case id, every number as written
    (to the bit), the columns ``text`` as text."""
    import pandas as pd

    # pandas 3 reads every float to the bit by default and deprecates the option that pandas 2
    # needs for it.
    exact = {} if int(pd.__version__.split(".")[0]) >= 3 else {"float_precision": "round_trip"}
    return pd.read_csv(
        path,
        index_col="case",
        keep_default_na=False,
        na_values=[""],
        dtype={column: str for column in text},
        **exact,
    )


def read_sweep(out: str | os.PathLike):
    """The cases of a finished sweep folder (the command line's or Python's) as a pandas
    DataFrame keyed by case id, every number as written (to the bit)."""
    return _read_table(Path(out) / "cases.csv")


def residual(spec: str | os.PathLike, out: str | os.PathLike):
    """For every case of the sweep ``spec`` finished in ``out``, the limit at rest of its wall
    where its run left it, beside its wall's as built (``pirqa sweep FILE --out DIR
    --residual``, docs/sweeps.md): writes residual.csv and capacity-left.svg into ``out`` and
    returns residual.csv as a pandas DataFrame keyed by case id (the exact limits as text)."""
    _pirqa.sweep_residual(os.fspath(spec), os.fspath(out))
    return _read_table(Path(out) / "residual.csv", ("plus_x_exact_g", "minus_x_exact_g"))


def _report(progress: Callable[[int, int], None] | None, total: int):
    if progress is not None:
        return progress
    if not sys.stderr.isatty():
        return lambda done, total: None

    def line(done: int, total: int) -> None:
        print(f"\rpirqa sweep: {done}/{total} cases", end="" if done < total else "\n",
              file=sys.stderr, flush=True)

    return line


def sweep(
    spec: str | os.PathLike,
    executor: Executor | None = None,
    *,
    out: str | os.PathLike | None = None,
    resume: bool = False,
    fresh: bool = False,
    batch_size: int | None = None,
    threads: int | None = None,
    progress: Callable[[int, int], None] | None = None,
):
    """Runs the sweep file ``spec`` (the command line's format, docs/sweeps.md) and returns its
    cases as a pandas DataFrame keyed by case id: cases.csv, row for row.

    ``executor``: where the cases run, one task per batch of ``batch_size`` cases (default:
    hundreds of small cases per task, one case of a very large wall); ``None`` runs them in
    this process on ``threads`` threads (default: every core). The sweep file and the files it
    names must be readable by the workers at the same path (a shared file system on a cluster).

    ``out``: the folder for cases.csv, blocks.csv, timing.csv, manifest.json, results.json and
    the charts, the same files as ``pirqa sweep`` writes; cases are stored as they finish, so a
    killed sweep loses nothing and ``resume=True`` runs only the cases not finished (``fresh``
    discards what is there). Without ``out`` the files go to a temporary folder.

    ``progress(done, total)`` is called as batches finish (default: a line on a terminal).

    Ctrl-C (or a notebook's interrupt) starts no more cases. In this process the cases running
    finish and are stored, then ``KeyboardInterrupt`` is raised; with an executor it is raised
    at once and the batches not started are cancelled. Either way ``resume=True`` runs the rest.
    """
    if resume and fresh:
        raise _option("resume", "give resume or fresh, not both")
    if (resume or fresh) and out is None:
        raise _option("resume" if resume else "fresh", "it concerns a folder: give out=")
    if threads is not None and executor is not None:
        raise _option("threads", "the executor's workers run the cases: leave threads out, or "
                      "the executor (threads are for a sweep in this process)")
    if batch_size is not None and batch_size < 1:
        raise _option("batch_size", f"{batch_size}: give at least 1 case per task")
    path = str(Path(spec).resolve())
    if out is None:
        with tempfile.TemporaryDirectory(prefix="pirqa-sweep-") as tmp:
            return _sweep(path, executor, Path(tmp), "fresh", batch_size, threads, progress)
    existing = "resume" if resume else "fresh" if fresh else "refuse"
    return _sweep(path, executor, Path(out), existing, batch_size, threads, progress)


def _option(name: str, rule: str):
    from .errors import OptionError

    return OptionError(f"{name}: {rule}")


def _sweep(path, executor, out, existing, batch_size, threads, progress):
    store = _pirqa.SweepStore(str(out), path, existing)
    pending = store.pending()
    info = _pirqa.sweep_info(path)
    total = info["cases"]
    report = _report(progress, total)
    done = total - len(pending)
    if executor is None:
        store.run(pending, threads)
        report(total, total)
    else:
        size = batch_size or auto_batch_size(len(pending), info["max_blocks"])
        batches = [pending[k:k + size] for k in range(0, len(pending), size)]
        futures = {
            executor.submit(_run_batch, path, store.fingerprint, ids): len(ids) for ids in batches
        }
        remaining = set(futures)
        try:
            while remaining:
                finished, remaining = wait(remaining, return_when=FIRST_EXCEPTION)
                for f in finished:
                    if f.exception() is not None:
                        raise f.exception()
                    store.append(f.result())
                    done += futures[f]
                    report(done, total)
        except BaseException:
            for other in remaining:
                other.cancel()
            raise
    store.finish()
    return read_sweep(out)
