"""The Python API against the command line and against itself: the same numbers as `pirqa run`,
walls from files, RON and arrays alike, results that pickle, errors whose messages are the
command line's, histories handed over without a copy, the GIL released while a run goes, and
an interrupt heard during one."""

from __future__ import annotations

import json
import pickle
import sys
import threading
import time
import _thread

import numpy as np
import pytest

import pirqa

PAPER = "walls/five-block-variable.ron"


def test_the_papers_wall_from_a_numpy_record_equals_the_command_line(root, cli, tmp_path):
    """A record given as a numpy array and the same samples given to `pirqa run --record` as a
    file: the same summary.json, every number to the bit."""
    dt = 0.01
    t = np.arange(0, 10 + dt / 2, dt)
    accel_gal = 400.0 * np.sin(2 * np.pi * t) * np.exp(-0.1 * t)
    record = tmp_path / "record.txt"
    record.write_text("# dt_s: 0.01\n# units: gal\n" + "".join(f"{float(a)!r}\n" for a in accel_gal))
    out = tmp_path / "out"
    code, err = cli("run", str(root / PAPER), "--record", str(record), "--out", str(out))
    assert code == 0, err
    expected = json.loads((out / "summary.json").read_text())
    wall = pirqa.Wall.from_file(root / PAPER)
    motion = pirqa.Motion.from_array(accel_gal, dt_s=dt, units="gal", name="record")
    found = pirqa.run(wall, motion).summary
    expected["motion"] = found["motion"]  # the name of the record: its file's, or ours
    assert found == expected
    energy = found["energy"]
    assert abs(energy["residual_j"]) < 1e-9 * energy["input_j"]


def test_a_sine_equals_the_command_line(root, cli, tmp_path):
    out = tmp_path / "out"
    code, err = cli(
        "run", str(root / PAPER), "--sine", "400gal", "--freq", "1", "--duration", "20",
        "--out", str(out),
    )
    assert code == 0, err
    wall = pirqa.Wall.from_file(root / PAPER)
    sine = pirqa.Motion.sine("400gal", frequency_hz=1.0, duration_s=20.0)
    found = pirqa.run(wall, sine).summary
    expected = json.loads((out / "summary.json").read_text())
    # Equal, and in the same order, keys within keys (the dict is built from the same serde
    # description as the file, not parsed from it).
    assert found == expected and json.dumps(found) == json.dumps(expected)


def test_a_wall_from_arrays_of_rectangles_is_the_wall_from_its_file(root):
    """The paper's uniform wall as five rectangles runs to the same numbers as its file."""
    from_file = pirqa.Wall.from_file(root / "walls/five-block-uniform.ron")
    # walls/five-block-uniform.ron: courses of 0.6 m, blocks 1.2 + 1.2 below, 0.6 + 1.2 + 0.6
    # above, 0.8 m thick, 2650 kg/m3, friction 0.30.
    rectangles = pirqa.Wall.from_rectangles(
        np.array([0.0, 1.2, 0.0, 0.6, 1.8]),
        np.array([0.0, 0.0, 0.6, 0.6, 0.6]),
        np.array([1.2, 1.2, 0.6, 1.2, 0.6]),
        np.full(5, 0.6),
        thickness_m=0.8,
        friction=0.30,
        density_kg_m3=2650.0,
        name=from_file.name,
    )
    assert rectangles.blocks == from_file.blocks
    sine = pirqa.Motion.sine("400gal", frequency_hz=1.0, duration_s=10.0)
    a, b = pirqa.run(from_file, sine).summary, pirqa.run(rectangles, sine).summary
    assert a["blocks"] == b["blocks"] and a["energy"] == b["energy"]


def test_walls_motions_and_results_pickle_to_the_same_numbers(root):
    wall = pirqa.Wall.from_file(root / PAPER)
    t = np.arange(0, 5.0, 0.005)
    motions = [
        pirqa.Motion.from_array(0.41 * np.sin(3.0 * t), dt_s=0.005, units="g"),
        pirqa.Motion.sine("0.4g", frequency_hz=1.3, duration_s=5.0, phase_deg=33.0),
    ]
    for motion in motions:
        result = pirqa.run(wall, motion, output_dt_s=0.05)
        wall2, motion2 = pickle.loads(pickle.dumps((wall, motion)))
        assert wall2.ron == wall.ron and wall2.name == wall.name
        again = pirqa.run(wall2, motion2, output_dt_s=0.05)
        assert again.summary == result.summary
        np.testing.assert_array_equal(again.history.displacement_m, result.history.displacement_m)
        back = pickle.loads(pickle.dumps(result))
        assert back.summary == result.summary
        np.testing.assert_array_equal(back.history.time_s, result.history.time_s)


def test_a_history_is_handed_over_without_a_copy(root):
    """The arrays' memory is Rust's (a capsule owns it), not a copy numpy made; their shape is
    (times, blocks) and their values what summary.json reports."""
    wall = pirqa.Wall.from_file(root / PAPER)
    r = pirqa.run(wall, pirqa.Motion.sine("400gal", frequency_hz=1.0, duration_s=20.0),
                  output_dt_s=0.01, log_events=True)
    h = r.history
    for a in (h.time_s, h.displacement_m, h.velocity_m_s):
        assert a.dtype == np.float64 and not a.flags["OWNDATA"]
        assert a.base is not None and not isinstance(a.base, np.ndarray)
    assert h.displacement_m.shape == (len(h.time_s), 5) and h.blocks == wall.blocks
    peak = np.abs(h.displacement_m).max(axis=0)
    for k, block in enumerate(r.summary["blocks"]):
        assert peak[k] <= block["max_abs_displacement_m"] + 1e-15
    assert r.events and {"time_s", "kind", "blocks"} <= set(r.events[0])


def test_the_uplift_check_says_when_a_block_would_start_to_turn(root):
    """As ``pirqa run --check-uplift``: the Ollantaytambo wall under a 1 Hz sine of 0.3 g leaves
    rest where its limit at rest says, an end filler turning, by a mechanism decided the only one
    as the limit's is; unasked, no check is reported."""
    wall = pirqa.Wall.from_file(root / "walls/inca/ollantaytambo-monoliths.ron")
    motion = pirqa.Motion.sine("0.3g", frequency_hz=1.0, duration_s=1.0)
    r = pirqa.run(wall, motion, model="slide", check_uplift=True)
    first = r.summary["uplift_check"]["first_uplift"]
    limit = wall.limit_at_rest()["towards_plus_x"]["accel_m_s2"]
    assert abs(first["ground_accel_m_s2"] - limit) <= 1e-12 * limit
    assert first["turning"] == ["F1 turns counterclockwise about its bottom-left corner"]
    assert first["mechanism_uniqueness"] == wall.limit_at_rest()["towards_plus_x"][
        "mechanism_uniqueness"
    ]
    assert first["turning_in_every_mechanism"] == ["F1"]
    assert "uplift_check" not in pirqa.run(wall, motion, model="slide").summary


def test_after_the_first_uplift_moreau_jean_takes_over():
    """A slender block beside a squat one under a ground acceleration rising at 2 m/s3 lifts
    at g b/h = g/4, t = 1.22625 s: exact sliding to there, then every block with its rotation,
    in one history; the step is the stepping's, and asked for."""
    wall = pirqa.Wall.from_ron(
        """(version: 1, thickness_m: 0.5, density_kg_m3: 2500, friction: 0.6, rows: [
            (height_m: 1.2, blocks: [(width_m: 0.3, name: "S"), (width_m: 1.2, name: "W")])])"""
    )
    ramp = pirqa.Motion.from_array(2.0 * 0.01 * np.arange(301), dt_s=0.01)
    r = pirqa.run(wall, ramp, duration_s=2.0, output_dt_s=0.01, after_uplift="moreau", dt_s=1e-3)
    s = r.summary
    assert s["method"] == "event+moreau"
    assert abs(s["uplift_check"]["first_uplift"]["time_s"] - 9.81 / 8) <= 1e-12
    theta = r.history.rotation_rad
    before = r.history.time_s <= 9.81 / 8
    assert np.all(theta[before] == 0.0)
    assert abs(theta[-1, 0]) > 0.25 and abs(theta[-1, 1]) < 1e-6
    with pytest.raises(pirqa.OptionError, match="dt_s"):
        pirqa.run(wall, ramp, after_uplift="moreau")
    with pytest.raises(pirqa.OptionError, match="give slide, moreau or moreau-while-rocking"):
        pirqa.run(wall, ramp, after_uplift="rock", dt_s=1e-3)


def test_where_the_exact_rocking_model_stops_moreau_jean_goes_on(root):
    """The trilith under El Centro at 0.5 g: the exact model follows it until the lintel would
    slip on its left column (5.887 s), then every block steps with its rotation from there until
    the lintel slides off; the rows up to the stop are the exact run's own. The two-block column
    under a 0.4 g, 0.7 Hz sine stops where its upper drum would lift off the lower one's corner
    (2.36 s), leaning so far that the stepper counts it fallen there: the run ends at the stop."""
    trilith = pirqa.Wall.from_file(root / "walls/rocking/trilith.ron")
    record = pirqa.Motion.from_file(
        root / "records/elcentro1940_IELC180_peer_dt0p01_g.AT2", pga="0.5g"
    )
    exact = pirqa.run(trilith, record, output_dt_s=0.01)
    assert "stops there" in " ".join(exact.summary["warnings"])
    r = pirqa.run(trilith, record, output_dt_s=0.01, after_stop="moreau", dt_s=1e-4)
    s = r.summary
    assert s["method"] == "event+moreau"
    assert "the exact model to t = 5.887" in s["model"]["why"]
    assert not any("stops there" in w for w in s["warnings"])
    assert s["collapse"]["block"] == "Lintel"
    assert s["collapse"]["time_s"] > exact.summary["duration_s"]
    n = len(exact.history.time_s)
    assert len(r.history.time_s) > n
    assert np.array_equal(r.history.rotation_rad[:n], exact.history.rotation_rad)
    wall = pirqa.Wall.from_file(root / "walls/rocking/two-block-column.ron")
    sine = pirqa.Motion.sine("0.4g", frequency_hz=0.7, duration_s=4.0)
    exact = pirqa.run(wall, sine, output_dt_s=0.01)
    r = pirqa.run(wall, sine, output_dt_s=0.01, after_stop="moreau", dt_s=5e-4)
    assert "the exact model to t = 2.36" in r.summary["model"]["why"]
    assert r.summary["collapse"]["time_s"] == exact.summary["duration_s"]
    assert np.array_equal(r.history.rotation_rad, exact.history.rotation_rad)
    with pytest.raises(pirqa.OptionError, match="dt_s"):
        pirqa.run(wall, sine, after_stop="moreau")
    with pytest.raises(pirqa.OptionError, match="give end or moreau"):
        pirqa.run(wall, sine, after_stop="rock", dt_s=1e-3)


def test_while_blocks_rock_moreau_jean_steps_them_and_then_gives_the_wall_back():
    """The slender block under a pulse to 3.5 m/s2 and back: it lifts at g/4 on the way up,
    rocks, lands and settles; from there the exact sliding model has the wall again, every
    rotation zero, nothing moving on still ground."""
    wall = pirqa.Wall.from_ron(
        """(version: 1, thickness_m: 0.5, density_kg_m3: 2500, friction: 0.6, rows: [
            (height_m: 1.2, blocks: [(width_m: 0.3, name: "S"), (width_m: 1.2, name: "W")])])"""
    )
    rise = np.linspace(0.0, 3.5, 41)
    pulse = pirqa.Motion.from_array(np.concatenate([rise, rise[-2::-1], np.zeros(220)]), dt_s=0.01)
    r = pirqa.run(
        wall, pulse, duration_s=3.0, output_dt_s=0.01, after_uplift="moreau-while-rocking", dt_s=1e-3
    )
    s = r.summary
    assert s["method"] == "event+moreau"
    assert "stretches stepped (1)" in s["model"]["why"]
    assert s["stats"]["steps"] < 1500
    after = r.history.time_s >= 2.0
    assert np.all(r.history.rotation_rad[after] == 0.0)
    assert np.all(r.history.displacement_m[after] == r.history.displacement_m[-1])


def test_a_sliding_run_says_how_much_overlap_sliding_took_away():
    """A block bridging two abutments, pushed right at (3 - 0.2 g) m/s2 relative to them for
    0.5 s, leaves (3 - 0.2 g) 0.5^2 / 2 m of its 0.8 m on the left one: summary["max_overlap_loss"]
    to round-off, and the warning that names the joint; with rotations there is none."""
    wall = pirqa.Wall.from_ron(
        """(version: 1, thickness_m: 1, density_kg_m3: 2000, friction: 0.2, rectangles: [
            (x_m: 0, y_m: 0, width_m: 1, height_m: 0.5, fixed: true),
            (x_m: 1.2, y_m: 0, width_m: 1, height_m: 0.5, fixed: true),
            (x_m: 0.2, y_m: 0.5, width_m: 1.2, height_m: 0.5, name: "Top"),
        ])"""
    )
    push = pirqa.Motion.from_array(np.full(52, -3.0), dt_s=0.01)
    s = pirqa.run(wall, push, duration_s=0.5).summary
    assert abs(s["max_overlap_loss"] - (3 - 0.2 * 9.81) * 0.125 / 0.8) < 1e-15
    assert any(w.startswith("Top on B1: at u_Top - u_B1 = 0.129") for w in s["warnings"])
    turning = pirqa.run(wall, push, duration_s=0.5, model="slide-rock", method="moreau", dt_s=1e-3)
    assert "max_overlap_loss" not in turning.summary


def test_errors_are_classed_and_say_what_the_command_line_says(root, cli, tmp_path):
    bad = tmp_path / "floating.ron"
    bad.write_text(
        "(version: 1, thickness_m: 1.0, density_kg_m3: 2600.0, friction: 0.3,\n"
        " rectangles: [(x_m: 0.0, y_m: 0.5, width_m: 1.0, height_m: 0.5)])\n"
    )
    code, err = cli("check", str(bad))
    assert code == 1
    with pytest.raises(pirqa.WallError) as e:
        pirqa.Wall.from_file(bad)
    assert isinstance(e.value, ValueError) and isinstance(e.value, pirqa.PirqaError)
    assert err.strip() == f"error: {e.value}"
    assert "floating.ron" in str(e.value)
    with pytest.raises(pirqa.FileError) as e:
        pirqa.Wall.from_file(tmp_path / "missing.ron")
    assert isinstance(e.value, OSError)
    with pytest.raises(pirqa.MotionError, match="sample 3"):
        pirqa.Motion.from_array(np.array([0.0, 1.0, np.nan]), dt_s=0.01)
    with pytest.raises(pirqa.MotionError, match="gal, g, m/s2"):
        pirqa.Motion.sine("400", frequency_hz=1.0, duration_s=1.0)
    with pytest.raises(pirqa.OptionError, match="units"):
        pirqa.Motion.from_array([0.0, 1.0], dt_s=0.01, units="furlongs")
    with pytest.raises(pirqa.OptionError, match="dt_s"):
        pirqa.run(pirqa.Wall.from_file(root / PAPER),
                  pirqa.Motion.sine("1g", frequency_hz=1.0, duration_s=1.0), method="moreau")
    with pytest.raises(pirqa.OptionError, match="contact_solver"):
        pirqa.run(pirqa.Wall.from_file(root / PAPER),
                  pirqa.Motion.sine("1g", frequency_hz=1.0, duration_s=1.0), method="moreau",
                  dt_s=1e-3, model="slide-rock", contact_solver="jacobi")
    with pytest.raises(pirqa.SimulationError, match="leave --contact-solver out"):
        pirqa.run(pirqa.Wall.from_file(root / PAPER),
                  pirqa.Motion.sine("1g", frequency_hz=1.0, duration_s=1.0),
                  contact_solver="newton")
    with pytest.raises(pirqa.OptionError, match="y_m"):
        pirqa.Wall.from_rectangles([0.0], [0.0, 1.0], [1.0], [1.0], thickness_m=1.0,
                                   friction=0.3, density_kg_m3=2600.0)


def test_a_run_releases_the_gil(root):
    """While a long run goes on in a thread, this thread keeps running Python: its longest
    pause is a small part of the run (holding the GIL, the run would pause it throughout)."""
    wall = pirqa.Wall.from_file(root / PAPER)
    motion = pirqa.Motion.sine("400gal", frequency_hz=1.0, duration_s=5000.0)
    span = {}

    def go():
        span["start"] = time.perf_counter()
        pirqa.run(wall, motion)
        span["end"] = time.perf_counter()

    worker = threading.Thread(target=go)
    last, longest = time.perf_counter(), 0.0
    worker.start()
    while worker.is_alive():
        now = time.perf_counter()
        longest, last = max(longest, now - last), now
    worker.join()
    run_s = span["end"] - span["start"]
    assert longest < 0.5 * run_s, f"paused {longest:.4f} s during a run of {run_s:.4f} s"


def test_a_run_the_exact_model_stops_says_where(root):
    """Under El Centro at 0.6 g the upper drum of two-block-column.ron would lift off the corner
    of the lower one it turns on at 5.862 s, as the column falls and that corner slips, which
    the exact model does not follow: it stops following the wall there, and the run ends with its summary saying
    where and why; slender-on-stack.ron under 0.3 g runs to its end and says nothing of the
    kind."""
    wall = pirqa.Wall.from_file(root / "walls/rocking/two-block-column.ron")
    record = pirqa.Motion.from_file(
        root / "records/elcentro1940_IELC180_peer_dt0p01_g.AT2", pga="0.6g"
    )
    stopped = pirqa.run(wall, record).summary
    assert stopped["stopped_at_s"] == stopped["duration_s"]
    assert 5.861 < stopped["stopped_at_s"] < 5.862
    assert any("Drum2/Drum1 would lift off" in w for w in stopped["warnings"])
    wall = pirqa.Wall.from_file(root / "walls/rocking/slender-on-stack.ron")
    whole = pirqa.run(wall, pirqa.Motion.sine("0.3g", frequency_hz=1.5, duration_s=1.0)).summary
    assert whole.get("stopped_at_s") is None
    assert whole["duration_s"] == 1.0


def test_an_interrupt_stops_a_run_and_keeps_what_it_reached(root, interruptible):
    """An interrupt (what Ctrl-C or a notebook's "interrupt the kernel" sends) half a second into
    a run that would take half a minute: KeyboardInterrupt, carrying the run up to where it
    stopped, which is the same run made to end there."""
    wall = pirqa.Wall.from_file(root / PAPER)
    motion = pirqa.Motion.sine("400gal", frequency_hz=1.0, duration_s=1e6)
    timer = threading.Timer(0.5, _thread.interrupt_main)
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt) as stopped:
            pirqa.run(wall, motion)
    finally:
        timer.cancel()
    partial = stopped.value.result.summary
    t = partial["interrupted_at_s"]
    assert 0.0 < t < 1e6
    whole = pirqa.run(wall, motion, duration_s=t).summary
    assert whole.get("interrupted_at_s") is None
    assert [b["max_abs_displacement_m"] for b in partial["blocks"]] == [
        b["max_abs_displacement_m"] for b in whole["blocks"]
    ]


def test_an_interrupt_stops_the_limit_at_rest_inside_its_programs(cli, tmp_path, interruptible):
    """An interrupt a second into the limit at rest of a 976-block running bond (whose exact
    programs take many seconds): KeyboardInterrupt, raised from inside the call (the profiler
    sees the call end with an exception, not return and the signal handled after it)."""
    path = tmp_path / "bond.ron"
    code, err = cli("generate", "--blocks", "1000", "-o", str(path))
    assert code == 0, err
    wall = pirqa.Wall.from_file(path)
    ends = []

    def watch(frame, event, arg):
        if event in ("c_return", "c_exception") and getattr(arg, "__name__", "") == "limit_at_rest":
            ends.append(event)

    timer = threading.Timer(1.0, _thread.interrupt_main)
    timer.start()
    sys.setprofile(watch)
    try:
        with pytest.raises(KeyboardInterrupt):
            wall.limit_at_rest()
    finally:
        sys.setprofile(None)
        timer.cancel()
    assert ends == ["c_exception"]


def test_the_history_names_its_blocks_as_the_run_lists_them():
    """A wall of one column on an abutment rocks: the run lists every block of the wall in its
    order, as a sliding run does, the abutment at rest with the ground."""
    wall = pirqa.Wall.from_ron(
        '(version: 1, name: "on an abutment", thickness_m: 1.0, density_kg_m3: 2500, '
        'friction: 0.8, rows: [(height_m: 0.5, blocks: [(width_m: 1.0, name: "A", fixed: true)]), '
        '(height_m: 0.8, x_m: 0.4, blocks: [(width_m: 0.2, name: "B")])])'
    )
    result = pirqa.run(wall, pirqa.Motion.sine("0.3g", frequency_hz=1.5, duration_s=2.0),
                       output_dt_s=0.01)
    assert result.summary["model"]["name"] == "slide-rock"
    assert [b["name"] for b in result.summary["blocks"]] == ["A", "B"]
    assert result.history.blocks == ["A", "B"]
    assert result.history.rotation_rad.shape[1] == 2
    assert result.history.rotation_rad[:, 0].max() == 0.0
    assert result.history.displacement_m[:, 0].max() == 0.0
    assert result.history.rotation_rad[:, 1].max() > 0.01
    # The stone rocks on a corner of its base: the middle of its base rises by b |sin theta|.
    lift = 0.1 * abs(np.sin(result.history.rotation_rad[:, 1]))
    assert abs(result.history.lift_m[:, 1] - lift).max() < 1e-15
    assert result.history.lift_m[:, 0].max() == 0.0


def test_time_stepping_with_rotations_takes_either_contact_solver(root):
    """Moreau-Jean with every block's rotation solves its steps by Gauss-Seidel or, asked, by
    Newton's method on the whole wall: the summary says which, and on the paper's uniform wall
    (one friction everywhere, where the split of a block on two others does not matter) both
    give the wall's slide within a few micrometres of each other."""
    wall = pirqa.Wall.from_file(root / "walls/five-block-uniform.ron")
    motion = pirqa.Motion.sine("400gal", frequency_hz=1.0, duration_s=3.0)
    peaks = {}
    for solver, equations in [("gauss-seidel", "moreau-jean"), ("newton", "moreau-jean-newton")]:
        result = pirqa.run(wall, motion, method="moreau", dt_s=5e-4, model="slide-rock",
                           contact_solver=solver)
        assert result.summary["model"]["equations"] == equations
        peaks[solver] = max(b["max_abs_displacement_m"] for b in result.summary["blocks"])
    assert peaks["newton"] > 0.01
    assert abs(peaks["newton"] - peaks["gauss-seidel"]) < 5e-6, peaks


def test_releases_and_runs_across_the_plane_are_the_command_lines(root, cli, tmp_path):
    """Blocks released from a rotation on still ground (the standing stone exactly, the paper
    wall's top left block time stepped with every block's rotation) and a run across the wall's
    plane: the same summary as `pirqa run` with the same options, every number to the bit."""
    cases = [
        ("walls/inca/stela.ron", ["--initial-rotation", "Huanca=0.1", "--duration", "3"],
         pirqa.Motion.rest(), dict(duration_s=3.0, initial_rotation={"Huanca": 0.1})),
        (PAPER, ["--initial-rotation", "B3=-0.1", "--duration", "1", "--model", "slide-rock",
                 "--method", "moreau", "--dt", "1e-3"],
         pirqa.Motion.rest(),
         dict(duration_s=1.0, initial_rotation={"B3": -0.1}, model="slide-rock",
              method="moreau", dt_s=1e-3)),
        (PAPER, ["--sine", "0.3g", "--freq", "1.5", "--duration", "2", "--direction",
                 "out-of-plane"],
         pirqa.Motion.sine("0.3g", frequency_hz=1.5, duration_s=2.0),
         dict(direction="out-of-plane")),
    ]
    found = []
    for k, (path, options, motion, settings) in enumerate(cases):
        out = tmp_path / f"out{k}"
        code, err = cli("run", str(root / path), *options, "--out", str(out))
        assert code == 0, err
        expected = json.loads((out / "summary.json").read_text())
        found.append(pirqa.run(pirqa.Wall.from_file(root / path), motion, **settings).summary)
        assert found[-1] == expected
    # The released blocks start at their rotation; the third run is across the plane.
    assert found[0]["blocks"][0]["max_abs_rotation_rad"] == 0.1
    assert found[1]["blocks"][2]["max_abs_rotation_rad"] == 0.1
    assert found[2]["model"]["direction"] == "out-of-plane"
    assert pickle.loads(pickle.dumps(pirqa.Motion.rest())).duration_s == 0.0
    wall = pirqa.Wall.from_file(root / "walls/inca/stela.ron")
    with pytest.raises(pirqa.OptionError, match="duration_s"):
        pirqa.run(wall, pirqa.Motion.rest(), initial_rotation={"Huanca": 0.1})
    with pytest.raises(pirqa.OptionError, match="initial_rotation"):
        pirqa.run(wall, pirqa.Motion.rest(), duration_s=1.0, initial_rotation={"Huanca": "x"})
    with pytest.raises(pirqa.OptionError, match="direction"):
        pirqa.run(wall, pirqa.Motion.rest(), duration_s=1.0, direction="sideways")


def test_a_walls_limit_at_rest_is_exact_with_its_mechanism(root):
    """The paper's variable wall leaves rest at 7/25 g each way (B3 slides on B1 towards -x,
    B5 on B2 towards +x, each the only mechanism there, while the uniform wall's is one of
    several), as `pirqa check --limit --json` says; a wall too large for the exact program
    raises with the reason."""
    wall = pirqa.Wall.from_file(root / "walls/five-block-variable.ron")
    limits = wall.limit_at_rest()
    for side, block, how in [
        ("towards_plus_x", "B3", "slides towards -x"),
        ("towards_minus_x", "B5", "slides towards +x"),
    ]:
        limit = limits[side]
        assert limit["kind"] == "holds" and limit["exact_g"] == "7/25"
        assert limit["accel_g"] == 0.28
        assert [(m["block"], m["how"]) for m in limit["mechanism"]] == [(block, how)]
        assert limit["mechanism_uniqueness"] == "unique"
        assert limit["moving_in_every_mechanism"] == [block]
        assert limit["turning_in_every_mechanism"] == []
    uniform = pirqa.Wall.from_file(root / "walls/five-block-uniform.ron").limit_at_rest()
    assert uniform["towards_minus_x"]["mechanism_uniqueness"] == "one_of_several"
    # Of its several mechanisms, every one moves the top end block the blocks slide towards.
    assert uniform["towards_minus_x"]["moving_in_every_mechanism"] == ["B5"]
    assert uniform["towards_minus_x"]["turning_in_every_mechanism"] == []
    x = np.arange(2001, dtype=float)
    big = pirqa.Wall.from_rectangles(
        x, np.zeros(2001), np.ones(2001), np.full(2001, 0.5),
        thickness_m=0.5, friction=0.3, density_kg_m3=2500,
    )
    with pytest.raises(pirqa.PirqaError, match="up to 2000 movable blocks"):
        big.limit_at_rest()


def test_the_limit_at_rest_of_a_wall_moved_by_a_run():
    """A slender block on a fixed ledge slides past its edge under half a cycle of a 0.5 g
    sine; moved by the run's final displacements it tips about the edge at its centroid's
    distance from it over its height above it (as `pirqa check --run --limit`), where the wall
    as built slides at its friction, 3/20 g. Fallen blocks are taken out; a count that is not
    one per block is refused by name."""
    from fractions import Fraction

    wall = pirqa.Wall.from_ron(
        """(version: 1, name: "ledge", thickness_m: 0.5, density_kg_m3: 2500, friction: 0.8,
            joint_friction: {"U/L": 0.15},
            rows: [(height_m: 0.5, blocks: [(width_m: 1.0, name: "L", fixed: true)]),
                   (height_m: 1.2, x_m: 0.1, blocks: [(width_m: 0.3, name: "U")])])"""
    )
    sine = pirqa.Motion.sine("0.5g", frequency_hz=1.0, duration_s=0.5)
    r = pirqa.run(wall, sine, model="slide")
    u = [b["final_displacement_m"] for b in r.summary["blocks"]]
    assert u[1] < -0.1
    moved = wall.limit_at_rest(displacement_m=np.array(u))
    tips = (Fraction(1, 4) + Fraction(repr(u[1]))) / Fraction(3, 5)
    assert Fraction(moved["towards_plus_x"]["exact_g"]) == min(tips, Fraction(3, 20))
    assert moved["towards_minus_x"]["exact_g"] == "3/20"
    assert wall.limit_at_rest()["towards_plus_x"]["exact_g"] == "3/20"
    assert moved["moved"]["largest_displacement_m"] == -u[1]
    assert moved["moved"]["fallen"] == []
    gone = wall.limit_at_rest(displacement_m=u, fallen=[False, True])
    assert gone["moved"]["fallen"] == ["U"]
    assert gone["towards_plus_x"]["kind"] == "unlimited"
    with pytest.raises(pirqa.OptionError, match="displacement_m: 1 values for 2 blocks"):
        wall.limit_at_rest(displacement_m=[0.0])
    with pytest.raises(pirqa.WallError, match="finite"):
        wall.limit_at_rest(displacement_m=[0.0, float("nan")])
