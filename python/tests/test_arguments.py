"""Every numeric argument of every function: a bad value raises a ValueError naming the argument
(or, for a negative count where the binding takes an unsigned integer, nanobind's TypeError),
before any work. The arguments are read from the functions' own signatures, so a new one is
covered without a new test."""
import math
import re

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
}
# Values valid for an argument although they are bad for most: any unsigned 64-bit seed.
ALSO_VALID = {"seed": {10**15}}


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
    bad = [math.nan, math.inf, -math.inf, -1.0] if kind == "float" else [-1, 10**15]
    for value in bad:
        if value in ALSO_VALID.get(argument, set()):
            continue
        try:
            getattr(bt, name)(*args, **{**kwargs, argument: value})
        except ValueError as e:
            assert argument in str(e) or argument.replace("_", " ") in str(e), (name, argument, value, str(e))
        except TypeError:
            assert kind == "int", (name, argument, value)  # unsigned or narrower C++ integer
        else:
            pytest.fail(f"{name}({argument}={value!r}) was accepted")


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
        with pytest.raises(ValueError, match=r"^points\[1\]: x = 1 is outside \[0, 1\) \(points % 1.0 wraps them"):
            function(points)
    assert bt.analyze(points % 1.0, psa_measures=False, discrepancy=False)["rho"] == 0.0  # wrapped by the caller
    # relax and centroids wrap, as the tool wraps point files it relaxes.
    bt.centroids(np.array([[1.25, 0.5], [0.5, 0.5]]), engine="exact")


def test_messages_quoting_bytes_that_are_not_utf8_keep_their_text(tmp_path):
    # The Error had no message at all: its text quoted the file's bytes \xff\xfe.
    path = tmp_path / "b.txt"
    path.write_bytes(b"\xff\xfe0.1 0.2\n")
    with pytest.raises(bt.Error) as caught:
        bt.load_table(str(path))
    assert str(caught.value) == f"{path}:1: not a number '\ufffd\ufffd0.1'"


def test_fixed_out_of_range_names_the_range():
    # A negative count said "fixed: -1 is more than the 5 points".
    for fixed in (-1, 6):
        with pytest.raises(ValueError, match=rf"^fixed: expected 0 to 5 \(the points\), got {fixed}$"):
            bt.relax(count=5, iterations=1, fixed=fixed, engine="exact")
