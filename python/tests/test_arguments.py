"""Every numeric argument of every function: a bad value raises a ValueError naming the argument
(a value that is not an integer where one is asked for, a TypeError naming it), before any work.
The arguments are read from the functions' own signatures, so a new one is covered without a new
test. Paths and arrays: os.PathLike paths and sequences of numbers are taken, anything else is
refused by name."""
import math
import os
import re
import shutil
import subprocess
import sys
import time

import numpy as np
import pytest

import pybluetile as bt

# The smallest valid call of each function; the argument under test is added to it.
CALLS = {
    "relax": ((), {"count": 10, "iterations": 1, "engine": "exact"}),
    "stipple": ((np.ones((4, 4)),), {"count": 10, "iterations": 1}),
    "progressive": ((), {"count": 8, "levels": 2, "iterations": 1, "engine": "exact"}),
    "dart": ((10,), {}),
    "wang_tiles": ((), {"points": 2, "iterations": 1, "warm": 0, "lattice_steps": 0, "lattice_steps_per_iteration": 0,
                        "seam_steps": 0, "strategy": "rounds"}),
    "tile": (((0.0, 0.0, 1.0, 1.0),), {}),
    "analyze": ((np.random.default_rng(1).random((20, 2)),), {"psa_measures": False, "discrepancy": False}),
    "centroids": ((np.random.default_rng(2).random((20, 2)),), {"engine": "exact"}),
    "random_points": ((5,), {}),
    "periodogram": ((np.random.default_rng(3).random((20, 2)),), {}),
    "radial_power": ((np.random.default_rng(4).random((20, 2)),), {}),
}
# Values valid for an argument although they are bad for most: any unsigned 64-bit seed or set.
ALSO_VALID = {"seed": {10**15, 2**63 + 1}, "set": {10**15, 2**63 + 1}}


def numeric_arguments(function):
    signature = function.__nb_signature__[0][0]
    keyword_part = signature.split("*,", 1)[1] if "*," in signature else signature
    return re.findall(r"(\w+): (int|float) =", keyword_part)


CASES = [(name, argument, kind) for name in CALLS for argument, kind in numeric_arguments(getattr(bt, name))]


def test_the_table_covers_every_function_with_numeric_arguments():
    assert len(CASES) > 30
    assert {name for name, _, _ in CASES} == set(CALLS)


@pytest.mark.parametrize("name,argument,kind", CASES)
def test_bad_values_are_refused_naming_the_argument(name, argument, kind):
    args, kwargs = CALLS[name]
    # -1 and 2**64 were nanobind's TypeError listing the signature, where the binding took an
    # unsigned or narrower C++ integer; 2**63 + 1 named another value (2**62) in the message.
    bad = [math.nan, math.inf, -math.inf, -1.0] if kind == "float" else [-1, 10**15, 2**63 + 1, 2**64, -2**70]
    for value in bad:
        if value in ALSO_VALID.get(argument, set()):
            continue
        try:
            getattr(bt, name)(*args, **{**kwargs, argument: value})
        except ValueError as e:
            assert argument in str(e) or argument.replace("_", " ") in str(e), (name, argument, value, str(e))
            if kind == "int":
                assert str(e).startswith(f"{argument}: expected ") and str(e).endswith(f", got {value}"), str(e)
        else:
            pytest.fail(f"{name}({argument}={value!r}) was accepted")
    if kind == "int":
        with pytest.raises(TypeError, match=rf"^{argument}: expected an integer, got float$"):
            getattr(bt, name)(*args, **{**kwargs, argument: 2.5})


def test_sizes_past_the_tools_limits_are_refused_not_a_memory_error():
    # The tool refuses these before any work; the module ran out of memory (std::bad_alloc) or
    # swapped instead.
    with pytest.raises(bt.Error, match=r"^region 0 0 1000000 1000000 holds about 100000000000000 points \(100 per "
                                       r"unit area\), more than the limit of 100000000 points"):
        bt.tile((0.0, 0.0, 1e6, 1e6), density=100)
    with pytest.raises(bt.Error, match=r"more than the limit of 100000000 tiles: use a larger tile_size"):
        bt.tile((0.0, 0.0, 2e4, 2e4), tile_size=1, density=1e-6)
    with pytest.raises(ValueError, match=r"^count: expected 0 to 100000000, got 1000000000000$"):
        bt.random_points(10**12)
    assert bt.random_points(0).shape == (0, 2)


def test_analysis_refuses_points_outside_the_torus_as_the_tool_does():
    # (1, 1) was wrapped onto (0, 0) without a word: rho 0 from a pair that is not there.
    points = np.array([[0.0, 0.0], [1.0, 1.0], [0.5, 0.5]])
    for function in (bt.analyze, bt.periodogram, bt.radial_power, bt.nearest_neighbour_distances):
        with pytest.raises(ValueError, match=r"^points\[1\]: x = 1 is outside \[0, 1\) \(points % 1.0 % 1.0 wraps them"):
            function(points)
    assert bt.analyze(points % 1.0 % 1.0, psa_measures=False, discrepancy=False)["rho"] == 0.0  # wrapped by the caller


def test_the_wrapping_the_refusal_suggests_is_accepted():
    # The hint said "points % 1.0", but -1e-17 % 1.0 is 1.0, which was refused again.
    for x in (-1e-17, -0.0, 1.0, 1.5, -2.5, 3.0 - 2**-51):
        points = np.array([[x, 0.5], [0.25, 0.25]])
        if not 0.0 <= x < 1.0:
            with pytest.raises(ValueError, match=r"\(points % 1.0 % 1.0 wraps them onto the torus"):
                bt.periodogram(points)
        assert bt.periodogram(points % 1.0 % 1.0).shape == (14, 14), x
    # relax and centroids wrap, as the tool wraps point files it relaxes.
    bt.centroids(np.array([[1.25, 0.5], [0.5, 0.5]]), engine="exact")


def test_messages_quoting_bytes_that_are_not_utf8_keep_their_text(tmp_path):
    # The Error had no message at all: its text quoted the file's bytes \xff\xfe (which now read
    # as UTF-16's byte order mark, with their own message: \xff\xff is no encoding's).
    path = tmp_path / "b.txt"
    path.write_bytes(b"\xff\xff0.1 0.2\n")
    with pytest.raises(bt.Error) as caught:
        bt.load_table(str(path))
    assert str(caught.value) == f"{path}:1: not a number '\ufffd\ufffd0.1'"


def test_fixed_out_of_range_names_the_range():
    # A negative count said "fixed: -1 is more than the 5 points".
    for fixed in (-1, 6):
        with pytest.raises(ValueError, match=rf"^fixed: expected 0 to 5 \(the points\), got {fixed}$"):
            bt.relax(count=5, iterations=1, fixed=fixed, engine="exact")


def test_seeds_take_the_tools_range(tool, tmp_path):
    # A negative seed was nanobind's TypeError listing the signature; the tool refuses it too.
    cli = tool("relax", "--count", 5, "--iterations", 0, "--seed", -1, "--output", tmp_path / "p.txt", check=False)
    assert cli.returncode != 0 and "expected an integer from 0 to 18446744073709551615" in cli.stderr
    for value in (-1, 2**64):
        with pytest.raises(ValueError, match=rf"^seed: expected 0 to 18446744073709551615, got {value}$"):
            bt.relax(count=5, iterations=0, seed=value, engine="exact")
        with pytest.raises(ValueError, match=rf"^seed: expected 0 to 18446744073709551615, got {value}$"):
            bt.random_points(5, seed=value)
    with pytest.raises(ValueError, match=r"^set: expected 0 to 18446744073709551615, got -1$"):
        bt.random_points(5, set=-1)
    # The largest is the tool's largest, the same points; NumPy's integers are integers.
    tool("relax", "--count", 5, "--iterations", 0, "--seed", 2**64 - 1, "--engine", "exact",
         "--output", tmp_path / "p.txt")
    top = bt.random_points(5, seed=2**64 - 1)
    assert np.array_equal(top, np.loadtxt(tmp_path / "p.txt", comments="#"))
    assert np.array_equal(bt.random_points(np.int64(5), seed=np.uint64(2**64 - 1)), top)


def test_counts_out_of_range_name_their_value():
    # Each was nanobind's TypeError listing the signature, or named another value.
    with pytest.raises(ValueError, match=r"^count: expected 1 to 1024 threads, got -1$"):
        bt.set_thread_count(-1)
    with pytest.raises(ValueError, match=r"^levels: expected 1 to 32, got -1$"):
        bt.wang_tiles(points=4, levels=-1)
    with pytest.raises(ValueError, match=r"^count: expected 1 to 100000000, got -1$"):
        bt.dart(-1)
    with pytest.raises(ValueError, match=r"^size: expected 0 \(from N\) or an even number 2 to 65536, got 1000000$"):
        bt.periodogram(np.random.default_rng(1).random((10, 2)), size=10**6)  # 8 TB: a MemoryError before
    with pytest.raises(TypeError, match=r"^count: expected an integer, got float$"):
        bt.random_points(10.0)


def test_dart_max_failures_is_refused_past_the_tools_limit():
    # Past 10^9 rejections in a row a run would not end (the library's limit, as --max-failures);
    # past 2**63 the message named 4611686018427387904 instead of the value given.
    for value in (0, 10**9 + 1, 2**62, 2**63, 2**64 - 1, 2**64):
        with pytest.raises(ValueError, match=rf"^max_failures: expected 1 to 1000000000, got {value}$"):
            bt.dart(10, max_failures=value)
    assert bt.dart(10, max_failures=1).shape == (10, 2)


def test_paths_may_be_os_pathlike(tmp_path):
    # A pathlib.Path (tmp_path is one) was nanobind's TypeError listing the signature ("incompatible
    # function arguments").
    points = bt.random_points(16, seed=2)
    bt.save_table(tmp_path / "p.npy", points)
    (back,) = bt.load_table(tmp_path / "p.npy")
    assert np.array_equal(back, points)
    (back,) = bt.load_table(bytes(tmp_path / "p.npy"))
    assert np.array_equal(back, points)
    text = bt.wang_tiles(**CALLS["wang_tiles"][1])
    (tmp_path / "set.tiles").write_text(text)
    assert np.array_equal(bt.tile_set(tmp_path / "set.tiles")["tiles"][3]["points"], bt.tile_set(text)["tiles"][3]["points"])
    assert np.array_equal(bt.tile((0.0, 0.0, 2.0, 2.0), tiles=tmp_path / "set.tiles", tile_size=1.0),
                          bt.tile((0.0, 0.0, 2.0, 2.0), tiles=text, tile_size=1.0))
    with pytest.raises(TypeError, match=r"^path: expected a str or os.PathLike path, got int$"):
        bt.load_table(3)
    with pytest.raises(TypeError, match=r"^tiles: expected a str or os.PathLike path, got list$"):
        bt.tile_set([text])
    with pytest.raises(ValueError, match=r"^path: embedded null character$"):
        bt.save_table(str(tmp_path / "a\0b.npy"), points)


def test_sequences_of_numbers_are_arrays():
    # A list was nanobind's TypeError listing the signature: now read as NumPy reads it.
    points = bt.random_points(12, seed=3)
    assert np.array_equal(bt.relax(points.tolist(), iterations=2, engine="exact"),
                          bt.relax(points, iterations=2, engine="exact"))
    assert np.array_equal(bt.relax([[0, 0], [0.5, 0.5]], iterations=0, engine="exact"), [[0, 0], [0.5, 0.5]])
    assert np.array_equal(bt.centroids(tuple(map(tuple, points)), engine="exact")[1], bt.centroids(points, engine="exact")[1])
    assert np.array_equal(bt.nearest_neighbour_distances(points.tolist()), bt.nearest_neighbour_distances(points))
    density = [[1, 0.5], [0.25, 1]]
    assert np.array_equal(bt.stipple(density, count=10, iterations=1), bt.stipple(np.array(density), count=10, iterations=1))
    base, levels = bt.progressive(count=6, levels=2, iterations=1, engine="exact")
    more, _ = bt.progressive(base.tolist(), levels.tolist(), add=3, iterations=1, engine="exact")
    assert np.array_equal(more, bt.progressive(base, levels, add=3, iterations=1, engine="exact")[0])


def test_arrays_in_the_other_byte_order_are_read_as_their_values(tmp_path):
    # A big-endian array (a FITS catalogue, np.fromfile of another machine's file) was refused:
    # "expected float64 (or float32) values, got >f8".
    points = bt.random_points(12, seed=3)
    swapped = points.astype(">f8")
    assert np.array_equal(bt.relax(swapped, iterations=2, engine="exact"), bt.relax(points, iterations=2, engine="exact"))
    assert np.array_equal(bt.nearest_neighbour_distances(points.astype(">f4")),
                          bt.nearest_neighbour_distances(points.astype(np.float32)))
    density = np.array([[1, 0.5], [0.25, 1]])
    assert np.array_equal(bt.stipple(density.astype(">f8"), count=10, iterations=1), bt.stipple(density, count=10, iterations=1))
    levels = np.array([0, 0, 1, 1], dtype=">i8")
    bt.save_table(tmp_path / "swapped.npy", points[:4], levels=levels)
    bt.save_table(tmp_path / "native.npy", points[:4], levels=levels.astype(np.int64))
    assert (tmp_path / "swapped.npy").read_bytes() == (tmp_path / "native.npy").read_bytes()


def test_what_is_not_an_array_is_refused_by_name(tmp_path):
    expected = r"points: expected an array of shape \(N, 2\) or \(K, N, 2\), or a sequence of \[x, y\] pairs"
    with pytest.raises(TypeError, match=rf"^{expected}, got str$"):
        bt.relax("0.5 0.5", engine="exact")
    with pytest.raises(ValueError, match=rf"^{expected}; NumPy cannot read this list as numbers \(.*inhomogeneous"):
        bt.analyze([[0.1, 0.2], [0.3]])
    with pytest.raises(ValueError, match=r"^points: expected shape \(N, 2\) or \(K, N, 2\) with N >= 1, got \(2,\)$"):
        bt.centroids([0.5, 0.5], engine="exact")
    with pytest.raises(TypeError, match=r"^points: expected float64 \(or float32\) values, got object"):
        bt.centroids(np.array([[0.5, 0.5]], dtype=object), engine="exact")
    with pytest.raises(TypeError, match=r"^levels: expected an array of whole numbers of shape \(N,\), or a sequence of "
                                        r"them, got int$"):
        bt.save_table(tmp_path / "l.npy", bt.random_points(4), levels=-1)
    with pytest.raises(TypeError, match=r"^levels: expected integer values, got float64$"):
        bt.save_table(tmp_path / "l.npy", bt.random_points(4), levels=[0.5, 1, 1, 1])
    with pytest.raises(TypeError, match=r"^density_map: expected a 2-D array of densities \(rows, columns\), or a sequence "
                                        r"of rows, got float$"):
        bt.relax(count=5, density_map=1.0)


def test_save_table_names_its_format_argument(tmp_path):
    # Both messages named the tool's --format, which a Python caller never passed.
    points = bt.random_points(4)
    with pytest.raises(bt.Error, match=r"^format: expected one of 'text', 'npy', 'binary', 'header', 'csv', got 'png'$"):
        bt.save_table(tmp_path / "t.npy", points, format="png")
    with pytest.raises(bt.Error) as caught:
        bt.save_table(tmp_path / "t.png", points)
    assert str(caught.value) == (f"{tmp_path / 't.png'}: unknown extension '.png' (.txt .dat .pts: text, .npy: npy, "
                                 ".bpt: binary, .h .hpp: header, .csv: csv; or pass format=)")
    assert not (tmp_path / "t.png").exists()
    bt.save_table(tmp_path / "t.png", points, format="npy")
    assert np.array_equal(np.load(tmp_path / "t.png")[0], points)


def test_save_table_refuses_options_its_format_ignores(tmp_path):
    # float32 for a text table and name for anything but a C header were ignored without a word.
    points = bt.random_points(4)
    with pytest.raises(bt.Error, match=r"^float32: .*t\.txt is text; 4-byte floats are for npy and binary tables$"):
        bt.save_table(tmp_path / "t.txt", points, float32=True)
    with pytest.raises(bt.Error, match=r"^name: .*t\.npy is npy; the array name is for C headers \(\.h, \.hpp\)$"):
        bt.save_table(tmp_path / "t.npy", points, name="table")
    assert list(tmp_path.iterdir()) == []
    bt.save_table(tmp_path / "t.bpt", points, float32=True)
    bt.save_table(tmp_path / "t.h", points, name="table")
    # A comment was dropped without a word where the format holds none.
    for name, kind in (("c.npy", "npy"), ("c.bpt", "binary")):
        with pytest.raises(bt.Error, match=rf"^comment: .*{name} is {kind}; comment lines are for text and CSV tables and C headers$"):
            bt.save_table(tmp_path / name, points, comment=["made here"])
        assert not (tmp_path / name).exists()
    bt.save_table(tmp_path / "c.txt", points, comment=["made here"])
    bt.save_table(tmp_path / "c.h", points, comment=["made here"])
    assert "made here" in (tmp_path / "c.txt").read_text() and "made here" in (tmp_path / "c.h").read_text()


def test_raster_settings_with_the_exact_engine_are_refused():
    # As the tool refuses them: they changed nothing, an absent device included.
    points = bt.random_points(20)
    with pytest.raises(ValueError, match=r"^resolution=100: a raster engine setting, and the exact engine runs here; "
                                         r'engine="raster" uses it$'):
        bt.centroids(points, engine="exact", resolution=100)
    with pytest.raises(ValueError, match=r"^device='7': a raster engine setting"):
        bt.relax(count=20, iterations=1, engine="exact", device="7")
    with pytest.raises(ValueError, match=r"^pixel_work='device': a raster engine setting"):
        bt.relax(count=20, iterations=1, bounded=True, pixel_work="device")  # exact: the default when bounded
    with pytest.raises(ValueError, match=r"^coverage='point': a raster engine setting"):
        bt.stipple(np.ones((4, 4)), count=10, iterations=1, coverage="point")  # exact by default
    assert bt.relax(count=20, iterations=1, engine="exact", coverage="area").shape == (20, 2)  # the default value


def test_the_fill_order_refuses_what_it_would_ignore(tool, tmp_path):
    # The fill order relaxes nothing and runs no engine; iterations, placement and the rest were
    # ignored without a word, where the tool refuses them.
    cli = tool("progressive", "--count", 10, "--rank-order", "fill", "--iterations", 7, "-o", tmp_path / "p.txt",
               check=False)
    assert cli.returncode != 0 and "--rank-order fill relaxes nothing and runs no engine" in cli.stderr
    settings = {"iterations": (7, "7"), "tolerance": (0.5, "0.5"), "placement": ("random", "'random'"),
                "engine": ("exact", "'exact'"), "resolution": (64, "64"), "coverage": ("point", "'point'"),
                "cone": ("fan", "'fan'"), "device": ("0", "'0'"), "pixel_work": ("host", "'host'")}
    for argument, (value, text) in settings.items():
        with pytest.raises(ValueError, match=rf"^{argument}={re.escape(text)}: rank_order='fill' relaxes nothing and "
                                             r"runs no engine; this is for the orders that relax \('voids', 'placement'\)$"):
            bt.progressive(count=10, rank_order="fill", **{argument: value})
    # The defaults, given or not, are the same call; the tool's points bit for bit.
    tool("progressive", "--count", 10, "--rank-order", "fill", "-o", tmp_path / "f.txt")
    points, levels = bt.progressive(count=10, rank_order="fill", iterations=80, placement="gaps", engine="raster")
    assert np.array_equal(points, np.loadtxt(tmp_path / "f.txt", comments="#")[:, :2])
    assert bt.progressive(count=10, levels=2, iterations=7, placement="random", engine="exact")[0].shape == (20, 2)


def test_tile_refuses_a_fit_without_a_map(tool, tmp_path):
    # fit placed nothing without a density_map and was ignored; the tool refuses --fit alone.
    cli = tool("tile", "--region", 0, 0, 2, 2, "--density", 100, "--fit", "cover", "-o", tmp_path / "t.txt", check=False)
    assert cli.returncode != 0 and "--fit cover places a --density-map: give one" in cli.stderr
    for fit in ("cover", "stretch"):
        with pytest.raises(ValueError, match=rf"^fit='{fit}' places a density_map: give one$"):
            bt.tile((0.0, 0.0, 2.0, 2.0), density=100, fit=fit)
    assert bt.tile((0.0, 0.0, 2.0, 2.0), density=100, fit="contain").shape[1] == 2
    assert bt.tile((0.0, 0.0, 2.0, 2.0), density_map=np.ones((2, 2)), count=50, fit="cover").shape[1] == 2


def test_relax_refuses_a_seed_or_weight_exponent_that_would_change_nothing():
    # The seed draws only a random start, and the exponent weights only a map's cells: with
    # points given, or no map, they were ignored without a word.
    points = bt.random_points(10)
    with pytest.raises(ValueError, match=r"^seed=7: only with count \(it draws the random start; the points given are "
                                         r"the start\)$"):
        bt.relax(points, seed=7, iterations=1, engine="exact")
    with pytest.raises(ValueError, match=r"^weight_exponent=3 weights the cells by a density_map: give one$"):
        bt.relax(count=5, weight_exponent=3, iterations=1, engine="exact")
    with pytest.raises(ValueError, match=r"^weight_exponent=0.5 weights the cells by a density_map: give one$"):
        bt.relax(points, weight_exponent=0.5, iterations=1, engine="exact")
    assert np.array_equal(bt.relax(points, seed=1, iterations=1, engine="exact"), bt.relax(points, iterations=1, engine="exact"))
    assert bt.relax(count=5, seed=7, weight_exponent=3, density_map=np.ones((2, 2)), iterations=1).shape == (5, 2)


def test_wang_tiles_refuses_settings_the_call_would_not_use(tool, tmp_path):
    # void_sigma with the fill order, ratio with one level, period without the instances strategy
    # and the rest were ignored without a word, where the tool refuses them.
    cli = tool("wang", "--points", 8, "--void-sigma", 0.7, "-o", tmp_path / "t.tiles", check=False)
    assert cli.returncode != 0
    assert "--void-sigma 0.7: only with --rank-order voids (this run: --rank-order fill)" in cli.stderr
    small = {"points": 8, "iterations": 1, "warm": 0}
    cases = [
        ({"ratio": 3}, r"ratio=3: only with levels=2 or more \(this call: levels=1\)"),
        ({"period": 6}, r"period=6: only with strategy='instances' \(this call: strategy='auto', exact for wang8\)"),
        ({"void_sigma": 0.7}, r"void_sigma=0.7: only with rank_order='voids' \(this call: rank_order='fill'\)"),
        ({"lattice_steps": 0, "lattice_steps_per_iteration": 0, "lattice_step": 0.01},
         r"lattice_step=0.01: only with lattice_steps or lattice_steps_per_iteration above 0 \(this call: "
         r"lattice_steps=0, lattice_steps_per_iteration=0\)"),
        ({"seam_steps": 0, "seam_spacing": 0.7}, r"seam_spacing=0.7: only with seam_steps above 0 \(this call: seam_steps=0\)"),
        ({"levels": 2, "level_seam_spacing": 0.7},
         r"level_seam_spacing=0.7: only with seam_steps above 0, levels=2 or more and rank_order='farthest' or "
         r"'voids', whose later levels are relaxed, not filled \(this call: seam_steps=20, levels=2, rank_order='fill'\)"),
        ({"filled_lattice_steps": 9},
         r"filled_lattice_steps=9: only with rank_order='fill' and levels=2 or more \(this call: rank_order='fill', levels=1\)"),
        ({"levels": 2, "filled_lattice_steps": 0, "filled_lattice_up_to": 64},
         r"filled_lattice_up_to=64: only with rank_order='fill', levels=2 or more and filled_lattice_steps above 0 "
         r"\(this call: rank_order='fill', levels=2, filled_lattice_steps=0\)"),
        ({"filled_lattice_spacing": 0.5}, r"filled_lattice_spacing=0.5: only with rank_order='fill', levels=2 or more"),
    ]
    for arguments, message in cases:
        with pytest.raises(ValueError, match="^" + message):
            bt.wang_tiles(**small, **arguments)
    # Their defaults, given or not, are the same call; where the call uses them, they are taken.
    assert bt.wang_tiles(**small, ratio=2, period=16, void_sigma=0.5) == bt.wang_tiles(**small)
    bt.wang_tiles(**small, levels=2, rank_order="voids", void_sigma=0.7, level_seam_spacing=0.7, ratio=3)
    bt.wang_tiles(**small, set="corner81", period=4)  # strategy 'auto' is instances for corner81


def test_bounded_relaxation_refuses_points_outside_the_square():
    # bounded=True wrapped a point at x = 1.5 to 0.5 and relaxed it there, as relax --bounded did.
    points = np.array([[0.5, 0.5], [1.5, 0.25], [0.2, 0.8]])
    with pytest.raises(ValueError, match=r"^points\[1\]: x = 1.5 is outside \[0, 1\) \(bounded=True: the points lie in "
                                         r"the unit square, and are not wrapped onto a torus\)$"):
        bt.relax(points, iterations=1, bounded=True)
    assert bt.relax(points, iterations=1, engine="exact").shape == (3, 2)  # on the torus: wrapped, as before
    assert bt.relax(points % 1.0, iterations=1, bounded=True).shape == (3, 2)


@pytest.mark.parametrize("dtype", [np.int8, np.int16, np.int32, np.int64])
def test_negative_levels_are_quoted_as_given(tmp_path, dtype):
    # An int32 -1 was read as uint32 and quoted as 4294967295.
    points = bt.random_points(10)
    with pytest.raises(ValueError, match=r"^levels\[0\]: level must be in \[0, 1000000\], got -1$"):
        bt.save_table(tmp_path / "x.txt", points, levels=-np.ones(10, dtype))
    with pytest.raises(ValueError, match=r"^base_levels\[0\]: level must be in \[0, 1000000\], got -1$"):
        bt.progressive(points, -np.ones(10, dtype), add=5, iterations=1, engine="exact")
    with pytest.raises(ValueError, match=r"^levels\[0\]: level must be in \[0, 1000000\], got 18446744073709551615$"):
        bt.save_table(tmp_path / "x.txt", points, levels=np.full(10, 2**64 - 1, np.uint64))
    bt.save_table(tmp_path / "x.txt", points, levels=np.arange(10, dtype=dtype))
    assert np.array_equal(bt.load_table(tmp_path / "x.txt", levels=True)[0][1], np.arange(10))


def test_tile_set_text_is_told_from_a_path(tmp_path):
    # Text that began with a space, a byte-order mark or a newline was taken for a path, and the
    # error quoted it whole ("cannot open: File name too long"); bytes always were a path.
    text = bt.wang_tiles(**CALLS["wang_tiles"][1])
    expected = bt.tile_set(text)["tiles"][3]["points"]
    for variant in (" " + text, "\ufeff" + text, "\t" + text, text.encode(), ("\ufeff" + text).encode()):
        assert np.array_equal(bt.tile_set(variant)["tiles"][3]["points"], expected), repr(variant[:3])
    # Text with a line break is text, refused by its line as a file with the same bytes would be.
    with pytest.raises(bt.Error, match=r"^tiles:1: not a tile-set file: the first line must be '# bluetile tiles 1'$"):
        bt.tile_set("\n" + text)
    with pytest.raises(bt.Error, match=r"^tiles:1: not a tile-set file"):
        bt.tile((0.0, 0.0, 1.0, 1.0), tiles="points\n0.5 0.5\n")
    # Anything else is a path, str, bytes or os.PathLike.
    (tmp_path / "set.tiles").write_text(text)
    for path in (str(tmp_path / "set.tiles"), bytes(tmp_path / "set.tiles"), tmp_path / "set.tiles"):
        assert np.array_equal(bt.tile_set(path)["tiles"][3]["points"], expected)
    with pytest.raises(bt.Error, match=r"absent\.tiles: cannot open: No such file or directory$"):
        bt.tile_set(str(tmp_path / "absent.tiles"))


def test_numbers_in_messages_are_written_shortest():
    # They were printed with %f: "got -1.000000", "got 0.500000".
    points = np.random.default_rng(5).random((20, 2))
    with pytest.raises(ValueError, match=r"^tolerance: expected a finite number >= 0, got -1$"):
        bt.relax(count=5, tolerance=-1.0, engine="exact")
    with pytest.raises(ValueError, match=r"^tolerance: expected a finite number >= 0, got -0.25$"):
        bt.stipple(np.ones((2, 2)), count=5, tolerance=-0.25)
    with pytest.raises(ValueError, match=r"^ratio: expected a finite number >= 0, got -1e\+20$"):
        bt.progressive(count=5, ratio=-1e20, engine="exact")
    with pytest.raises(bt.Error, match=r"^the ratio must be above 1, got 0.5$"):
        bt.progressive(count=5, ratio=0.5, engine="exact")
    with pytest.raises(ValueError, match=r"^bin_width: expected a positive number, got -1$"):
        bt.analyze(points, bin_width=-1.0)
    with pytest.raises(ValueError, match=r"^bin_width: expected a positive number, got 0$"):
        bt.radial_power(points, bin_width=0.0)
    with pytest.raises(ValueError, match=r"^density_map: values must be finite and >= 0, got -0.5 at row 1, column 0$"):
        bt.relax(count=5, density_map=[[1.0, 1.0], [-0.5, 1.0]])


# Run in a child whose address space is limited to about 1 GiB more than it maps after the imports,
# so that every request below is past what is available on any machine.
_LIMITED = """
import resource, sys
import numpy as np, pybluetile as bt
vm = int([l for l in open("/proc/self/status") if l.startswith("VmSize")][0].split()[1]) * 1024
resource.setrlimit(resource.RLIMIT_AS, (vm + (1 << 30), resource.getrlimit(resource.RLIMIT_AS)[1]))
p = np.random.default_rng(1).random((1000, 2))
big = np.random.default_rng(1).random((2 * 10**6, 2))
calls = {
    "relax": lambda: bt.relax(count=10**8, sets=10**7, iterations=0, engine="exact"),
    "relax_sets": lambda: bt.relax(count=10**6, sets=1000, iterations=0, engine="exact"),
    "relax_points": lambda: bt.relax(big, iterations=1, engine="exact"),
    "centroids": lambda: bt.centroids(big, engine="exact"),
    "stipple": lambda: bt.stipple(np.ones((2, 2)), count=10**8),
    "progressive": lambda: bt.progressive(count=10**7, levels=2, engine="exact"),
    "dart": lambda: bt.dart(10**8),
    "random_points": lambda: bt.random_points(10**8),
    "periodogram": lambda: bt.periodogram(p, size=65536),
    "analyze": lambda: bt.analyze(p, size=65536),
    "radial_power": lambda: bt.radial_power(p, size=65536),
    "tile": lambda: bt.tile((0.0, 0.0, 1e4, 1e4), density=1),
}
for name, call in calls.items():
    try:
        call()
        print(name, "accepted")
    except bt.Error as e:
        print(name, "refused:", e)
    except MemoryError as e:
        print(name, "MemoryError:", e)
"""


def test_requests_past_the_memory_are_refused_at_once_with_the_tools_estimate(tool, tmp_path):
    # Each ended in a bare "MemoryError: std::bad_alloc" after seconds of work, or ran for long;
    # the tool refuses them at once with its estimate, and so does the module now.
    started = time.monotonic()
    child = subprocess.run([sys.executable, "-c", _LIMITED], capture_output=True, text=True, timeout=120,
                           env={**os.environ, "OPENBLAS_NUM_THREADS": "1"})
    assert child.returncode == 0, child.stderr
    assert time.monotonic() - started < 60
    lines = dict(line.split(" ", 1) for line in child.stdout.splitlines())
    expected = {
        "relax": r"count=100000000 x sets=10000000 needs about 568\.4 PiB of memory",
        "relax_sets": r"count=1000000 x sets=1000 needs about 596\.0 GiB of memory",
        "relax_points": r"relax of 2000000 points needs about 1\.2 GiB of memory",
        "centroids": r"centroids of 2000000 points needs about 1\.2 GiB of memory",
        "stipple": r"count=100000000 needs about 59\.6 GiB of memory",
        "progressive": r"20000000 points in 2 levels needs about 12\.1 GiB of memory",
        "dart": r"count=100000000 needs about 17\.9 GiB of memory",
        "random_points": r"count=100000000 needs about 3\.0 GiB of memory",
        "periodogram": r"periodogram of 1000 points, size=65536 needs about \d+\.\d GiB of memory",
        "analyze": r"analyze of 1000 points, size=65536 needs about \d+\.\d GiB of memory",
        "radial_power": r"radial_power of 1000 points, size=65536 needs about \d+\.\d GiB of memory",
        "tile": r"region 0 0 10000 10000 of about 100000000 points needs about \d+\.\d GiB of memory",
    }
    for name, message in expected.items():
        assert re.fullmatch(rf"refused: {message}, more than the \d+\.\d [KMG]iB available", lines[name]), lines[name]
    # The same estimate as the tool's, in the same words after the request.
    cli = tool("relax", "--count", 10**8, "--sets", 10**7, "--engine", "exact", "--output", tmp_path / "p.txt",
               check=False)
    assert "--count 100000000 x --sets 10000000 needs about 568.4 PiB of memory, more than the" in cli.stderr


def test_save_table_writes_coordinates_as_given_like_the_tools_tile(tool, tmp_path):
    # x = 1.5 was written as 0.5: another point than the one given. tile()'s plane coordinates
    # are saved as they are, in the bytes `bluetile tile` writes for them.
    points = np.array([[0.25, 0.25], [1.5, 0.5], [-2.0, 3.25]])
    for name in ("t.txt", "t.npy", "t.bpt", "t.h"):
        bt.save_table(tmp_path / name, points)
    text = (tmp_path / "t.txt").read_text().splitlines()
    assert text == ["0.25 0.25", "1.5 0.5", "-2 3.25"]
    npy = (tmp_path / "t.npy").read_bytes()
    assert np.frombuffer(npy[-6 * 8:], dtype="<f8").tolist() == points.ravel().tolist()
    plane = bt.tile((0.0, 0.0, 3.0, 2.0), density=4)
    assert plane.max() > 1.0
    bt.save_table(tmp_path / "plane.txt", plane)
    tool("tile", "--region", "0", "0", "3", "2", "--density", "4", "-o", tmp_path / "tool.txt")
    tool_rows = [l for l in (tmp_path / "tool.txt").read_text().splitlines() if not l.startswith("#")]
    assert (tmp_path / "plane.txt").read_text().splitlines() == tool_rows
    # Read back, they are placed on the torus, as relax -i places them; analysis refuses them as given.
    assert np.array_equal(bt.load_table(tmp_path / "t.txt")[0], points % 1.0 % 1.0)
    with pytest.raises(ValueError, match=r"^points\[1\]: x = 1.5 is outside \[0, 1\)"):
        bt.analyze(points)


def test_load_table_refuses_a_file_without_points_as_the_tool_does(tool, tmp_path):
    # It returned [] where the tool says "no points".
    for name, text in (("empty.txt", ""), ("comments.txt", "# nothing here\n#\n")):
        path = tmp_path / name
        path.write_text(text)
        with pytest.raises(bt.Error) as caught:
            bt.load_table(path)
        assert str(caught.value) == f"{path}: no points"
        cli = tool("analyze", "--input", path, "--output", tmp_path / "out", check=False)
        assert cli.returncode != 0 and cli.stderr == f"bluetile: {caught.value}\n"


def test_wang_tiles_documents_every_argument():
    doc = bt.wang_tiles.__doc__
    names = re.findall(r"(\w+): ", bt.wang_tiles.__nb_signature__[0][0].split("(", 1)[1])
    assert len(names) == 22
    for name in names:
        assert re.search(rf"^{name}: \S", doc, re.M), name


def test_wang_tiles_with_too_few_points_names_points():
    # It said only "a cell of tile 2 reaches beyond its 3x3 block of tiles (radius 1.773116 tiles):
    # too few points per tile", the tool's words for a run of its --points.
    with pytest.raises(bt.Error, match=r"^points=4: too few points per tile for this set and seed: a cell of tile 2 "
                                       r"reaches beyond its 3x3 block of tiles \(radius 1.773116 tiles\); give more "
                                       r"points \(the default is 52; how few work depends on the set and the seed\)$"):
        bt.wang_tiles(points=4)


def test_wang_tiles_ratio_range_is_written_as_typed():
    # "expected above 1 to 1e+08, got 1e+09".
    for ratio, text in ((1e9, "1000000000"), (1.0, "1"), (math.inf, "infinity"), (math.nan, "nan")):
        with pytest.raises(bt.Error, match=rf"^ratio: expected above 1 to 100000000, got {text}$"):
            bt.wang_tiles(points=4, levels=2, ratio=ratio)


def test_tile_names_its_own_arguments(tool, tmp_path):
    # The library's words were the tool's: "max density: expected ...", "max density and count
    # need a density map", "use a smaller tile size".
    ones = np.ones((2, 2))
    cases = [
        (dict(max_density=-1.0, density_map=ones), r"^max_density: expected a finite number >= 0 \(0: not given\), got -1$"),
        (dict(tile_size=-0.5), r"^tile_size: expected a finite number >= 0 \(0: not given\), got -0.5$"),
        (dict(count=math.nan, density_map=ones), r"^count: expected a finite number >= 0 \(0: not given\), got nan$"),
        (dict(density=-1.0), r"^density: expected a finite number >= 0 \(0: not given\), got -1$"),
        (dict(max_density=5.0), r"^max_density=5 needs a density_map: give one$"),
        (dict(count=100.0), r"^count=100 needs a density_map: give one$"),
        (dict(count=100.0, max_density=5.0, density_map=ones), r"^count and max_density exclude each other: give one$"),
        (dict(density=5.0, density_map=ones), r"^density=5 is for uniform tilings; with a density_map give max_density or count$"),
        (dict(tile_size=1.0, density=1e9), r"\): use a smaller tile_size or leave it out$"),
        # Tiles too small for a finite density were "density 1 is too low for tiles of size 1e-170 (inf ...)".
        (dict(tile_size=1e-170, density=1.0), r"^tile size 1e-170 is too small: .* than a double holds; use a larger tile_size$"),
    ]
    for kwargs, message in cases:
        with pytest.raises(ValueError, match=message):
            bt.tile((0.0, 0.0, 1.0, 1.0), **kwargs)
    # The tool says the same with its own option names.
    cli = tool("tile", "--region", 0, 0, 1, 1, "--tile-size", 1, "--density", 1e9, "--output", tmp_path / "t.txt",
               check=False)
    assert "use a smaller --tile-size or leave it out" in cli.stderr


def test_float32_values_in_messages_are_the_float32s_shortest():
    # -0.1 as float32 was quoted as -0.10000000149011612, the double it widens to.
    with pytest.raises(ValueError, match=r"^density_map: values must be finite and >= 0, got -0.1 at row 0, column 0$"):
        bt.relax(count=5, density_map=np.array([[-0.1, 1.0]], dtype=np.float32))
    with pytest.raises(ValueError, match=r"^points\[0\]: x = 1.1 is outside \[0, 1\)"):
        bt.analyze(np.array([[1.1, 0.5], [0.25, 0.25]], dtype=np.float32))
    # float64 values keep their own shortest form, every digit it needs.
    with pytest.raises(ValueError, match=r"^points\[0\]: y = 1.0000000000000002 is outside \[0, 1\)"):
        bt.analyze(np.array([[0.5, 1.0 + 2**-52], [0.25, 0.25]]))
    with pytest.raises(ValueError, match=r"^points\[0\]: x = -1e-17 is outside \[0, 1\)"):
        bt.analyze(np.array([[-1e-17, 0.5], [0.25, 0.25]]))


def _set_comma_locale(tmp_path):
    """Sets LC_ALL to a locale whose decimal point is a comma, as an embedding program may
    (locale.setlocale(locale.LC_ALL, 'de_DE.UTF-8')); one made with localedef where the system
    has none. Returns False where none can be had."""
    import locale
    names = ("de_DE.UTF-8", "de_DE.utf8", "fr_FR.UTF-8", "fr_FR.utf8")
    for name in names:
        try:
            locale.setlocale(locale.LC_ALL, name)
            if locale.localeconv()["decimal_point"] == ",":
                return True
        except locale.Error:
            pass
    if shutil.which("localedef") is None:
        return False
    made = subprocess.run(["localedef", "-i", "de_DE", "-f", "UTF-8", str(tmp_path / "de_DE.UTF-8")],
                          capture_output=True, check=False)
    if made.returncode != 0:
        return False
    os.environ["LOCPATH"] = str(tmp_path)
    try:
        locale.setlocale(locale.LC_ALL, "de_DE.UTF-8")
    except locale.Error:
        return False
    return locale.localeconv()["decimal_point"] == ","


def test_messages_write_numbers_with_a_point_under_a_comma_locale(tmp_path):
    # A float32 value in a message was "x = 1,5" under the program's German locale.
    import locale
    saved = locale.setlocale(locale.LC_ALL)
    saved_locpath = os.environ.get("LOCPATH")
    try:
        if not _set_comma_locale(tmp_path):
            pytest.skip("no locale with a decimal comma, and localedef cannot make one")
        points = np.array([[0.25, 0.25], [1.5, 0.5]], dtype=np.float32)
        with pytest.raises(ValueError) as raised:
            bt.analyze(points)
        message = str(raised.value)
    finally:
        locale.setlocale(locale.LC_ALL, saved)
        if saved_locpath is None:
            os.environ.pop("LOCPATH", None)
        else:
            os.environ["LOCPATH"] = saved_locpath
    assert message.startswith("points[1]: x = 1.5 is outside [0, 1)"), message
