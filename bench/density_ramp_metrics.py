"""Density control of point sets made for the ramp density(x, y) = x on the unit square
(docs/RESULTS.md, stippling against a thinned tiling), measured as bluetile_tiler_bench --ramp
measures the tiler: counts in 16 vertical strips against the map's integral, and local rho =
nearest-neighbour distance / d_hex at the target density D(x) = 2 N x, leaving out points within
2 d_hex of the border and the first strip (where D nears 0).

Usage: python3 bench/density_ramp_metrics.py POINTS.txt ...   (needs numpy)
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


def ramp_metrics(points):
    n = len(points)
    edges = np.linspace(0.0, 1.0, STRIPS + 1)
    counts = np.histogram(points[:, 0], edges)[0]
    expected = n * (edges[1:] ** 2 - edges[:-1] ** 2)  # the integral of x over each strip, times N
    strip_error = np.abs(counts - expected) / expected
    d_hex = np.sqrt(2.0 / (np.sqrt(3.0) * np.maximum(2.0 * n * points[:, 0], 1e-12)))
    x, y = points[:, 0], points[:, 1]
    inside = (x > 2 * d_hex) & (x < 1 - 2 * d_hex) & (y > 2 * d_hex) & (y < 1 - 2 * d_hex) & (x > 1.0 / STRIPS)
    rho = nearest_neighbour_distances(points)[inside] / d_hex[inside]
    return {
        "points": n,
        "strip error mean %": 100 * strip_error.mean(),
        "worst strip %": 100 * strip_error.max(),
        "lowest strip %": 100 * strip_error[0],
        "rho min": rho.min(),
        "rho p1": np.percentile(rho, 1),
        "rho median": np.median(rho),
    }


if __name__ == "__main__":
    for path in sys.argv[1:]:
        figures = ramp_metrics(load(path))
        print(path + ": " + ", ".join(f"{k} {v:.3f}" if isinstance(v, float) else f"{k} {v}" for k, v in figures.items()))
