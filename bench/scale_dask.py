"""Scale-out on Dask's local schedulers (docs/SCALE.md): batch tables and a plane window made in
chunks, against one call in one process, in the same run; checks the bits agree and prints the
wall times.

    build/python-venv/bin/python bench/scale_dask.py --tables 4096 --chunks 16 --window 200 --window-chunks 4
"""
import argparse
import os
import tempfile
import time

import dask
import numpy as np

import pybluetile as bt


def table_chunk(first, count, points, iterations, seed):
    starts = np.stack([bt.random_points(points, seed=seed, set=k) for k in range(first, first + count)])
    return bt.relax(starts, iterations=iterations, engine="exact")


def window_chunk(region, density, seed, path):
    points = bt.tile(region, density=density, seed=seed)
    bt.save_table(path, points)
    return len(points)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--tables", type=int, default=4096)
    ap.add_argument("--points", type=int, default=64)
    ap.add_argument("--iterations", type=int, default=50)
    ap.add_argument("--chunks", type=int, default=16)
    ap.add_argument("--window", type=float, default=200.0, help="side of the square window, in tiles")
    ap.add_argument("--window-chunks", type=int, default=4, help="chunks per side")
    ap.add_argument("--density", type=float, default=16.0)
    args = ap.parse_args()
    print(f"threads {bt.thread_count()}, load {os.getloadavg()[0]:.1f}")

    t = time.perf_counter()
    whole = bt.relax(count=args.points, sets=args.tables, iterations=args.iterations, seed=1, engine="exact")
    one = time.perf_counter() - t
    per = args.tables // args.chunks
    threads = bt.thread_count()
    for inner in (threads, 1):
        # Dask's threads run chunks side by side; the library's own threads inside each chunk
        # compete with them unless set to 1.
        bt.set_thread_count(inner)
        t = time.perf_counter()
        parts = dask.compute(*[dask.delayed(table_chunk)(f, per, args.points, args.iterations, 1)
                               for f in range(0, args.tables, per)], scheduler="threads")
        chunked = time.perf_counter() - t
        same = np.array_equal(np.concatenate(parts), whole)
        print(f"| tables {args.tables} x {args.points} x {args.iterations} | one call {one:.2f} s | "
              f"{args.chunks} chunks, Dask threads, library threads {inner}: {chunked:.2f} s | ratio {chunked / one:.2f} | "
              f"same bits {same} |")
    bt.set_thread_count(threads)

    side, k = args.window, args.window_chunks
    edges = np.linspace(0.0, side, k + 1)
    with tempfile.TemporaryDirectory() as folder:
        t = time.perf_counter()
        whole_count = window_chunk((0.0, 0.0, side, side), args.density, 3, os.path.join(folder, "whole.npy"))
        one = time.perf_counter() - t
        jobs = [dask.delayed(window_chunk)((edges[i], edges[j], edges[i + 1], edges[j + 1]), args.density, 3,
                                           os.path.join(folder, f"chunk-{i}-{j}.npy"))
                for i in range(k) for j in range(k)]
        t = time.perf_counter()
        counts = dask.compute(*jobs, scheduler="threads")
        chunked = time.perf_counter() - t
        rows = lambda p: p[np.lexsort((p[:, 1], p[:, 0]))]
        merged = np.concatenate([np.load(os.path.join(folder, f"chunk-{i}-{j}.npy")).reshape(-1, 2)
                                 for i in range(k) for j in range(k)])
        same = sum(counts) == whole_count and np.array_equal(rows(merged), rows(np.load(os.path.join(folder, "whole.npy")).reshape(-1, 2)))
    print(f"| window {side:g} x {side:g}, {whole_count} points | one call {one:.2f} s | "
          f"{k * k} chunks to .npy, threads {chunked:.2f} s | ratio {chunked / one:.2f} | same bits {same} |")


if __name__ == "__main__":
    main()
