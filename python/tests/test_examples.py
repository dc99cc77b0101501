"""The examples docs/python.md shows run as written: the first run, and the fragility study on a
Dask cluster drawn with matplotlib (on a smaller sweep of the same kind)."""

from __future__ import annotations

import subprocess
import sys

import pirqa
from conftest import ROOT


def run(*args: str) -> str:
    p = subprocess.run([sys.executable, *args], capture_output=True, text=True, cwd=ROOT)
    assert p.returncode == 0, p.stderr
    return p.stdout


def test_the_first_run_prints_the_blocks_and_a_closed_energy_balance():
    out = run("docs/python/first_run.py")
    assert out.count("max |u| =") == 5
    assert "history:" in out and "El Centro at 1500 gal:" in out


def test_the_fragility_example_draws_its_curve_on_dask(tmp_path):
    record = ROOT / "records/elcentro1940_IELC180_peer_dt0p01_g.AT2"
    spec = tmp_path / "fragility.ron"
    spec.write_text(
        f"""(
    version: 1,
    name: "small fragility",
    walls: [File(path: "{ROOT / 'walls/five-block-variable.ron'}")],
    motion: Records(files: ["{record}"], pga: ["1000gal", "2000gal", "3000gal"]),
    friction: Random(distribution: Lognormal, cov: 0.2, samples: 24, seed: 7),
)
"""
    )
    out = tmp_path / "out"
    printed = run("docs/python/fragility_dask.py", str(spec), str(out))
    png = out / "fragility-matplotlib.png"
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "median collapse PGA" in printed, printed
    # The example's table is the sweep's own.
    assert len(pirqa.read_sweep(out)) == 72
