"""pirqa: how dry-stone block walls slide, rock, collide and fail in earthquakes, computed
exactly (every stick-slip transition and impact found to round-off, no time step).

A first run, the paper's five-block wall under a record given as a numpy array::

    import numpy as np, pirqa
    wall = pirqa.Wall.from_file("walls/five-block-variable.ron")
    t = np.arange(0, 20, 0.01)
    motion = pirqa.Motion.from_array(4.0 * np.sin(2 * np.pi * t), dt_s=0.01)
    result = pirqa.run(wall, motion, output_dt_s=0.01)
    print(result.summary["blocks"][0]["max_abs_displacement_m"])

Sweeps over many walls, motions and friction samples run on any
``concurrent.futures.Executor`` (Dask, mpi4py, a process pool; Ray through
``pirqa.executors.RayExecutor``): see ``pirqa.sweep`` and docs/python.md.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from collections.abc import Mapping
from typing import Any

import numpy as np

from . import errors
from ._pirqa import Motion, Wall, __version__
from ._pirqa import run as _run
from ._sweep import read_sweep, residual, sweep
from .errors import (
    FileError,
    MotionError,
    OptionError,
    PirqaError,
    ResultsError,
    SimulationError,
    SweepError,
    WallError,
)


@dataclass(frozen=True)
class History:
    """The state of every block at each output time: arrays of shape (times, blocks).
    For blocks that rotate, ``rotation_rad`` (clockwise positive), ``angular_velocity_rad_s``
    and ``lift_m``, the vertical displacement of the middle of each block's base."""

    time_s: np.ndarray
    displacement_m: np.ndarray
    velocity_m_s: np.ndarray
    blocks: list[str]
    rotation_rad: np.ndarray | None = None
    angular_velocity_rad_s: np.ndarray | None = None
    lift_m: np.ndarray | None = None


@dataclass(frozen=True)
class Result:
    """What a run returns: ``summary`` is summary.json as a dict, ``history`` the sampled
    motion (when ``output_dt_s`` was given), ``events`` the event log (when ``log_events``)."""

    summary: dict[str, Any]
    history: History | None = None
    events: list[dict[str, Any]] = field(default_factory=list)


def run(
    wall: Wall,
    motion: Motion,
    *,
    duration_s: float | None = None,
    output_dt_s: float | None = None,
    method: str = "event",
    dt_s: float | None = None,
    model: str = "auto",
    contact_solver: str = "gauss-seidel",
    direction: str = "in-plane",
    initial_rotation: Mapping[str, float] | None = None,
    log_events: bool = False,
    check_uplift: bool = False,
    after_uplift: str = "slide",
    after_stop: str = "end",
) -> Result:
    """Runs ``wall`` under ``motion`` (the GIL is released while it runs).

    ``duration_s``: simulated time (default: the motion's length). ``output_dt_s``: sample the
    history this often (default: no history). ``method``: "event" (exact), "moreau" or
    "paper" (time stepping, with ``dt_s``). ``model``: "auto", "slide" or "slide-rock".
    ``contact_solver``: how "moreau" with model "slide-rock" solves each step's contacts,
    "gauss-seidel" (rigid contacts) or "newton" (the whole wall at once, stiff contacts: many
    times faster on tall walls; docs/rocking-walls.md). ``direction``: "in-plane" or
    "out-of-plane" (the part above each bed joint rocks across the wall as one body).
    ``initial_rotation``: blocks (or sections across the plane) started from rest at a rotation,
    ``{"B17": 0.1}`` in rad (positive: on the right corner, or towards the back face), as
    ``pirqa run --initial-rotation``; on still ground give ``Motion.rest()`` and ``duration_s``.
    ``check_uplift``: watch the exact sliding run for the first instant at which no contact
    forces keep every block seated (``summary["uplift_check"]``), as ``pirqa run
    --check-uplift``. ``after_uplift``: what follows that instant on a wall the sliding model
    runs, "slide" (slide on), "moreau" (exact sliding up to it, then Moreau-Jean with every
    block's rotation, step ``dt_s``) or "moreau-while-rocking" (the same until every block is
    seated and calm again, then exact sliding again, to the next uplift), as ``pirqa run
    --after-uplift``. ``after_stop``: what follows where the exact rocking model stops following
    a wall of columns or a trilith before the end (a held joint gives way, a body would fly),
    "end" (the run ends there, its warning says why) or "moreau" (Moreau-Jean with every
    block's rotation, step ``dt_s``, from every block's state there), as ``pirqa run
    --after-stop``.

    Ctrl-C (or a notebook's interrupt) stops the run within about 50 ms of wall-clock time and
    raises ``KeyboardInterrupt``; what the run reached is the exception's ``result``, its
    summary's ``interrupted_at_s`` saying where it stopped, as ``pirqa run`` writes it.
    """
    try:
        raw = _run(
            wall,
            motion,
            duration_s=duration_s,
            output_dt_s=output_dt_s,
            method=method,
            dt_s=dt_s,
            model=model,
            contact_solver=contact_solver,
            direction=direction,
            initial_rotation=None if initial_rotation is None else dict(initial_rotation),
            log_events=log_events,
            check_uplift=check_uplift,
            after_uplift=after_uplift,
            after_stop=after_stop,
        )
    except BaseException as signal:
        partial = getattr(signal, "partial", None)
        if partial is not None:
            signal.result = _result(partial)
            del signal.partial
        raise
    return _result(raw)


def _result(raw: dict[str, Any]) -> Result:
    history = None
    if raw["history"] is not None:
        history = History(blocks=raw["blocks"], **raw["history"])
    return Result(summary=raw["summary"], history=history, events=raw["events"])


__all__ = [
    "Wall",
    "Motion",
    "run",
    "Result",
    "History",
    "sweep",
    "read_sweep",
    "residual",
    "errors",
    "PirqaError",
    "WallError",
    "MotionError",
    "SweepError",
    "OptionError",
    "SimulationError",
    "FileError",
    "ResultsError",
    "__version__",
]
