"""Blue-noise sample points by Lloyd relaxation on the unit torus.

After Hiller, Deussen and Keller, *Tiled Blue Noise Samples* (2001). Point sets are NumPy
arrays of shape (N, 2) (or (K, N, 2) for K sets) of float64 coordinates in [0, 1). Every
function releases the GIL while it computes; bad input raises ``pybluetile.Error`` (a
``ValueError``) with the same message the ``bluetile`` tool prints, or a ``TypeError`` /
``ValueError`` naming the argument. ``None`` for an argument with a default means that default.
"""

# NumPy first: nanobind would import it lazily on the first array returned, and an interrupt
# (Ctrl-C) caught during a first long call then surfaces from that import as a TypeError
# instead of KeyboardInterrupt.
import numpy as _numpy  # noqa: F401  (private: the module's names are its functions)

from ._core import (
    Error,
    analyze,
    centroids,
    dart,
    load_table,
    nearest_neighbour_distances,
    periodogram,
    progressive,
    radial_power,
    random_points,
    relax,
    save_table,
    set_thread_count,
    stipple,
    thread_count,
    tile,
    tile_set,
    wang_tiles,
)

import copyreg as _copyreg

from . import _core


def _reduce_function(function):
    """Pickles this module's functions by name, as Python's own built-in functions are pickled,
    so that they can be sent to other processes (multiprocessing, concurrent.futures, Dask's
    process scheduler); nanobind's function type has no pickling of its own. Functions of other
    nanobind modules (the type is shared) are refused as before."""
    if getattr(function, "__module__", None) == _core.__name__ and getattr(_core, function.__name__, None) is function:
        return function.__name__  # a global of function.__module__
    return function.__reduce_ex__(4)


_copyreg.pickle(type(_core.relax), _reduce_function)

__version__ = "0.1.0"

__all__ = [
    "Error",
    "analyze",
    "centroids",
    "dart",
    "load_table",
    "nearest_neighbour_distances",
    "periodogram",
    "progressive",
    "radial_power",
    "random_points",
    "relax",
    "save_table",
    "set_thread_count",
    "stipple",
    "thread_count",
    "tile",
    "tile_set",
    "wang_tiles",
]
