"""The Python package against the command line it wraps.

What is compared, and why exactly: the package and the command line call the same Rust
functions, and every number crosses the boundary either as raw float64 bytes or as the
shortest decimal that reads back to the same double. So the same scene gives bit-identical
histories and summaries (apart from wall-clock times), and any difference is a bug of the
binding, not round-off. Sweeps by three routes (built-in threads, a process pool, a Dask
cluster) and a planned sweep in two shards must give the same table for the same reason.
"""

import concurrent.futures
import itertools
import multiprocessing
import os
import pickle
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import yaml

import rollbeam

ROOT = Path(__file__).resolve().parents[2]
STUDIES = ROOT / "studies"
BIN = Path(os.environ.get("ROLLBEAM_BIN", ROOT / "target" / "release" / "rollbeam"))


def cli(*args, check=True):
    done = subprocess.run([str(BIN), *map(str, args)], capture_output=True, text=True)
    if check and done.returncode != 0:
        raise AssertionError(f"rollbeam {' '.join(map(str, args))}: {done.stderr}")
    return done


def read_csv(path):
    with open(path) as f:
        head = f.readline().strip().split(",")
    data = np.genfromtxt(path, delimiter=",", skip_header=1, ndmin=2)
    return {name: data[:, k] for k, name in enumerate(head)}


def without_wall(summary):
    """A summary with its wall-clock time left out: the one number that differs by run."""
    s = dict(summary)
    s["solver"] = {k: v for k, v in s["solver"].items() if k != "wall_s"}
    return s


def same_table(a, b):
    assert list(a) == list(b)
    for name in a:
        if name == "wall_s":
            continue
        if a[name].dtype.kind == "f":
            assert np.array_equal(a[name], b[name], equal_nan=True), name
        else:
            assert list(a[name]) == list(b[name]), name


RIGID = {
    "name": "hump",
    "duration": 1.0,
    "track": {"curve": {"parabola": {"k": -0.05}}},
    "disk": {"mass": 2.0, "radius": 0.1, "s0": -1.0, "omega0": -10.0},
}


# --- scenes ---------------------------------------------------------------------------------


def test_a_scene_from_a_path_from_its_text_and_from_a_dict_is_the_same_scene():
    path = STUDIES / "parabola-p1.yaml"
    from_path = rollbeam.Scene.from_yaml(path)
    from_text = rollbeam.Scene.from_yaml(path.read_text())
    assert from_path.name == from_text.name == "parabola-p1"
    assert from_path.to_yaml() == from_text.to_yaml()
    again = rollbeam.Scene.from_yaml(from_path.to_yaml())
    assert again.to_yaml() == from_path.to_yaml()
    assert rollbeam.Scene(RIGID).name == "hump"


def test_scene_errors_carry_the_command_lines_sentence_key_and_line(tmp_path):
    bad = (STUDIES / "parabola-p1.yaml").read_text().replace("radius: 0.1", "radius: -0.1")
    assert bad != (STUDIES / "parabola-p1.yaml").read_text()
    file = tmp_path / "bad.yaml"
    file.write_text(bad)
    with pytest.raises(rollbeam.SceneError) as e:
        rollbeam.Scene.from_yaml(file)
    done = cli("check", file, check=False)
    assert done.returncode == 1
    assert done.stderr.strip() == f"rollbeam: {e.value}"
    assert e.value.key == "disk.radius"
    assert e.value.line == bad.splitlines().index(
        next(l for l in bad.splitlines() if "radius: -0.1" in l)
    ) + 1


def test_dict_scenes_are_checked_as_files_are():
    with pytest.raises(rollbeam.SceneError) as e:
        rollbeam.Scene({**RIGID, "disk": {**RIGID["disk"], "mass": 0.0}})
    assert e.value.key == "disk.mass"
    # The key says where; the line of the JSON text the dict was read as, never seen, does not.
    assert e.value.message.startswith("scene dict: ") and e.value.line is None, e.value
    table = rollbeam.sweep(rollbeam.Scene(RIGID), {"disk.mass": [1.0, -1.0]})
    assert table["status"][1].startswith("failed: scene dict: `disk.mass`"), table["status"][1]
    with pytest.raises(rollbeam.SceneError) as e:
        rollbeam.Scene({**RIGID, "gravity": float("nan")})
    with pytest.raises(rollbeam.SceneError) as e:
        rollbeam.Scene({**RIGID, "unknown": 1})
    assert e.value.message.startswith("scene dict: ") and e.value.line is None, e.value
    with pytest.raises(rollbeam.SceneError):
        rollbeam.Scene("not a dict")


def test_dict_scenes_name_the_nested_key_the_reader_refused():
    # The dict is read as JSON, every key quoted: the reader's own errors (a list of the wrong
    # length, a key left out) still name the dotted key, as a file's do.
    beam = yaml.safe_load((STUDIES / "beam-b1.yaml").read_text())
    three = {**beam, "track": {"beam": {**beam["track"]["beam"], "from": [0.0, 0.0, 0.0]}}}
    with pytest.raises(rollbeam.SceneError) as e:
        rollbeam.Scene(three)
    assert e.value.key == "track.beam.from", e.value
    left_out = {k: v for k, v in beam["track"]["beam"].items() if k != "rho"}
    with pytest.raises(rollbeam.SceneError) as e:
        rollbeam.Scene({**beam, "track": {"beam": left_out}})
    assert e.value.key == "track.beam.rho", e.value


def test_with_values_returns_a_changed_copy_and_checks_it():
    scene = rollbeam.Scene.from_yaml(STUDIES / "bridge-d44.yaml")
    faster = scene.with_values({"disk.omega0": -80.0, "disk.coupling": "moving-force"})
    assert "omega0: -80.0" in faster.to_yaml()
    assert "coupling: moving-force" in faster.to_yaml()
    assert "omega0: -80.0" not in scene.to_yaml()
    with pytest.raises(rollbeam.SceneError) as e:
        scene.with_values({"track.beam.E": -1.0})
    assert e.value.key == "track.beam.E"
    with pytest.raises(rollbeam.SceneError):
        scene.with_values({"disk.no_such_key": 1.0})


def test_vehicles_from_a_dict_run_and_are_checked_as_files_are(tmp_path):
    """A vehicle given as a dict is the scene the command line reads from YAML: its summary's
    vehicle block and history columns are the same numbers; a flawed vehicle is refused in
    one sentence naming the key."""
    sprung = rollbeam.Scene.from_yaml(STUDIES / "vehicle-sprung.yaml")
    as_dict = {
        "name": "vehicle-sprung",
        "duration": 1.0,
        "track": {
            "beam": {
                "from": [0.0, 0.0], "to": [25.0, 0.0], "E": 2.87e9, "G": 1.0e12,
                "rho": 2.303, "A": 1000.0, "Av": 1000.0, "I": 2.9, "depth": 0.01,
                "supports": {"from": "pinned", "to": "roller"},
            }
        },
        "vehicles": [{
            "name": "car", "speed": 27.78,
            "bodies": [{"name": "body", "mass": 5750.0}],
            "axles": [{"name": "wheel", "x": 0.0}],
            "springs": [{"upper": "body", "lower": "wheel", "x": 0.0, "k": 1595.0e3}],
        }],
        "output": {"probes": [{"name": "mid", "x": 12.5}]},
    }
    ours = rollbeam.run(rollbeam.Scene(as_dict))
    theirs = rollbeam.run(sprung)
    assert without_wall(ours.summary) == without_wall(theirs.summary)
    assert ours.summary["vehicles"]["car"]["bodies"]["body"]["a_max"] > 0.0
    assert np.array_equal(ours.history["car.body.a"], theirs.history["car.body.a"])
    car = as_dict["vehicles"][0]
    for flaw, key in [
        ({"springs": [{**car["springs"][0], "lower": "nowhere"}]}, "vehicles.springs.lower"),
        ({"bodies": [{"name": "body", "mass": -1.0}]}, "vehicles.bodies.mass"),
        ({"axles": []}, "vehicles.axles"),
    ]:
        with pytest.raises(rollbeam.SceneError) as e:
            rollbeam.Scene({**as_dict, "vehicles": [{**car, **flaw}]})
        assert e.value.key == key


def test_several_disks_from_a_dict_run_and_name_their_columns():
    """Two moving forces 10 m apart on D44's bridge, listed as `disks`: each has its own
    history columns and summary entry in the list's order, leaving the beam at (20 − s0) / v;
    a listed disk's keys are changed as disks.<k>.<field>, and a flawed disk is refused
    naming its place in the list."""
    beam = {
        "from": [0.0, 0.0], "to": [20.0, 0.0], "E": 210.0e9, "G": 81.0e9, "rho": 7850,
        "A": 181.0e-4, "Av": 46.8e-4, "I": 43190.0e-8, "depth": 0.36,
        "supports": {"from": "pinned", "to": "roller"}, "elements": 4, "model": "modal",
        "modes": 8,
    }
    disk = {"mass": 1500, "radius": 0.4, "omega0": -44, "coupling": "moving-force"}
    scene = {
        "duration": 1.2,
        "track": {"beam": beam},
        "disks": [{**disk, "s0": 10.0}, {**disk, "s0": 0.0}],
        "output": {"probes": [{"name": "mid", "x": 10.0}]},
    }
    result = rollbeam.run(rollbeam.Scene(scene))
    assert "disk" not in result.summary
    first, second = result.summary["disks"]
    assert first["left_track_t"] == pytest.approx(10.0 / 17.6, rel=1e-9)
    assert second["left_track_t"] == pytest.approx(20.0 / 17.6, rel=1e-9)
    s1, s2 = result.history["disk1.s"], result.history["disk2.s"]
    on = ~np.isnan(s1)
    assert np.allclose(s1[on] - s2[on], 10.0)
    assert np.isnan(s1[-1]) and np.isnan(s2[-1])
    moved = rollbeam.Scene(scene).with_values({"disks.2.s0": 5.0})
    assert rollbeam.run(moved).summary["disks"][1]["left_track_t"] == pytest.approx(
        15.0 / 17.6, rel=1e-9
    )
    table = rollbeam.sweep(rollbeam.Scene(scene), {"disks.2.s0": [0.0, 5.0]})
    assert np.allclose(table["disk1.left_track_t"], 10.0 / 17.6, rtol=1e-9)
    assert np.allclose(table["disk2.left_track_t"], [20.0 / 17.6, 15.0 / 17.6], rtol=1e-9)
    with pytest.raises(rollbeam.SceneError) as e:
        rollbeam.Scene({**scene, "disks": [{**disk, "s0": 1.0}, {**disk, "mass": -1.0}]})
    assert e.value.key == "disks[2].mass"


def test_scenes_pickle():
    scene = rollbeam.Scene.from_yaml(STUDIES / "bridge-d44.yaml").with_values({"disk.omega0": -30})
    back = pickle.loads(pickle.dumps(scene))
    assert back.to_yaml() == scene.to_yaml() and back.name == scene.name


# --- runs against the command line ----------------------------------------------------------


@pytest.mark.parametrize("study", ["parabola-p1.yaml", "bridge-d44.yaml"])
def test_run_gives_the_numbers_the_command_line_writes(study, tmp_path):
    scene = rollbeam.Scene.from_yaml(STUDIES / study)
    result = rollbeam.run(scene)
    cli("run", STUDIES / study, "--out", tmp_path / "cli")
    written = read_csv(tmp_path / "cli" / "history.csv")
    assert list(written) == list(result.history)
    for name, column in written.items():
        assert np.array_equal(column, result.history[name], equal_nan=True), name
    import yaml

    on_disk = yaml.load((tmp_path / "cli" / "summary.yaml").read_text(), Loader=rollbeam._Loader)
    assert without_wall(on_disk) == without_wall(result.summary)
    assert result.stopped == on_disk["stopped"]["reason"]
    np.testing.assert_array_equal(result.t, written["t"])


def test_result_write_writes_what_run_writes(tmp_path):
    study = STUDIES / "bridge-d44.yaml"
    result = rollbeam.run(rollbeam.Scene.from_yaml(study), rtol=1e-4)
    result.write(tmp_path / "py")
    cli("run", study, "--rtol", "1e-4", "--out", tmp_path / "cli")
    assert sorted(os.listdir(tmp_path / "py")) == sorted(os.listdir(tmp_path / "cli"))
    assert (tmp_path / "py" / "history.csv").read_text() == (tmp_path / "cli" / "history.csv").read_text()
    result.write(tmp_path / "py-bare", figures=False)
    cli("run", study, "--rtol", "1e-4", "--no-figures", "--out", tmp_path / "cli-bare")
    bare = sorted(os.listdir(tmp_path / "py-bare"))
    assert bare == sorted(os.listdir(tmp_path / "cli-bare")) == ["history.csv", "summary.yaml"]


def test_beam_results_have_shapes_and_envelope_consistent_with_the_history():
    result = rollbeam.run(rollbeam.Scene.from_yaml(STUDIES / "bridge-d44.yaml"), rtol=1e-4)
    shapes, env = result.shapes, result.envelope
    assert shapes["w"].shape == (len(shapes["t"]), len(shapes["x"]))
    # The envelope is taken over every step; the probe is read at the output times, so it
    # lies inside the envelope at the probe's point (x = 10 m is a sample point).
    k = int(np.argmin(abs(env["x"] - 10.0)))
    assert env["x"][k] == pytest.approx(10.0)
    assert env["w_min"][k] <= result.history["mid.w"].min() + 1e-12
    assert env["w_max"][k] >= result.history["mid.w"].max() - 1e-12
    assert rollbeam.run(rollbeam.Scene.from_yaml(STUDIES / "parabola-p1.yaml")).shapes is None


def test_options_override_the_scene_and_are_checked():
    scene = rollbeam.Scene.from_yaml(STUDIES / "parabola-p1.yaml")
    r = rollbeam.run(scene, method="trbdf2", rtol=1e-5)
    assert r.summary["solver"]["method"] == "trbdf2" and r.summary["solver"]["rtol"] == 1e-5
    with pytest.raises(rollbeam.SceneError):
        rollbeam.run(scene, method="euler")
    with pytest.raises(rollbeam.SceneError):
        rollbeam.run(scene, rtol=-1.0)


def test_a_physical_stop_is_a_result_and_a_solver_failure_raises(tmp_path):
    # The disk rolls off the end of a short straight track: a stop with its reason.
    off = rollbeam.Scene(
        {
            "duration": 2.0,
            "track": {"curve": {"line": {"from": [0.0, 0.0], "to": [1.0, 0.0]}}},
            "disk": {"mass": 1.0, "radius": 0.1, "s0": 0.2, "omega0": -20.0},
        }
    )
    assert rollbeam.run(off).stopped == "left-track"
    # A load that Newton's method cannot carry, even in load steps: the solver's error.
    text = (STUDIES / "beam-b1.yaml").read_text().replace("fy: -10.0e3", "fy: -1.0e13")
    text = text.replace("from: clamped, to: pinned", "from: clamped, to: free")
    huge = rollbeam.Scene.from_yaml(text)
    with pytest.raises(rollbeam.SolverError):
        rollbeam.static(huge)


# --- check, static, modes, tradeoff ---------------------------------------------------------


def test_check_prints_what_the_command_line_prints():
    study = STUDIES / "bridge-d44.yaml"
    assert rollbeam.check(rollbeam.Scene.from_yaml(study)) == cli("check", study).stdout.rstrip("\n")


def test_static_and_modes_agree_with_the_command_line(tmp_path):
    import yaml

    b1 = STUDIES / "beam-b1.yaml"
    cli("static", b1, "--out", tmp_path)
    assert rollbeam.static(rollbeam.Scene.from_yaml(b1)) == yaml.load(
        (tmp_path / "static.yaml").read_text(), Loader=rollbeam._Loader
    )
    d44 = STUDIES / "bridge-d44.yaml"
    cli("modes", d44, "--count", "4", "--out", tmp_path)
    modes = rollbeam.modes(rollbeam.Scene.from_yaml(d44), count=4)
    on_disk = yaml.load((tmp_path / "modes.yaml").read_text(), Loader=rollbeam._Loader)
    np.testing.assert_array_equal(modes.frequencies_hz, on_disk["frequencies_hz"])
    # Mass-normalised shapes of a simply supported beam: mode k has k half-waves, so the
    # first one does not change sign along the span.
    assert modes.w.shape == (4, 201)
    assert np.all(modes.w[0] <= 1e-12) or np.all(modes.w[0] >= -1e-12)
    with pytest.raises(rollbeam.SceneError):
        rollbeam.modes(rollbeam.Scene.from_yaml(STUDIES / "parabola-p1.yaml"))


def test_tradeoff_writes_the_table_and_names_the_cheapest(tmp_path):
    scene = rollbeam.Scene.from_yaml(STUDIES / "parabola-p1.yaml")
    table, lines = rollbeam.tradeoff(scene, tmp_path, methods=["dopri5"], rtols=[1e-3, 1e-5])
    assert (tmp_path / "tradeoff.svg").exists()
    assert table.rows == 2 and set(table["method"]) == {"dopri5"}
    assert any("stored reference" in l for l in lines)
    # Tightening rtol a hundredfold does not make dopri5 less accurate on this smooth problem.
    errors = table["headline_error"] if "headline_error" in table else next(
        v for k, v in table.items() if "error" in k and v.dtype.kind == "f"
    )
    assert errors[1] <= errors[0]
    # A rigid curve has no elements whose degree could be swept: one sentence, no table.
    with pytest.raises(rollbeam.SceneError, match="--orders"):
        rollbeam.tradeoff(scene, tmp_path / "p", methods=["dopri5"], orders=[4])


# --- sweeps ---------------------------------------------------------------------------------

SWEPT = {"disk.omega0": np.array([-20.0, -60.0, -40.0]), "disk.coupling": ["consistent", "moving-force"]}


@pytest.fixture(scope="module")
def d44():
    return rollbeam.Scene.from_yaml(STUDIES / "bridge-d44.yaml")


@pytest.fixture(scope="module")
def built_in(d44):
    return rollbeam.sweep(d44, SWEPT, rtol=1e-4)


def test_the_built_in_sweep_is_the_grid_in_order_with_one_column_per_key(built_in, d44):
    assert built_in.rows == 6
    np.testing.assert_array_equal(built_in["disk.omega0"], [-20, -20, -60, -60, -40, -40])
    assert list(built_in["disk.coupling"]) == ["consistent", "moving-force"] * 3
    assert set(built_in["status"]) == {"ok"}
    # Each row is the run of that case: its extremes, located on the solution, are the
    # summary's, and no sample of its history lies beyond them.
    one = rollbeam.run(d44.with_values({"disk.omega0": -60.0, "disk.coupling": "moving-force"}), rtol=1e-4)
    assert built_in["mid.w_min"][3] == one.summary["probes"]["mid"]["w_min"]
    assert built_in["mid.w_min"][3] <= one.history["mid.w"].min()
    df = built_in.to_pandas()
    assert list(df.columns) == list(built_in)


def test_a_process_pool_gives_the_same_table(built_in, d44):
    context = multiprocessing.get_context("spawn")
    with concurrent.futures.ProcessPoolExecutor(max_workers=2, mp_context=context) as pool:
        pooled = rollbeam.sweep(d44, SWEPT, executor=pool, rtol=1e-4)
    same_table(pooled, built_in)


def test_a_local_dask_cluster_gives_the_same_table(built_in, d44):
    distributed = pytest.importorskip("dask.distributed")
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        on_dask = rollbeam.sweep(d44, SWEPT, executor=client.get_executor(), rtol=1e-4)
    same_table(on_dask, built_in)


def test_sweep_errors(d44):
    with pytest.raises(rollbeam.SceneError):
        rollbeam.sweep(d44, {"disk.no_such_key": [1.0, 2.0]})
    with pytest.raises(rollbeam.SceneError):
        rollbeam.sweep(d44, {"track.beam.elements": [10.5]})
    with pytest.raises(rollbeam.SceneError):
        rollbeam.sweep(d44, {"disk.omega0": []})
    with pytest.raises(rollbeam.SceneError):
        rollbeam.sweep(d44, {"disk.omega0": np.zeros(400), "disk.s0": np.zeros(400)})
    # Values a sweep could not run are refused before they are made into a list: a billion
    # of them took all the memory there was.
    for endless in (range(10**9), itertools.count()):
        with pytest.raises(rollbeam.SceneError, match="more than 100000 values") as e:
            rollbeam.sweep(d44, {"disk.omega0": endless})
        assert e.value.key == "disk.omega0"
    # A value the scene can hold but not run with is that case's row, with its reason.
    table = rollbeam.sweep(d44, {"disk.radius": [0.4, -1.0]}, rtol=1e-3)
    assert table["status"][0] == "ok" and table["status"][1].startswith("failed: ")
    assert np.isnan(table["mid.w_min"][1])


def test_bad_values_fail_in_pythons_words_naming_the_key(d44):
    for bad in (None, [1.0], 10**400, float("nan"), True):
        with pytest.raises(rollbeam.SceneError) as e:
            d44.with_values({"disk.omega0": bad})
        assert e.value.key == "disk.omega0", e.value
    with pytest.raises(rollbeam.SceneError, match="one value per key"):
        rollbeam.sweep_case(d44, ["disk.mass", "disk.radius"], [1.0])
    for count in (-1, 0, 2.5):
        with pytest.raises(rollbeam.SceneError) as e:
            rollbeam.modes(d44, count=count)
        assert e.value.key == "count"
    with pytest.raises(rollbeam.SceneError, match="more than the 120 modes the mesh holds"):
        rollbeam.modes(d44, count=121)


def test_what_is_not_a_scene_fails_in_pythons_words(tmp_path):
    deep: dict = {}
    node = deep
    for _ in range(5000):
        node["a"] = {}
        node = node["a"]
    with pytest.raises(rollbeam.SceneError, match="nested deeper"):
        rollbeam.Scene(deep)
    for function in (rollbeam.run, rollbeam.check, rollbeam.static, rollbeam.modes):
        with pytest.raises(rollbeam.SceneError, match=r"takes a rollbeam.Scene \(got dict\)"):
            function({"name": "x"})
    fifo = tmp_path / "scene.yaml"
    os.mkfifo(fifo)
    with pytest.raises(rollbeam.SceneError, match="not a regular file"):
        rollbeam.Scene.from_yaml(fifo)
    # A path given as text is a path still: a folder, a device or a misspelt name is said to
    # be one, not read as a scene's text that lacks a mapping.
    for path, why in ((str(tmp_path), "not a regular file"), ("/dev/zero", "not a regular file"),
                      (str(tmp_path / "missing.yaml"), "no such file")):
        with pytest.raises(rollbeam.SceneError, match=f"cannot read scene file {path}: {why}"):
            rollbeam.Scene.from_yaml(path)


def test_merged_records_must_agree(d44):
    record = rollbeam.sweep_case(d44, ["disk.omega0"], [-44.0])
    other = record.replace("- name: mid", "- name: elsewhere", 1)
    assert other != record
    with pytest.raises(rollbeam.SceneError, match="not of one scene"):
        rollbeam._call(rollbeam._native.merge, ["disk.omega0"], [record, other])


def test_the_sweep_matches_the_command_lines_sweep_csv(tmp_path, d44):
    cli("sweep", STUDIES / "bridge-d44.yaml", "--set", "disk.omega0=-20:-40:3", "--rtol", "1e-4", "--out", tmp_path)
    table = rollbeam.sweep(d44, {"disk.omega0": [-40.0, -30.0, -20.0]}, rtol=1e-4)
    written = read_csv(tmp_path / "sweep.csv")
    for name in written:
        if name not in ("wall_s", "status", "stopped"):
            np.testing.assert_array_equal(written[name], table[name], err_msg=name)


def test_a_planned_sweep_in_two_shards_merges_into_the_one_shot_table(tmp_path):
    scene = STUDIES / "bridge-d44.yaml"
    sets = ["--set", "disk.omega0=-20:-50:4", "--set", "disk.coupling=consistent,moving-force"]
    cli("sweep", scene, *sets, "--out", tmp_path / "one")
    cli("sweep", scene, *sets, "--plan", tmp_path / "plan")
    cli("sweep", "--plan", tmp_path / "plan", "--shard", "1/2")
    cases = sorted((tmp_path / "plan" / "cases").iterdir())
    # One case by `rollbeam run` on its file, as a job array's task would; then the shard
    # that holds it skips it.
    cli("run", cases[1])
    assert "1 already done" in cli("sweep", "--plan", tmp_path / "plan", "--shard", "2/2").stdout
    cli("sweep", "--merge", tmp_path / "plan")
    one = (tmp_path / "one" / "sweep.csv").read_text().splitlines()
    merged = (tmp_path / "plan" / "sweep.csv").read_text().splitlines()
    wall = one[0].split(",").index("wall_s")
    strip = lambda lines: [",".join(c for k, c in enumerate(l.split(",")) if k != wall) for l in lines]
    assert strip(one) == strip(merged)


# --- examples -------------------------------------------------------------------------------


@pytest.mark.parametrize("example", ["run_and_plot.py", "speed_sweep.py", "dask_sweep.py"])
def test_examples_run(example, tmp_path):
    pytest.importorskip("matplotlib")
    env = {**os.environ, "MPLBACKEND": "Agg"}
    done = subprocess.run(
        [sys.executable, str(ROOT / "examples" / example)],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        env=env,
        timeout=600,
    )
    assert done.returncode == 0, done.stderr
    if example != "dask_sweep.py":
        assert any(p.suffix == ".png" for p in tmp_path.iterdir())
