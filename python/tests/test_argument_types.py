"""None and values of the wrong type for every argument of every function: None means the
argument's default where it has one (as in Python's own functions); anything else of the wrong type
(None for an argument without a default, a bool for a number) is a TypeError naming the argument
and what it takes. Each was nanobind's TypeError listing the whole signature ("incompatible
function arguments"), or a bool was taken as 0 or 1. The arguments are read from the functions'
own signatures, so a new one is covered without a new test."""
import re

import numpy as np
import pytest

import pybluetile as bt
from test_arguments import CALLS

# Functions CALLS leaves out (they write files or need no numbers): their smallest valid call.
MORE_CALLS = {
    "nearest_neighbour_distances": ((np.random.default_rng(6).random((20, 2)),), {}),
    "tile_set": ((), {}),
    "set_thread_count": ((bt.thread_count(),), {}),
}


def arguments(function):
    """(name, has a default, default text) for each argument of the signature."""
    signature = function.__nb_signature__[0][0]
    inside = signature[signature.index("(") + 1:signature.rindex(") ->")]
    # Split at the commas between arguments, not those inside brackets (tuple[float, float, ...]).
    parts, depth, current = [], 0, ""
    for c in inside:
        depth += c in "[(" and 1 or c in "])" and -1 or 0
        if c == "," and depth == 0:
            parts.append(current.strip())
            current = ""
        else:
            current += c
    parts.append(current.strip())
    result = []
    for part in parts:
        if part in ("*", "/"):
            continue
        name, rest = part.split(":", 1)
        result.append((name.strip(), "=" in rest, rest.split("=", 1)[1].strip() if "=" in rest else None))
    return result


ALL_CALLS = {**CALLS, **MORE_CALLS}
DEFAULTED = [(name, argument) for name in ALL_CALLS for argument, has_default, default
             in arguments(getattr(bt, name)) if has_default and default != "None"]
EVERY = [(name, argument) for name in ALL_CALLS for argument, _, _ in arguments(getattr(bt, name))]


def call(name, **override):
    args, kwargs = ALL_CALLS[name]
    kwargs = {**kwargs, **override}
    args = list(args)
    # A positional argument given by name replaces its place.
    for index, (argument, _, _) in enumerate(arguments(getattr(bt, name))[:len(args)]):
        if argument in kwargs:
            args[index] = kwargs.pop(argument)
    return getattr(bt, name)(*args, **kwargs)


def outcome(name, **override):
    """The result of the call, or the type and message of what it raised (count=0 means "not
    given", and a call without points or count is refused: so must one with count=None be)."""
    try:
        return call(name, **override)
    except (TypeError, ValueError) as e:
        return type(e), str(e)


def same(a, b):
    if isinstance(a, dict):
        return isinstance(b, dict) and a.keys() == b.keys() and all(same(a[k], b[k]) for k in a)
    if isinstance(a, (tuple, list)):
        return type(a) is type(b) and len(a) == len(b) and all(same(x, y) for x, y in zip(a, b))
    if isinstance(a, np.ndarray):
        return a.dtype == b.dtype and np.array_equal(a, b, equal_nan=a.dtype.kind == "f")
    return a == b or (a != a and b != b)


def test_the_tables_cover_every_function():
    assert {name for name, _ in EVERY} == set(bt.__all__) - {"Error", "thread_count", "save_table", "load_table"}
    # What completion shows is what __all__ lists (numpy was a public name of the module).
    assert {name for name in dir(bt) if not name.startswith("_")} == set(bt.__all__)
    assert len(DEFAULTED) > 80


@pytest.mark.parametrize("name,argument", DEFAULTED)
def test_none_means_the_default(name, argument):
    # The default the signature shows, given by name, and None: the same result.
    default = {a: d for a, _, d in arguments(getattr(bt, name))}[argument]
    value = eval(default, {"__builtins__": {}})
    assert same(outcome(name, **{argument: None}), outcome(name, **{argument: value})), (name, argument)


@pytest.mark.parametrize("name,argument", EVERY)
def test_a_wrong_type_is_a_type_error_naming_the_argument(name, argument):
    class Something:
        pass

    with pytest.raises(TypeError, match=rf"^{argument}: expected .*, got test_argument_types\.Something$"):
        call(name, **{argument: Something()})


@pytest.mark.parametrize("name,argument", [(n, a) for n, a in EVERY if (n, a) not in DEFAULTED])
def test_none_without_a_default_is_a_type_error_naming_the_argument(name, argument):
    defaults = {a: d for a, _, d in arguments(getattr(bt, name))}
    if defaults[argument] == "None":  # None is the default: "not given"
        return
    with pytest.raises(TypeError, match=rf"^{argument}: expected .*, got None(Type)?$"):
        call(name, **{argument: None})


def test_bools_are_not_numbers():
    # count=True was a count of 1.
    for name, argument in EVERY:
        signature = getattr(bt, name).__nb_signature__[0][0]
        match = re.search(rf"\b{argument}: (int|float)\b", signature)
        if not match:
            continue
        expected = "an integer" if match.group(1) == "int" else r"a number \(int or float\)"
        for value in (True, np.False_):
            with pytest.raises(TypeError, match=rf"^{argument}: expected {expected}, got bool_?$"):
                call(name, **{argument: value})
    with pytest.raises(TypeError, match=r"^count: expected an integer, got bool$"):
        bt.relax(count=True, iterations=1, engine="exact")
    # and numbers are not bools.
    with pytest.raises(TypeError, match=r"^history: expected a bool \(True or False\), got int$"):
        bt.relax(count=5, iterations=1, engine="exact", history=1)


def test_save_and_load_table_take_none_and_name_wrong_types(tmp_path):
    points = bt.random_points(8)
    bt.save_table(tmp_path / "a.txt", points, format=None, float32=None, name=None, comment=None, levels=None)
    bt.save_table(tmp_path / "b.txt", points)
    assert (tmp_path / "a.txt").read_bytes() == (tmp_path / "b.txt").read_bytes()
    assert same(bt.load_table(tmp_path / "a.txt", levels=None), bt.load_table(tmp_path / "a.txt"))
    for argument, value, message in [
        ("format", 1, r"^format: expected a str, got int$"),
        ("float32", 1, r"^float32: expected a bool \(True or False\), got int$"),
        ("name", b"x", r"^name: expected a str, got bytes$"),
        ("comment", 1, r"^comment: expected a str or a sequence of str, got int$"),
        ("comment", ["a", 2], r"^comment\[1\]: expected a str, got int$"),
        ("comment", b"x", r"^comment: expected a str or a sequence of str, got bytes$"),
    ]:
        with pytest.raises(TypeError, match=message):
            bt.save_table(tmp_path / "c.txt", points, **{argument: value})
        assert not (tmp_path / "c.txt").exists()
    for value, message in [(None, r"^path: expected a str or os.PathLike path, got None$"),
                           (1, r"^path: expected a str or os.PathLike path, got int$")]:
        with pytest.raises(TypeError, match=message):
            bt.save_table(value, points)
        with pytest.raises(TypeError, match=message):
            bt.load_table(value)
    with pytest.raises(TypeError, match=r"^levels: expected a bool \(True or False\), got int$"):
        bt.load_table(tmp_path / "a.txt", levels=1)


def test_a_str_comment_is_one_comment_line_escaped_as_the_tool_escapes(tool, tmp_path):
    # A str was refused with the signature; it is one line, as one item of a list is.
    points = bt.random_points(8)
    bt.save_table(tmp_path / "one.txt", points, comment="made by hand")
    assert (tmp_path / "one.txt").read_text().startswith("# made by hand\n0")
    bt.save_table(tmp_path / "str.txt", points, comment="a\nb\tc\x01")
    bt.save_table(tmp_path / "list.txt", points, comment=["a\nb\tc\x01"])
    assert (tmp_path / "str.txt").read_bytes() == (tmp_path / "list.txt").read_bytes()
    assert (tmp_path / "str.txt").read_text().startswith("# a\\nb\tc\\x01\n")
    # The tool writes a file name it quotes in a comment the same way: the input's name in
    # relax's header, a line break in it escaped, the tab kept.
    source = tmp_path / "in\nput\t.txt"
    bt.save_table(source, points)
    tool("relax", "--input", source, "--iterations", 0, "--engine", "exact", "--output", tmp_path / "out.txt")
    assert "in\\nput\t.txt" in (tmp_path / "out.txt").read_text()
    assert len(bt.load_table(tmp_path / "str.txt")[0]) == 8


def test_tile_region_is_checked_by_name():
    for value, message in [("0 0 1 1", r"got str$"), ((0, 0, 1), r"got 3 values$"), (None, r"got None$"),
                           ((0, 0, "1", 1), r"^region\[2\]: expected a number \(int or float\), got str$")]:
        with pytest.raises(TypeError, match=message):
            bt.tile(value)
    assert np.array_equal(bt.tile([0, 0, 1, 1]), bt.tile((0.0, 0.0, 1.0, 1.0)))
