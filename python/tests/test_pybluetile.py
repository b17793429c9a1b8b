"""pybluetile against the bluetile tool (bit for bit, same seeds), NumPy as an independent
reader and writer of .npy, bad input, and the GIL released while the library works."""
import csv
import json
import os
import pickle
import signal
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

import pybluetile as bt


def load_text(path, columns=2):
    """Points written by the tool (17 significant digits: exact doubles)."""
    return np.loadtxt(path, comments="#", ndmin=2)[:, :columns]


def test_relax_matches_the_tool_bit_for_bit(tool, tmp_path):
    out = tmp_path / "relaxed.txt"
    tool("relax", "--count", 300, "--iterations", 12, "--seed", 5, "--engine", "exact", "--output", out)
    points = bt.relax(count=300, iterations=12, seed=5, engine="exact")
    assert points.shape == (300, 2) and points.dtype == np.float64
    assert np.array_equal(points, load_text(out))
    # From given points, with fixed sites, as relax --input --fixed.
    start = bt.random_points(100, seed=9)
    np.savetxt(tmp_path / "start.txt", start, fmt="%.17g")
    tool("relax", "--input", tmp_path / "start.txt", "--iterations", 4, "--fixed", 10, "--engine", "exact",
         "--output", tmp_path / "more.txt")
    more = bt.relax(start, iterations=4, fixed=10, engine="exact")
    assert np.array_equal(more, load_text(tmp_path / "more.txt"))
    assert np.array_equal(more[:10], start[:10])


def test_history_matches_the_log(tool, tmp_path):
    tool("relax", "--count", 100, "--iterations", 6, "--seed", 2, "--engine", "exact", "--output", tmp_path / "p.txt",
         "--log", tmp_path / "log.csv")
    log = np.loadtxt(tmp_path / "log.csv", delimiter=",", skiprows=1)
    points, history = bt.relax(count=100, iterations=6, seed=2, engine="exact", history=True)
    assert np.array_equal(points, load_text(tmp_path / "p.txt"))
    # Every column of the log (zero_density was missing) and no other.
    columns = ("iteration", "energy", "max_displacement", "mean_displacement", "coincident", "fallbacks",
               "zero_density")
    assert tuple((tmp_path / "log.csv").read_text().splitlines()[0].split(",")) == columns
    assert set(history) == set(columns)
    for c, name in enumerate(columns):
        assert np.array_equal(history[name], log[:, c]), name


def test_raster_engine_matches_the_tool(tool, tmp_path):
    out = tmp_path / "raster.txt"
    tool("relax", "--count", 64, "--iterations", 3, "--seed", 2, "--engine", "raster", "--output", out)
    assert np.array_equal(bt.relax(count=64, iterations=3, seed=2, engine="raster"), load_text(out))


def test_pixel_work_moves_the_work_not_the_result(tool, tmp_path):
    # As --pixel-work: the device's shaders and the host's threads give the tool's bits.
    out = tmp_path / "device.txt"
    tool("relax", "--count", 200, "--iterations", 3, "--seed", 6, "--engine", "raster", "--pixel-work", "device",
         "--output", out)
    from_tool = load_text(out)
    for work in ("device", "host", "auto"):
        points = bt.relax(count=200, iterations=3, seed=6, engine="raster", pixel_work=work)
        assert np.array_equal(points, from_tool), work
    centres, areas = bt.centroids(from_tool, engine="raster", pixel_work="device")
    host_centres, host_areas = bt.centroids(from_tool, engine="raster", pixel_work="host")
    assert np.array_equal(centres, host_centres) and np.array_equal(areas, host_areas)
    with pytest.raises(ValueError, match="pixel_work: expected one of 'auto', 'device', 'host', got 'gpu'"):
        bt.relax(count=10, engine="raster", pixel_work="gpu")


def test_sets_match_the_tool(tool, tmp_path):
    out = tmp_path / "sets.txt"
    tool("relax", "--count", 40, "--sets", 3, "--iterations", 5, "--seed", 4, "--engine", "exact", "--output", out)
    sets = bt.relax(count=40, sets=3, iterations=5, seed=4, engine="exact")
    assert sets.shape == (3, 40, 2)
    from_tool = bt.load_table(str(out))
    assert len(from_tool) == 3
    for k in range(3):
        assert np.array_equal(sets[k], from_tool[k])
    # The tool's .npy is NumPy's own format, the same bits.
    tool("relax", "--count", 40, "--sets", 3, "--iterations", 5, "--seed", 4, "--engine", "exact",
         "--output", tmp_path / "sets.npy")
    assert np.array_equal(np.load(tmp_path / "sets.npy"), sets)
    # Set k does not depend on how many sets there are; an (K, N, 2) input relaxes each set.
    assert np.array_equal(bt.relax(count=40, iterations=5, seed=4, engine="exact"), sets[0])
    again = bt.relax(bt.random_points(40, seed=4, set=2)[None], iterations=5, engine="exact")
    assert np.array_equal(again[0], sets[2])


def test_random_points_are_the_relax_start():
    assert np.array_equal(bt.random_points(50, seed=3), bt.relax(count=50, iterations=0, seed=3, engine="exact"))


def test_centroids_match_the_tool(tool, tmp_path):
    points = bt.random_points(80, seed=1)
    np.savetxt(tmp_path / "p.txt", points, fmt="%.17g")
    tool("centroids", "--input", tmp_path / "p.txt", "--engine", "exact", "--output", tmp_path / "c.txt")
    reference = np.loadtxt(tmp_path / "c.txt", comments="#")
    centres, areas = bt.centroids(points, engine="exact")
    assert np.array_equal(centres, reference[:, :2]) and np.array_equal(areas, reference[:, 2])
    assert abs(areas.sum() - 1.0) < 1e-12
    batched_centres, batched_areas = bt.centroids(np.stack([points, points]), engine="exact")
    assert batched_centres.shape == (2, 80, 2) and np.array_equal(batched_areas[1], areas)


def test_progressive_matches_the_tool(tool, tmp_path):
    out = tmp_path / "levels.txt"
    tool("progressive", "--count", 30, "--levels", 3, "--iterations", 5, "--seed", 7, "--engine", "exact",
         "--output", out)
    reference = np.loadtxt(out, comments="#")
    points, levels = bt.progressive(count=30, levels=3, iterations=5, seed=7, engine="exact")
    assert points.shape == (90, 2) and levels.dtype == np.int32
    assert np.array_equal(points, reference[:, :2]) and np.array_equal(levels, reference[:, 2])
    # One more level on that base keeps the base bit for bit.
    more, more_levels = bt.progressive(points, levels, add=30, iterations=5, engine="exact")
    assert np.array_equal(more[:90], points) and list(np.unique(more_levels)) == [0, 1, 2, 3]


def test_progressive_rank_order_matches_the_tool(tool, tmp_path):
    out = tmp_path / "voids.txt"
    tool("progressive", "--count", 1, "--add", 1, "--levels", 64, "--iterations", 10, "--seed", 3, "--engine", "exact",
         "--rank-order", "voids", "--output", out)
    reference = np.loadtxt(out, comments="#")
    points, levels = bt.progressive(count=1, add=1, levels=64, iterations=10, seed=3, engine="exact",
                                    rank_order="voids")
    assert np.array_equal(points, reference[:, :2]) and np.array_equal(levels, reference[:, 2])
    assert list(levels) == list(range(64))
    tool("progressive", "--count", 64, "--ratio", 2, "--levels", 3, "--seed", 3, "--rank-order", "fill", "--output", out)
    reference = np.loadtxt(out, comments="#")
    points, levels = bt.progressive(count=64, ratio=2, levels=3, seed=3, rank_order="fill")
    assert np.array_equal(points, reference[:, :2]) and np.array_equal(levels, reference[:, 2])
    # The fill relaxes nothing and opens no device: a device named for it is refused, as the tool's
    # --device with --rank-order fill, not looked for.
    with pytest.raises(ValueError, match=r"^device='no-such-device': rank_order='fill' relaxes nothing"):
        bt.progressive(count=64, ratio=2, levels=3, seed=3, rank_order="fill", device="no-such-device")
    with pytest.raises(ValueError, match="rank order: expected 'placement', 'voids' or 'fill', got 'farthest'"):
        bt.progressive(count=10, rank_order="farthest", engine="exact")


def test_dart_matches_the_tool(tool, tmp_path):
    tool("dart", "--count", 200, "--seed", 3, "--output", tmp_path / "d.txt")
    points, info = bt.dart(200, seed=3, info=True)
    assert np.array_equal(points, load_text(tmp_path / "d.txt"))
    assert info["final_radius"] <= info["initial_radius"]


# stats.json's keys that describe the run rather than the set (mode, inputs, the plots).
TOOL_ONLY_KEYS = {"mode", "label", "inputs", "bin_width", "frequency_axis", "images"}


def assert_same_values(mine, theirs, where):
    if isinstance(theirs, dict):
        assert isinstance(mine, dict) and set(mine) == set(theirs), (where, set(mine) ^ set(theirs))
        for key in theirs:
            assert_same_values(mine[key], theirs[key], f"{where}.{key}")
    elif isinstance(theirs, list):
        reference = np.array([np.nan if v is None else v for v in theirs])
        assert np.array_equal(np.asarray(mine), reference, equal_nan=True), where
    else:
        assert mine == theirs, (where, mine, theirs)


def test_analyze_matches_stats_json(tool, tmp_path):
    points = bt.relax(count=200, iterations=20, seed=1, engine="exact")
    np.savetxt(tmp_path / "p.txt", points, fmt="%.17g")
    tool("analyze", "--input", tmp_path / "p.txt", "--output", tmp_path / "a")
    stats = json.loads((tmp_path / "a" / "stats.json").read_text())
    # The same file read back, as a user would: the tool and the module see the same numbers.
    mine = bt.analyze(np.loadtxt(tmp_path / "p.txt"))
    series = {k: v for k, v in stats.items() if k not in TOOL_ONLY_KEYS}
    assert set(mine) - {"periodogram"} == set(series)
    for key in ("rho", "average_min_distance", "nu_eff", "omega", "bond_order", "boundary"):
        assert key in mine, key
    assert mine["nu_eff"] > 0.5 and mine["bond_order"]["local"] > 0.5  # a relaxed set
    assert_same_values({k: v for k, v in mine.items() if k != "periodogram"}, series, "stats")
    f = stats["periodogram_size"]
    spectrum = bt.periodogram(points)
    assert spectrum.shape == (f, f) and spectrum[f // 2, f // 2] == pytest.approx(200.0)
    assert np.array_equal(spectrum, mine["periodogram"])
    assert np.array_equal(bt.radial_power(points)["power"], mine["radial"]["power"])
    distances = bt.nearest_neighbour_distances(points)
    assert distances.min() == stats["nn_min"]


def test_analyze_averages_sets_and_skips_psa_measures_like_the_tool(tool, tmp_path):
    sets = np.stack([bt.relax(count=128, iterations=10, seed=s, engine="exact") for s in (3, 4)])
    text = "\n#\n".join("\n".join(f"{x:.17g} {y:.17g}" for x, y in points) for points in sets)
    (tmp_path / "two.txt").write_text(text + "\n")
    tool("analyze", "--input", tmp_path / "two.txt", "--output", tmp_path / "a", "--average", "--no-psa-measures")
    stats = json.loads((tmp_path / "a" / "stats.json").read_text())
    mine = bt.analyze(sets, psa_measures=False)
    assert mine["sets"] == 2 and mine["nu_eff"] is None and mine["omega"] is None
    assert_same_values({k: v for k, v in mine.items() if k != "periodogram"},
                       {k: v for k, v in stats.items() if k not in TOOL_ONLY_KEYS}, "stats")
    # Without the discrepancies, as --no-discrepancy.
    tool("analyze", "--input", tmp_path / "two.txt", "--output", tmp_path / "b", "--average", "--no-psa-measures",
         "--no-discrepancy")
    stats = json.loads((tmp_path / "b" / "stats.json").read_text())
    mine = bt.analyze(sets, psa_measures=False, discrepancy=False)
    assert "discrepancy" not in mine and "discrepancy" in bt.analyze(sets, psa_measures=False)
    assert_same_values({k: v for k, v in mine.items() if k != "periodogram"},
                       {k: v for k, v in stats.items() if k not in TOOL_ONLY_KEYS}, "stats")


def test_save_table_refuses_a_comment_load_table_would_refuse(tmp_path):
    # save_table wrote '# domain: bounded', and load_table then refused its own file.
    pts = np.array([[0.25, 0.5]])
    fix = ("is not a domain line, and reading the file back would fail on it: write 'domain periodic' or "
           "'domain bounded' alone")
    for comment, name in ((["domain: bounded"], "comment[0]"), ("Domain Bounded", "comment"),
                          (["made here", "domain bounde"], "comment[1]")):
        with pytest.raises(bt.Error) as error:
            bt.save_table(tmp_path / "c.txt", pts, comment=comment)
        line = comment if isinstance(comment, str) else comment[-1]
        assert str(error.value).startswith(f"{name}: '# {line}' {fix}"), str(error.value)
        assert not (tmp_path / "c.txt").exists()
    # What load_table takes is written: a real domain line (which it reads), prose.
    bt.save_table(tmp_path / "b.txt", pts, comment=["made here", "domain bounded", "domain torus"])
    assert np.array_equal(bt.load_table(tmp_path / "b.txt")[0], pts)
    # A C header is not read back: its '//' comment takes the line.
    bt.save_table(tmp_path / "c.h", pts, comment=["domain: bounded"])
    assert "// domain: bounded\n" in (tmp_path / "c.h").read_text()


def test_save_table_refuses_binary_tables_on_a_terminal(tmp_path):
    # save_table('/dev/tty', pts, format='npy') put the binary bytes onto the terminal; the tool
    # refuses that, and so does the module now. The terminal is a new pseudo-terminal, named by a
    # link in the temporary folder.
    controller, terminal = os.openpty()
    try:
        link = tmp_path / "tty"
        link.symlink_to(os.ttyname(terminal))
        pts = np.array([[0.25, 0.5]])
        for fmt, words in (("npy", "NumPy (.npy)"), ("binary", "point table (.bpt)")):
            with pytest.raises(bt.Error) as error:
                bt.save_table(link, pts, format=fmt)
            assert str(error.value) == (f"{link}: is a terminal, and {words} data is binary: write it to a file or "
                                        "pipe it to a program (| ...)")
        os.set_blocking(controller, False)
        try:
            assert os.read(controller, 4096) == b""
        except BlockingIOError:
            pass  # nothing was written
        # Text goes to a terminal as to a file.
        bt.save_table(link, pts, format="text")
        time.sleep(0.1)
        assert b"0.25" in os.read(controller, 4096)
    finally:
        os.close(controller)
        os.close(terminal)


def test_tables_round_trip_and_numpy_reads_them(tmp_path):
    sets = bt.relax(count=64, sets=5, iterations=2, seed=1, engine="exact")
    bt.save_table(str(tmp_path / "t.npy"), sets)
    assert np.array_equal(np.load(tmp_path / "t.npy"), sets)
    bt.save_table(str(tmp_path / "t32.npy"), sets, float32=True)
    loaded32 = np.load(tmp_path / "t32.npy")
    assert loaded32.dtype == np.float32 and np.array_equal(loaded32, sets.astype(np.float32))
    for name in ("t.npy", "t.bpt", "t.txt", "t.csv"):
        path = str(tmp_path / name)
        bt.save_table(path, sets)
        back = bt.load_table(path)
        assert len(back) == 5 and all(np.array_equal(back[k], sets[k]) for k in range(5)), name
    # A CSV as the csv module (and pandas with comment='#') reads it: a header, then x,y rows.
    bt.save_table(str(tmp_path / "one.csv"), sets[0], comment="made here")
    with open(tmp_path / "one.csv", newline="") as f:
        rows = list(csv.reader(line for line in f if not line.startswith("#")))
    assert rows[0] == ["x", "y"] and np.array_equal(np.array(rows[1:], dtype=float), sets[0])
    assert (tmp_path / "one.csv").read_text().startswith("# made here\nx,y\n")
    points, levels = bt.progressive(count=8, levels=2, iterations=2, engine="exact")
    bt.save_table(str(tmp_path / "l.csv"), points, levels=levels)
    (back, back_levels), = bt.load_table(str(tmp_path / "l.csv"), levels=True)
    assert np.array_equal(back, points) and np.array_equal(back_levels, levels)
    # Writing leaves the signals to Python: none blocked (they were, for good, after a first
    # write, so Ctrl-C ended the interpreter and every process it started could not be stopped).
    assert signal.pthread_sigmask(signal.SIG_BLOCK, []) == set()
    # A comment holding a line break stays a comment: no point added, no code in a C header.
    bt.save_table(str(tmp_path / "c.txt"), sets[0], comment=["hello\n0.25 0.75"])
    assert bt.load_table(str(tmp_path / "c.txt"))[0].shape == (64, 2)
    bt.save_table(str(tmp_path / "c.h"), sets[0], comment=["a\nint evil;", "ends in \\"])
    assert "\nint evil;" not in (tmp_path / "c.h").read_text()
    assert "// ends in \\x5c\n" in (tmp_path / "c.h").read_text()
    # Files NumPy writes, in any order and byte order, read back exactly.
    np.save(tmp_path / "f.npy", np.asfortranarray(sets))
    np.save(tmp_path / "b.npy", sets.astype(">f8"))
    for name in ("f.npy", "b.npy"):
        back = bt.load_table(str(tmp_path / name))
        assert all(np.array_equal(back[k], sets[k]) for k in range(5)), name
    bt.save_table(str(tmp_path / "t.h"), sets[:2], name="blue")
    header = (tmp_path / "t.h").read_text()
    assert "static const float blue[2][64][2] = {" in header
    with pytest.raises(bt.Error, match=r"unknown extension '\.png'"):
        bt.save_table(str(tmp_path / "t.png"), sets)


def test_levels_round_trip(tmp_path):
    points, levels = bt.progressive(count=20, levels=2, iterations=2, engine="exact")
    bt.save_table(str(tmp_path / "l.npy"), points, levels=levels)
    table = np.load(tmp_path / "l.npy")
    assert table.shape == (1, 40, 3) and np.array_equal(table[0, :, 2], levels)
    (back, back_levels), = bt.load_table(str(tmp_path / "l.npy"), levels=True)
    assert np.array_equal(back, points) and np.array_equal(back_levels, levels)


def test_bad_input_raises_clear_exceptions(tool, tmp_path):
    with pytest.raises(TypeError, match=r"points: expected float64 \(or float32\) values, got int64"):
        bt.relax(np.zeros((10, 2), dtype=np.int64), engine="exact")
    with pytest.raises(ValueError, match=r"points: expected shape \(N, 2\) or \(K, N, 2\) with N >= 1, got \(10, 3\)"):
        bt.centroids(np.zeros((10, 3)), engine="exact")
    # x and y as rows, numpy.array([xs, ys]): the way to turn them is said.
    rows = r"expected shape \(N, 2\) or \(K, N, 2\) with N >= 1, got \(2, 50\); coordinates as rows\? pass points\.T$"
    with pytest.raises(ValueError, match=rows):
        bt.relax(np.zeros((2, 50)), engine="exact")
    with pytest.raises(ValueError, match=r"got \(4, 2, 50\); coordinates as rows\? pass points\.transpose\(0, 2, 1\)$"):
        bt.analyze(np.zeros((4, 2, 50)))
    bad = bt.random_points(5)
    bad[3, 1] = np.nan
    with pytest.raises(ValueError, match=r"points\[3\]: not a finite number 'nan'"):
        bt.relax(bad, engine="exact")
    with pytest.raises(ValueError, match="engine: expected one of 'raster', 'exact', got 'gpu'"):
        bt.relax(count=10, engine="gpu")
    with pytest.raises(ValueError, match="give either points or count"):
        bt.relax()
    with pytest.raises(ValueError, match="seam_spacing: expected 0.01 to 2 hexagonal spacings, got 5"):
        bt.wang_tiles(points=4, seam_spacing=5)
    with pytest.raises(ValueError, match="lattice_step: expected 0.0001 to 0.1 hexagonal spacings, got 0.5"):
        bt.wang_tiles(points=4, lattice_step=0.5)
    with pytest.raises(ValueError, match="lattice_steps_per_iteration"):
        bt.wang_tiles(points=4, lattice_steps_per_iteration=-1)
    # float32 input is taken exactly; a strided view is read as it is.
    pts32 = bt.random_points(30).astype(np.float32)
    assert np.array_equal(bt.relax(pts32, iterations=0, engine="exact"), pts32.astype(np.float64))
    wide = np.zeros((30, 4))
    wide[:, ::2] = pts32
    assert np.array_equal(bt.relax(wide[:, ::2], iterations=0, engine="exact"), pts32.astype(np.float64))
    # The library's errors carry the tool's message (the tool prints "bluetile: " before it).
    damaged = tmp_path / "damaged.txt"
    damaged.write_text("0.1 0.2\n0.3 inf\n")
    cli = tool("relax", "--input", damaged, "--iterations", 1, "--output", tmp_path / "o.txt", check=False)
    assert cli.returncode != 0
    with pytest.raises(bt.Error) as error:
        bt.load_table(str(damaged))
    assert cli.stderr.strip() == "bluetile: " + str(error.value)
    assert isinstance(error.value, ValueError)


def test_a_lone_points_nearest_neighbour_is_its_own_copy():
    # Periodic images count (analysis/nearest_neighbour.h): one point is one period from itself.
    assert bt.nearest_neighbour_distances(np.array([[0.25, 0.75]])).tolist() == [1.0]
    assert bt.nearest_neighbour_distances([[0.25, 0.75], [0.25, 0.25]]).tolist() == [0.5, 0.5]
    # The statistics of analyze need two.
    with pytest.raises(ValueError, match=r"^points: analysis needs at least 2 points per set$"):
        bt.analyze(np.array([[0.25, 0.75]]))


def test_functions_and_results_pickle():
    # The functions pickled as "cannot pickle nanobind.nb_func objects", so that they could not be
    # sent to another process; now by name, as Python's built-in functions.
    for protocol in range(pickle.HIGHEST_PROTOCOL + 1):
        assert pickle.loads(pickle.dumps(bt.relax, protocol=protocol)) is bt.relax
    from concurrent.futures import ProcessPoolExecutor
    with ProcessPoolExecutor(max_workers=1) as pool:
        assert all(np.array_equal(got, bt.random_points(n, seed=4))
                   for n, got in zip((3, 5), pool.map(bt.random_points, (3, 5), (4, 4))))
    # Results are plain dicts, tuples, lists and arrays.
    points, history = bt.relax(count=10, iterations=2, engine="exact", history=True)
    back_points, back_history = pickle.loads(pickle.dumps((points, history)))
    assert np.array_equal(back_points, points) and set(back_history) == set(history)
    window = bt.tile((0.0, 0.0, 1.0, 1.0), density=20, columns=True)
    assert np.array_equal(pickle.loads(pickle.dumps(window))["rank"], window["rank"])
    assert str(pickle.loads(pickle.dumps(bt.Error("a message")))) == "a message"


def test_the_gil_is_released_while_relaxing():
    counter = 0
    stop = False

    def count():
        nonlocal counter
        while not stop:
            counter += 1
            time.sleep(0)

    thread = threading.Thread(target=count)
    thread.start()
    try:
        time.sleep(0.05)
        before = counter
        # About 0.15 s here (2000 sites for 40 iterations, the size this test had, took 0.02 s once the
        # exact engine kept its triangulation: too short to count on).
        bt.relax(count=20000, iterations=40, seed=1, engine="exact")
        during = counter - before
    finally:
        stop = True
        thread.join()
    # With the GIL held the other thread could not run at all during the call.
    assert during > 100, f"the counting thread ran {during} times while relax ran"


FORKED_WORKERS = """
import multiprocessing, sys
import numpy as np
import pybluetile as bt

def relaxed(seed):
    return bt.relax(count=5000, iterations=3, seed=seed, engine="exact")

bt.set_thread_count(2)
here = [relaxed(seed) for seed in range(4)]  # the library's worker threads are running now
with multiprocessing.get_context("fork").Pool(2) as pool:
    there = pool.map_async(relaxed, range(4)).get(timeout=60)
print("same" if all(np.array_equal(a, b) for a, b in zip(here, there)) else "differ", flush=True)
"""


def test_processes_forked_after_a_call_relax_as_the_parent_does():
    # multiprocessing's default on Linux forks: the children inherited the library's thread pool
    # without its threads, and their first call waited for them forever.
    child = subprocess.run([sys.executable, "-c", FORKED_WORKERS], capture_output=True, text=True, timeout=120)
    assert child.returncode == 0, child.stderr[-2000:]
    assert child.stdout == "same\n"


@pytest.mark.skipif(len(os.sched_getaffinity(0)) < 2, reason="one CPU: the affinity and the machine agree")
def test_the_default_thread_count_is_the_cpus_the_process_may_run_on():
    # As nproc counts them: taskset, cpusets and batch schedulers restrict the affinity mask.
    code = ("import os\n"
            "os.sched_setaffinity(0, {min(os.sched_getaffinity(0))})\n"
            "import pybluetile as bt\n"
            "print(bt.thread_count())\n")
    env = {k: v for k, v in os.environ.items() if k != "BLUETILE_THREADS"}
    child = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60, env=env)
    assert child.returncode == 0, child.stderr[-2000:]
    assert child.stdout == "1\n"


def tile_set_body(text):
    """A tile-set file from its '# set' line on: the tiles, without the header that names the maker."""
    return text[text.index("# set "):]


def test_wang_tiles_match_the_tool(tool, tmp_path):
    out = tmp_path / "set.tiles"
    tool("wang", "--set", "wang8", "--points", 8, "--iterations", 3, "--warm", 2, "--levels", 2, "--ratio", 2,
         "--strategy", "instances", "--period", 4, "--lattice-steps", 3, "--lattice-steps-per-iteration", 2, "--lattice-step", 0.01, "--seam-steps", 5, "--seam-spacing", 0.75,
         "--level-seam-spacing", 0.6, "--rank-order", "farthest", "--engine", "exact", "--seed", 3, "--output", out)
    text = bt.wang_tiles("wang8", points=8, iterations=3, warm=2, levels=2, ratio=2, strategy="instances", period=4,
                         lattice_steps=3, lattice_steps_per_iteration=2, lattice_step=0.01, seam_steps=5, seam_spacing=0.75,
                         level_seam_spacing=0.6, rank_order="farthest", seed=3)
    assert tile_set_body(text) == tile_set_body(out.read_text())
    tiles = bt.tile_set(text)
    assert tiles["kind"] == "wang8" and len(tiles["tiles"]) == 8
    for t in tiles["tiles"]:
        assert t["points"].shape == (16, 2)
        assert sorted(t["ranks"].tolist()) == list(range(16))
        assert np.array_equal(np.bincount(t["levels"]), [8, 8])
        assert np.all((t["points"] >= 0) & (t["points"] < 1))
    # A path reads the same set.
    assert np.array_equal(bt.tile_set(str(out))["tiles"][5]["points"], tiles["tiles"][5]["points"])
    # The voids order too, and bad orders are refused by name.
    tool("wang", "--set", "wang8", "--points", 8, "--iterations", 3, "--warm", 2, "--levels", 2, "--ratio", 2,
         "--rank-order", "voids", "--void-sigma", 0.6, "--engine", "exact", "--seed", 3, "--output", out)
    voids = bt.wang_tiles("wang8", points=8, iterations=3, warm=2, levels=2, ratio=2, rank_order="voids", void_sigma=0.6, seed=3)
    assert tile_set_body(voids) == tile_set_body(out.read_text())
    assert tile_set_body(voids) != tile_set_body(bt.wang_tiles("wang8", points=8, iterations=3, warm=2, levels=2, ratio=2, seed=3))
    # The fill order: levels after the first filled, the same bits as the tool's.
    tool("wang", "--set", "wang8", "--points", 8, "--iterations", 3, "--warm", 2, "--levels", 2, "--ratio", 2,
         "--rank-order", "fill", "--engine", "exact", "--seed", 3, "--output", out)
    fill = bt.wang_tiles("wang8", points=8, iterations=3, warm=2, levels=2, ratio=2, rank_order="fill", seed=3)
    assert tile_set_body(fill) == tile_set_body(out.read_text())
    with pytest.raises(ValueError, match="rank_order"):
        bt.wang_tiles("wang8", points=8, rank_order="random")
    # The filled levels' lattice steps: the tool's options, the same bits; 0 steps is the fill alone.
    tool("wang", "--set", "wang8", "--points", 8, "--iterations", 3, "--warm", 2, "--levels", 3, "--ratio", 2,
         "--filled-lattice-steps", 7, "--filled-lattice-spacing", 0.6, "--filled-lattice-up-to", 16,
         "--engine", "exact", "--seed", 3, "--output", out)
    stepped = bt.wang_tiles("wang8", points=8, iterations=3, warm=2, levels=3, ratio=2, filled_lattice_steps=7,
                            filled_lattice_spacing=0.6, filled_lattice_up_to=16, seed=3)
    assert tile_set_body(stepped) == tile_set_body(out.read_text())
    assert "filled_lattice_steps=7" in stepped
    alone = bt.wang_tiles("wang8", points=8, iterations=3, warm=2, levels=3, ratio=2, filled_lattice_steps=0, seed=3)
    assert tile_set_body(alone) != tile_set_body(stepped)
    for name, value in (("filled_lattice_steps", -1), ("filled_lattice_spacing", 3.0), ("filled_lattice_up_to", 0)):
        with pytest.raises(ValueError, match=name):
            bt.wang_tiles("wang8", points=8, levels=2, **{name: value})
    # corner81: the default strategy is instances for it, as the tool's, and the same bits.
    tool("wang", "--set", "corner81", "--points", 4, "--iterations", 2, "--warm", 1, "--levels", 2, "--seed", 3,
         "--output", out)
    corner = bt.wang_tiles("corner81", points=4, iterations=2, warm=1, levels=2, seed=3)
    assert tile_set_body(corner) == tile_set_body(out.read_text())
    assert "strategy='instances'" in corner
    assert len(bt.tile_set(corner)["tiles"]) == 81
    with pytest.raises(ValueError, match="wang8, wang16, corner16, corner81"):
        bt.wang_tiles("corner64", points=4)


def test_tile_matches_the_tool(tool, tmp_path):
    out = tmp_path / "window.txt"
    region = (-3.5, -2.0, 4.25, 3.0)
    tool("tile", "--region", *region, "--density", 40, "--seed", 7, "--columns", "x,y,i,j,tile,level,rank",
         "--output", out)
    from_tool = np.loadtxt(out, comments="#", ndmin=2)
    got = bt.tile(region, density=40, seed=7, columns=True)
    assert len(got["points"]) > 100
    assert np.array_equal(got["points"], from_tool[:, :2])
    for c, name in enumerate(("i", "j", "tile", "level", "rank")):
        assert np.array_equal(got[name], from_tool[:, 2 + c]), name
    # Overlapping windows agree on their overlap, bit for bit.
    left = bt.tile((-3.5, -2.0, 1.0, 3.0), density=40, seed=7)
    inside = got["points"][got["points"][:, 0] < 1.0]
    assert np.array_equal(np.sort(left.view("f8,f8"), axis=0), np.sort(inside.copy().view("f8,f8"), axis=0))


def test_tile_fits_a_density_map_as_the_tool(tool, tmp_path):
    # A uniform 4 x 4 map on a 2:1 region: 'contain' fills only its square [0.5, 1.5] x [0, 1] (the
    # bilinear step reaches half a texel, 1/8, beyond), as `bluetile tile --fit contain` does.
    white = tmp_path / "white.pgm"
    white.write_text("P2\n4 4\n255\n" + "255 255 255 255\n" * 4)
    for fit in ("contain", "cover", "stretch"):
        out = tmp_path / f"{fit}.txt"
        tool("tile", "--region", 0, 0, 2, 1, "--density-map", white, "--transfer", "linear", "--max-density", 400,
             "--fit", fit, "--seed", 3, "--output", out)
        got = bt.tile((0, 0, 2, 1), density_map=np.ones((4, 4)), max_density=400, fit=fit, seed=3)
        assert np.array_equal(got, np.loadtxt(out, comments="#", ndmin=2)), fit
    contained = bt.tile((0, 0, 2, 1), density_map=np.ones((4, 4)), max_density=400, seed=3)
    assert contained[:, 0].min() >= 0.5 - 0.125 and contained[:, 0].max() <= 1.5 + 0.125
    with pytest.raises(ValueError, match="fit"):
        bt.tile((0, 0, 2, 1), density_map=np.ones((4, 4)), max_density=400, fit="fill")


def test_tile_follows_a_density_map():
    # Dense on the left column of the map, empty on the right: row 0 is the top.
    density_map = np.array([[1.0, 0.0], [1.0, 0.0]])
    points = bt.tile((0, 0, 8, 8), density_map=density_map, max_density=30, seed=2)
    left = np.count_nonzero(points[:, 0] < 2)
    right = np.count_nonzero(points[:, 0] > 6)
    assert left > 20 * max(right, 1)
    with pytest.raises(ValueError, match="density_map"):
        bt.tile((0, 0, 1, 1), density_map=np.array([[-1.0]]), max_density=10)
    with pytest.raises(ValueError, match="region"):
        bt.tile((0, 0, -1, 1))
    with pytest.raises(bt.Error, match="more than tiles"):
        bt.tile((0, 0, 1, 1), tile_size=1.0, density=1e9)


def test_an_interrupt_during_the_first_call_is_keyboard_interrupt(tmp_path):
    # A fresh interpreter, as a script's first call: Ctrl-C during the long call arrives as
    # KeyboardInterrupt when the call returns (it was a TypeError from nanobind's lazy NumPy
    # import before pybluetile imported NumPy itself).
    script = tmp_path / "first_call.py"
    script.write_text(
        "import pybluetile as bt\n"
        "print('ready', flush=True)\n"
        "try:\n"
        "    bt.progressive(count=2500, levels=3, ratio=2, rank_order='fill')\n"
        "except KeyboardInterrupt:\n"
        "    print('interrupted', flush=True)\n")
    child = subprocess.Popen([sys.executable, str(script)], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                             preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    assert child.stdout.readline() == "ready\n"
    time.sleep(0.2)
    child.send_signal(signal.SIGINT)
    out, err = child.communicate(timeout=120)
    assert out == "interrupted\n", (child.returncode, err)


def assert_ctrl_c_ends(call, after, within):
    """A SIGINT `after` seconds into `call` raises KeyboardInterrupt within `within` seconds. Python's
    own handler is installed for it: a run started in the background (nohup, `cmd &`) inherits
    SIGINT ignored, and Python then installs none."""
    def interrupt():
        time.sleep(after)
        os.kill(os.getpid(), signal.SIGINT)

    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        threading.Thread(target=interrupt).start()
        started = time.monotonic()
        with pytest.raises(KeyboardInterrupt):
            call()
        assert time.monotonic() - started < within
    finally:
        signal.signal(signal.SIGINT, previous)


@pytest.mark.parametrize("call", [
    lambda: bt.relax(count=100000, iterations=100000, engine="exact"),
    lambda: bt.progressive(count=50000, levels=3, iterations=100000, engine="exact"),
    # Calls without iterations ran to their end (psa's RDF spectrum: about 8 minutes on 2 cores;
    # dart: minutes): the library's loops now run Python's signal handlers now and then.
    lambda: bt.analyze(np.random.default_rng(7).random((300000, 2))),
    lambda: bt.dart(5 * 10**6),
])
def test_ctrl_c_ends_a_long_call(call):
    # Long calls ran to their last iteration before a Ctrl-C was seen; as asked they take hours.
    assert_ctrl_c_ends(call, after=0.5, within=60)


def test_ctrl_c_ends_the_filled_levels_lattice_steps():
    # The steps of a filled level come after its last fill round (whose callback answered Ctrl-C):
    # asked for 100000 of them (about 2 minutes here), the call now ends within a step. The signal
    # comes after 4 s, when level 0 and the fill (about 1.5 s) are done.
    assert_ctrl_c_ends(
        lambda: bt.wang_tiles("corner81", points=16, iterations=1, warm=0, levels=2, filled_lattice_steps=100000),
        after=4, within=30)
