"""The scale-out recipe of docs/SCALE.md on Dask's local schedulers: batch tables and a plane
window made in independent chunks give, bit for bit, what one process makes in one call."""
import numpy as np
import pytest

import pybluetile as bt

dask = pytest.importorskip("dask", reason="python3-dask (./setup.sh installs it) runs the scale-out recipe")


def table_chunk(first, count, points=32, iterations=10, seed=1):
    """Tables first .. first + count - 1 of a seed: their starts are the tool's sets of that seed."""
    starts = np.stack([bt.random_points(points, seed=seed, set=k) for k in range(first, first + count)])
    return bt.relax(starts, iterations=iterations, engine="exact")


def test_tables_in_chunks_match_one_call():
    whole = bt.relax(count=32, sets=24, iterations=10, seed=1, engine="exact")
    chunks = [dask.delayed(table_chunk)(first, 6) for first in range(0, 24, 6)]
    for scheduler in ("threads", "processes", "sync"):
        parts = dask.compute(*chunks, scheduler=scheduler)
        assert np.array_equal(np.concatenate(parts), whole), scheduler


def sorted_rows(points):
    return points[np.lexsort((points[:, 1], points[:, 0]))]


def test_a_window_in_chunks_matches_the_whole_window():
    region = (-6.0, -4.0, 6.0, 4.0)
    whole = bt.tile(region, density=30, seed=5)
    # 4 x 2 half-open chunks partition the window: every point lies in exactly one of them.
    xs, ys = np.linspace(region[0], region[2], 5), np.linspace(region[1], region[3], 3)
    chunks = [dask.delayed(bt.tile)((xs[i], ys[j], xs[i + 1], ys[j + 1]), density=30, seed=5)
              for i in range(4) for j in range(2)]
    parts = dask.compute(*chunks, scheduler="threads")
    assert sum(len(p) for p in parts) == len(whole) > 1000
    assert np.array_equal(sorted_rows(np.concatenate(parts)), sorted_rows(whole))
