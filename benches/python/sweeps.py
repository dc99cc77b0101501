"""What the Python layer costs (docs/performance.md, "Python"): one process, alternating rounds,
medians. Needs the package built with --release (`pip install ./python`), Dask, matplotlib, and
the command line's release build (`cargo build --release`).

    python benches/python/sweeps.py [ROUNDS] [--overhead-only]

1. The call overhead of `pirqa.run` on the paper's variable wall, 400 gal, 1 Hz sine, 20 s: the
   Python call (its summary read) against the Rust library's own time for the same run
   (`_time_runs`, no Python in the loop), one of each in turn, 400 pairs per round.
2. The 10,000-case Monte Carlo (mc-10000.ron) on a 2-worker Dask LocalCluster against the
   command line's rayon sweep on the same 2 cores (wall-clock, output into a fresh folder each
   time; the cluster is started before the clock).
3. Throughput (cases per second) on that cluster against the batch size, on the first 2,000 of
   those cases' kind (the same sweep with 2,000 samples): docs/python/throughput-batch.csv and
   .svg.
"""

from __future__ import annotations

import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import pirqa
from pirqa import _pirqa

ROOT = Path(__file__).resolve().parents[2]
ROUNDS = int(sys.argv[1]) if len(sys.argv) > 1 and sys.argv[1].isdigit() else 5
CLI = ROOT / "target/release/pirqa"
MC = ROOT / "benches/python/mc-10000.ron"


def overhead():
    wall = pirqa.Wall.from_file(ROOT / "walls/five-block-variable.ron")
    sine = pirqa.Motion.sine("400gal", frequency_hz=1.0, duration_s=20.0)
    # One run of each in turn, so that the machine's drift falls on both alike.
    rust, python = [], []
    for _ in range(400 * ROUNDS):
        rust.extend(_pirqa._time_runs(wall, sine, 1))
        start = time.perf_counter()
        result = pirqa.run(wall, sine)
        result.summary["blocks"][0]["max_abs_displacement_m"]
        python.append(time.perf_counter() - start)
    r, p = statistics.median(rust), statistics.median(python)
    print(f"| call overhead | Rust library {r * 1e3:.3f} ms per run | pirqa.run {p * 1e3:.3f} ms "
          f"| +{100 * (p - r) / r:.1f} % |")


def two_cores():
    from dask.distributed import Client, LocalCluster

    small = Path(tempfile.mkdtemp()) / "mc-2000.ron"
    small.write_text(MC.read_text().replace("samples: 10000", "samples: 2000")
                     .replace("../../walls/", str(ROOT / "walls") + "/"))
    with LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=None) as cluster, \
            Client(cluster) as client:
        executor = client.get_executor()
        pirqa.sweep(small, executor, batch_size=100)  # workers warmed: imports, first loads
        cli, dask = [], []
        for _ in range(ROUNDS):
            with tempfile.TemporaryDirectory() as out:
                start = time.perf_counter()
                subprocess.run([CLI, "sweep", MC, "--out", out, "--threads", "2"], check=True,
                               capture_output=True)
                cli.append(time.perf_counter() - start)
            start = time.perf_counter()
            pirqa.sweep(MC, executor)
            dask.append(time.perf_counter() - start)
        c, d = statistics.median(cli), statistics.median(dask)
        print(f"| 10,000 cases, 2 cores | pirqa sweep (rayon) {c:.2f} s | pirqa.sweep on Dask "
              f"{d:.2f} s | {100 * (d - c) / c:+.1f} % |")
        rows = []
        for size in [1, 2, 5, 10, 20, 50, 100, 200, 500, 1000]:
            times = []
            for _ in range(max(1, ROUNDS // 2)):
                start = time.perf_counter()
                pirqa.sweep(small, executor, batch_size=size)
                times.append(time.perf_counter() - start)
            rows.append((size, 2000 / statistics.median(times)))
            print(f"  batch {size}: {rows[-1][1]:.0f} cases/s")
    auto = pirqa._sweep.auto_batch_size(2000, 5)
    return rows, auto


def chart(rows, auto):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out = ROOT / "docs/python"
    with open(out / "throughput-batch.csv", "w") as f:
        f.write("batch_size,cases_per_s\n")
        for size, rate in rows:
            f.write(f"{size},{rate:.1f}\n")
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.semilogx([r[0] for r in rows], [r[1] for r in rows], "o-")
    ax.axvline(auto, linestyle="--", color="grey", label=f"auto batch for these cases ({auto})")
    ax.set_xlabel("cases per task")
    ax.set_ylabel("cases per second (2 Dask workers)")
    ax.set_title("Paper's wall, 20 s sine, 2,000 cases")
    ax.legend()
    fig.tight_layout()
    fig.savefig(out / "throughput-batch.svg")


if __name__ == "__main__":
    print("| what | reference | Python | difference |\n|---|---|---|---|")
    overhead()
    if "--overhead-only" in sys.argv:
        sys.exit()
    rows, auto = two_cores()
    chart(rows, auto)
