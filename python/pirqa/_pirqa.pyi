"""Type stubs of the extension module (the Rust half of pirqa)."""

from os import PathLike
from typing import Any, Sequence

import numpy as np
import numpy.typing as npt

__version__: str

class Wall:
    @staticmethod
    def from_file(path: str | PathLike[str]) -> Wall: ...
    @staticmethod
    def from_ron(text: str, name: str | None = None) -> Wall: ...
    @staticmethod
    def from_rectangles(
        x_m: Sequence[float] | npt.ArrayLike,
        y_m: Sequence[float] | npt.ArrayLike,
        width_m: Sequence[float] | npt.ArrayLike,
        height_m: Sequence[float] | npt.ArrayLike,
        *,
        thickness_m: float,
        friction: float,
        density_kg_m3: float,
        names: Sequence[str] | None = None,
        fixed: Sequence[bool] | None = None,
        restitution: float = 1.0,
        g_m_s2: float = 9.81,
        joint_friction: dict[str, float] | None = None,
        name: str | None = None,
    ) -> Wall: ...
    @property
    def name(self) -> str: ...
    @property
    def blocks(self) -> list[str]: ...
    @property
    def ron(self) -> str: ...
    def limit_at_rest(
        self,
        *,
        displacement_m: npt.ArrayLike | None = None,
        fallen: Sequence[bool] | None = None,
    ) -> dict[str, Any]: ...
    def __len__(self) -> int: ...

class Motion:
    @staticmethod
    def from_array(
        accel_m_s2: npt.ArrayLike, *, dt_s: float, units: str = "m/s2", name: str = "array"
    ) -> Motion: ...
    @staticmethod
    def from_file(
        path: str | PathLike[str],
        *,
        scale: float | None = None,
        pga: str | None = None,
        dt_s: float | None = None,
        units: str | None = None,
        format: str | None = None,
    ) -> Motion: ...
    @staticmethod
    def sine(
        amplitude: str, *, frequency_hz: float, duration_s: float, phase_deg: float = 0.0
    ) -> Motion: ...
    @staticmethod
    def rest() -> Motion: ...
    @property
    def duration_s(self) -> float: ...
    @property
    def pga_m_s2(self) -> float: ...
    @property
    def dt_s(self) -> float | None: ...
    @property
    def accel_m_s2(self) -> np.ndarray | None: ...

class SweepStore:
    def __init__(self, out: str | PathLike[str], path: str | PathLike[str], existing: str) -> None: ...
    @property
    def fingerprint(self) -> str: ...
    def pending(self) -> list[int]: ...
    def append(self, batch: tuple[str, str, str]) -> None: ...
    def run(self, ids: list[int], threads: int | None = None) -> None: ...
    def finish(self) -> str: ...

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
    initial_rotation: dict[str, float] | None = None,
    log_events: bool = False,
    check_uplift: bool = False,
) -> dict[str, Any]: ...
def sweep_info(path: str | PathLike[str]) -> dict[str, Any]: ...
def sweep_residual(path: str | PathLike[str], out: str | PathLike[str]) -> None: ...
def run_batch(path: str | PathLike[str], fingerprint: str, ids: list[int]) -> tuple[str, str, str]: ...
def _time_runs(wall: Wall, motion: Motion, repeats: int) -> list[float]: ...
