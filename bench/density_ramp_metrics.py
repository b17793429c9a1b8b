"""Density control of point sets made for the ramp density(x, y) = x on the unit square
(docs/RESULTS.md, stippling against a thinned tiling), measured as bluetile_tiler_bench --ramp
measures the tiler: counts in 16 vertical strips against the map's integral, and local rho =
nearest-neighbour distance / d_hex at the target density D(x) = 2 N x, leaving out points within
2 d_hex of the border and the first strip (where D nears 0).

With --uniform, the sets are taken as uniform over the unit square instead: the count error of
16 vertical and of 16 horizontal strips against N / 16 (what bounds the ramp's counts: the same
strips on an even density, for tiled, relaxed and filled sets alike). With --warped, uniform sets
are carried onto the ramp by x -> sqrt(x) (the ramp's inverse distribution: a strip [a, b] of the
ramp holds exactly the points of the strip [a^2, b^2] of the set) and only the ramp's counts are
measured: what a set's own count fluctuations give on the ramp under an ideal transfer.

Usage: python3 bench/density_ramp_metrics.py [--uniform | --warped] POINTS.txt ...   (needs numpy)
"""
import sys

import numpy as np

STRIPS = 16
CHUNK = 1000  # points per block of the brute-force nearest-neighbour search


def load(path):
    return np.loadtxt(path, comments="#", ndmin=2)[:, :2]


def nearest_neighbour_distances(points):
    distances = np.empty(len(points))
    for start in range(0, len(points), CHUNK):
        block = points[start:start + CHUNK]
        squared = ((block[:, None, :] - points[None, :, :]) ** 2).sum(-1)
        squared[np.arange(len(block)), start + np.arange(len(block))] = np.inf
        distances[start:start + CHUNK] = np.sqrt(squared.min(1))
    return distances


def ramp_count_errors(points):
    n = len(points)
    edges = np.linspace(0.0, 1.0, STRIPS + 1)
    counts = np.histogram(points[:, 0], edges)[0]
    expected = n * (edges[1:] ** 2 - edges[:-1] ** 2)  # the integral of x over each strip, times N
    return np.abs(counts - expected) / expected


def count_figures(strip_error):
    return {
        "strip error mean %": 100 * strip_error.mean(),
        "worst strip %": 100 * strip_error.max(),
        "lowest strip %": 100 * strip_error[0],
    }


def warped_metrics(points):
    ramp = np.column_stack([np.sqrt(points[:, 0]), points[:, 1]])
    return {"points": len(points), **count_figures(ramp_count_errors(ramp))}


def ramp_metrics(points):
    n = len(points)
    strip_error = ramp_count_errors(points)
    d_hex = np.sqrt(2.0 / (np.sqrt(3.0) * np.maximum(2.0 * n * points[:, 0], 1e-12)))
    x, y = points[:, 0], points[:, 1]
    inside = (x > 2 * d_hex) & (x < 1 - 2 * d_hex) & (y > 2 * d_hex) & (y < 1 - 2 * d_hex) & (x > 1.0 / STRIPS)
    rho = nearest_neighbour_distances(points)[inside] / d_hex[inside]
    return {
        "points": n,
        **count_figures(strip_error),
        "rho min": rho.min(),
        "rho p1": np.percentile(rho, 1),
        "rho median": np.median(rho),
    }


def uniform_metrics(points):
    n = len(points)
    figures = {"points": n}
    for axis, name in ((0, "vertical"), (1, "horizontal")):
        counts = np.histogram(points[:, axis], np.linspace(0.0, 1.0, STRIPS + 1))[0]
        strip_error = np.abs(counts - n / STRIPS) / (n / STRIPS)
        figures[name + " strip error mean %"] = 100 * strip_error.mean()
        figures[name + " worst strip %"] = 100 * strip_error.max()
    return figures


if __name__ == "__main__":
    modes = {"--uniform": uniform_metrics, "--warped": warped_metrics}
    chosen = [a for a in sys.argv[1:] if a in modes]
    paths = [a for a in sys.argv[1:] if a not in modes]
    if len(chosen) > 1 or not paths:
        sys.exit("usage: density_ramp_metrics.py [--uniform | --warped] POINTS.txt ...")
    measure = modes[chosen[0]] if chosen else ramp_metrics
    for path in paths:
        figures = measure(load(path))
        print(path + ": " + ", ".join(f"{k} {v:.3f}" if isinstance(v, float) else f"{k} {v}" for k, v in figures.items()))
