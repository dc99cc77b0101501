"""Shared fixtures: the repository's root (walls/, records/), the command-line binary the Rust
test suite built (PIRQA_BIN), and small sweep files written for a test."""

from __future__ import annotations

import os
import signal
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def root() -> Path:
    return ROOT


@pytest.fixture
def interruptible():
    """Python's own SIGINT handler (KeyboardInterrupt) for the test, whatever the process was
    started with: a shell starts background jobs with SIGINT ignored, and then
    `_thread.interrupt_main` (the tests' Ctrl-C) does nothing and the test would fail for the
    launcher's sake, not pirqa's."""
    before = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, before)


@pytest.fixture(scope="session")
def cli():
    """Runs the command line (``pirqa ARGS``) and returns (exit code, stderr)."""
    binary = os.environ.get("PIRQA_BIN")
    if not binary:
        pytest.fail("PIRQA_BIN is not set: run the Python tests through `cargo test` (README)")

    def run(*args: str, env: dict[str, str] | None = None) -> tuple[int, str]:
        p = subprocess.run(
            [binary, *args], capture_output=True, text=True, env={**os.environ, **(env or {})}
        )
        return p.returncode, p.stderr

    return run


def write_sweep(folder: Path, *, samples: int = 15, seed: int = 7, duration_s: float = 5.0) -> Path:
    """A friction Monte Carlo on the paper's wall under sines of ``duration_s``: 4 motions x
    ``samples`` cases."""
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / f"mc-{seed}.ron"
    path.write_text(
        f"""(
    version: 1,
    name: "python sweep",
    walls: [File(path: "{ROOT / 'walls/five-block-variable.ron'}")],
    motion: Sine(amplitudes: ["300gal", "500gal"], frequencies_hz: List([1.0, 2.0]), duration_s: {duration_s}),
    friction: Random(distribution: Lognormal, cov: 0.2, samples: {samples}, seed: {seed}),
)
"""
    )
    return path


def same_files(expected: Path, found: Path) -> int:
    """Asserts that two sweep folders hold the same result files byte for byte (all but
    timing.csv, a measurement, and parts/); returns how many were compared."""
    names = lambda d: {p.name for p in d.iterdir()} - {"timing.csv", "parts"}
    assert names(expected) == names(found)
    for name in sorted(names(expected)):
        assert (expected / name).read_bytes() == (found / name).read_bytes(), name
    return len(names(expected))
