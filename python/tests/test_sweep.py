"""Sweeps from Python on real engines: Dask (a LocalCluster of two worker processes), the
standard library's process pool, MPI and Ray when present; their results equal the serial run
and the command line's, byte for byte, whatever the engine, batch size, threads or shards, and
a killed sweep resumes to the same files."""

from __future__ import annotations

import os
import shutil
import signal
import subprocess
import sys
import threading
import _thread
from concurrent.futures import ProcessPoolExecutor

import pytest

import pirqa
from conftest import same_files, write_sweep


@pytest.fixture(scope="module")
def spec(tmp_path_factory):
    return write_sweep(tmp_path_factory.mktemp("spec"))


@pytest.fixture(scope="module")
def serial(spec, tmp_path_factory):
    """The sweep run in this process on one thread: (its folder, its DataFrame)."""
    out = tmp_path_factory.mktemp("serial") / "out"
    return out, pirqa.sweep(spec, out=out, threads=1)


def test_the_serial_sweep_is_the_command_lines(spec, serial, cli, tmp_path):
    """pirqa.sweep writes the files `pirqa sweep` writes, and its DataFrame is cases.csv."""
    out, frame = serial
    code, err = cli("sweep", str(spec), "--out", str(tmp_path / "cli"))
    assert code == 0, err
    assert same_files(tmp_path / "cli", out) >= 6
    assert frame.equals(pirqa.read_sweep(tmp_path / "cli"))
    assert len(frame) == 60 and frame.index.name == "case" and list(frame.index) == list(range(60))
    assert "cpu_s" not in frame.columns
    # Every number as written, to the bit.
    import csv

    with open(out / "cases.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    for column in ("max_abs_u_m", "energy_input_j", "energy_residual_j", "residual_u_m"):
        written = [float(r[column]) for r in rows]
        assert frame[column].tolist() == written, column


def test_threads_do_not_change_a_number(spec, serial, tmp_path):
    out, frame = serial
    two = pirqa.sweep(spec, out=tmp_path / "two", threads=2)
    assert two.equals(frame)
    assert same_files(out, tmp_path / "two") >= 6


def test_a_dask_cluster_of_two_worker_processes_gives_the_serial_results(spec, serial, tmp_path):
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1",
        dashboard_address=None,
    ) as cluster, distributed.Client(cluster) as client:
        with distributed.get_task_stream(client) as stream:
            frame = pirqa.sweep(spec, client.get_executor(), out=tmp_path / "dask", batch_size=5)
        workers = {task["worker"] for task in stream.data}
        pids = set(client.run(os.getpid).values())
    assert len(workers) >= 2, f"tasks ran on {workers}"
    assert len(pids) == 2 and os.getpid() not in pids
    assert frame.equals(serial[1])
    assert same_files(serial[0], tmp_path / "dask") >= 6


@pytest.mark.parametrize("batch_size", [1, 7, None, 1000])
def test_a_process_pool_gives_the_serial_results_at_any_batch_size(spec, serial, batch_size):
    with ProcessPoolExecutor(max_workers=2) as pool:
        frame = pirqa.sweep(spec, pool, batch_size=batch_size)
    assert frame.equals(serial[1])


def test_three_shards_merged_are_the_serial_run(spec, serial, cli, tmp_path):
    out = tmp_path / "sharded"
    for part in range(3):
        code, err = cli("sweep", str(spec), "--shard", f"{part}/3", "--out", str(out))
        assert code == 0, err
    code, err = cli("sweep", "merge", str(out))
    assert code == 0, err
    assert same_files(serial[0], out) >= 6


KILLED = """
import os, signal, sys
from concurrent.futures import ProcessPoolExecutor
import pirqa
batches = 0
def progress(done, total):
    global batches
    batches += 1
    if batches == int(sys.argv[3]):
        os.kill(os.getpid(), signal.SIGKILL)
with ProcessPoolExecutor(max_workers=2) as pool:
    pirqa.sweep(sys.argv[1], pool, out=sys.argv[2], batch_size=4, progress=progress,
                resume=len(sys.argv) > 4)
"""


def test_a_killed_sweep_resumes_to_the_uninterrupted_files(spec, serial, tmp_path):
    """SIGKILL after 3 batches were stored, again after 2 more on resuming, then a resumption
    to the end: the files of the uninterrupted sweep."""
    out = tmp_path / "killed"
    script = tmp_path / "killed.py"
    script.write_text(KILLED)

    def run(*args: str) -> subprocess.Popen:
        # In a process group of its own, whose pool workers, orphaned by the kill, go with it
        # (as a batch system ends a job's processes), instead of outliving the tests.
        p = subprocess.Popen([sys.executable, str(script), str(spec), str(out), *args],
                             start_new_session=True)
        p.wait()
        try:
            os.killpg(p.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        return p

    assert run("3").returncode == -signal.SIGKILL
    stored = (out / "cases.csv").read_text().count("\n") - 1
    assert 12 <= stored < 60, stored
    assert run("2", "resume").returncode == -signal.SIGKILL
    frame = pirqa.sweep(spec, out=out, resume=True)
    assert frame.equals(serial[1])
    assert same_files(serial[0], out) >= 6


def test_an_interrupted_sweep_stores_the_cases_it_ran_and_resumes_to_the_same_files(
    tmp_path, interruptible
):
    """An interrupt (what Ctrl-C or a notebook's "interrupt the kernel" sends) during a sweep in
    this process, of cases about a tenth of a second each: KeyboardInterrupt after the case
    running is stored, no more started; a resumption ends with the uninterrupted files."""
    spec = write_sweep(tmp_path / "spec", samples=10, duration_s=2000.0)
    out = tmp_path / "interrupted"
    timer = threading.Timer(0.5, _thread.interrupt_main)
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            pirqa.sweep(spec, out=out, threads=1)
    finally:
        timer.cancel()
    stored = (out / "cases.csv").read_text().count("\n") - 1
    assert 1 <= stored < 40, stored
    frame = pirqa.sweep(spec, out=out, resume=True)
    assert frame.equals(pirqa.sweep(spec, out=tmp_path / "whole", threads=2))
    assert same_files(tmp_path / "whole", out) >= 6


def test_an_existing_folder_is_refused_and_bad_options_named(spec, serial):
    with pytest.raises(pirqa.ResultsError, match="--resume"):
        pirqa.sweep(spec, out=serial[0])
    with pytest.raises(pirqa.OptionError, match="batch_size"):
        pirqa.sweep(spec, batch_size=0)
    with pytest.raises(pirqa.OptionError, match="give out="):
        pirqa.sweep(spec, resume=True)
    with pytest.raises(pirqa.OptionError, match="threads"):
        with ProcessPoolExecutor(max_workers=1) as pool:
            pirqa.sweep(spec, pool, threads=2)
    with pytest.raises(pirqa.SweepError, match="line 1"):
        bad = serial[0].parent / "bad.ron"
        bad.write_text("(version: 1, name: 3)")
        pirqa.sweep(bad)


MPI_SWEEP = """
import sys
from mpi4py.futures import MPIPoolExecutor
import pirqa
if __name__ == "__main__":
    with MPIPoolExecutor() as pool:
        pirqa.sweep(sys.argv[1], pool, out=sys.argv[2])
"""


def test_an_mpi_pool_gives_the_serial_results(spec, serial, tmp_path):
    """Three MPI processes started by mpiexec (mpi4py.futures: one runs the sweep, two serve as
    its workers), as on a cluster."""
    pytest.importorskip("mpi4py.futures", reason="mpi4py is not installed")
    mpiexec = shutil.which("mpiexec")
    if mpiexec is None:
        pytest.skip("mpiexec is not on the PATH")
    script = tmp_path / "mpi_sweep.py"
    script.write_text(MPI_SWEEP)
    # Open MPI refuses root and more processes than cores unless told; others ignore these.
    env = {**os.environ, "OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1",
           "OMPI_MCA_rmaps_base_oversubscribe": "1"}
    out = tmp_path / "mpi"
    p = subprocess.run(
        [mpiexec, "-n", "3", sys.executable, "-m", "mpi4py.futures", str(script), str(spec),
         str(out)], env=env, capture_output=True, text=True, timeout=600,
    )
    assert p.returncode == 0, p.stderr
    assert same_files(serial[0], out) >= 6


def test_ray_gives_the_serial_results(spec, serial):
    ray = pytest.importorskip("ray", reason="ray is not installed")
    from pirqa.executors import RayExecutor

    ray.init(num_cpus=2, include_dashboard=False)
    try:
        assert pirqa.sweep(spec, RayExecutor()).equals(serial[1])
    finally:
        ray.shutdown()


def test_the_residual_limits_are_the_command_lines(spec, serial, cli, tmp_path):
    """pirqa.residual writes what `pirqa sweep --residual` writes into a copy of the same
    finished sweep, and returns residual.csv with its exact limits as text."""
    out, _ = serial
    ours, theirs = tmp_path / "python", tmp_path / "cli"
    shutil.copytree(out, ours)
    shutil.copytree(out, theirs)
    frame = pirqa.residual(spec, ours)
    code, err = cli("sweep", str(spec), "--out", str(theirs), "--residual")
    assert code == 0, err
    for name in ("residual.csv", "capacity-left.csv", "capacity-left.svg"):
        assert (ours / name).read_bytes() == (theirs / name).read_bytes(), name
    assert len(frame) == 60 and frame.index.name == "case"
    built = frame["as_built_plus_x_g"].notna()
    assert built.all() and frame["plus_x_exact_g"].map(type).eq(str).all()
    with pytest.raises(pirqa.PirqaError, match="manifest.json"):
        pirqa.residual(spec, tmp_path / "nothing")
