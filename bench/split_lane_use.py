#!/usr/bin/env python3
"""Kept candidates per boundary pixel and the SIMD lane use they give split_lane_f64.comp.

Recomputes, in plain Python, the boundary pixels of an area-coverage pass (corner owners differ)
and the pruning the split applies (sites within reach of the pixel centre, then within the
nearest one's distance plus the diagonal and nearer than it at some corner), for a point file on
the unit torus at R x R pixels. Eight pixels share a SIMD group on lavapipe, and the owner and
clip loops run as often as the group's largest count asks: lane use is the useful share.

    build/bluetile relax -n 10000 -k 100 --seed 1 --engine exact --output p.txt
    bench/split_lane_use.py p.txt 208

(An estimate: the corner owners are exact nearest sites, not the rasterized IDs, and the window
is a plain grid search; docs/BENCHMARKS.md, "The lane kernel under perf".)
"""
import collections
import math
import random
import sys


def read_points(path):
    points = []
    for line in open(path):
        fields = line.split()
        if len(fields) >= 2 and not line.startswith('#'):
            points.append((float(fields[0]), float(fields[1])))
    return points


def main():
    points = read_points(sys.argv[1])
    rx = int(sys.argv[2])
    h = 1.0 / rx
    side = max(1, int(math.sqrt(len(points))))  # grid buckets per side, about one site each
    buckets = collections.defaultdict(list)
    for k, (x, y) in enumerate(points):
        buckets[(int(x * side) % side, int(y * side) % side)].append(k)

    def sites_near(x, y, r):  # (site, x, y) of every periodic image in the buckets within r
        out = []
        for by in range(math.floor((y - r) * side), math.floor((y + r) * side) + 1):
            wy = math.floor(by / side)
            for bx in range(math.floor((x - r) * side), math.floor((x + r) * side) + 1):
                wx = math.floor(bx / side)
                for k in buckets[(bx - wx * side, by - wy * side)]:
                    out.append((k, points[k][0] + wx, points[k][1] + wy))
        return out

    def owner(i, j):
        x, y, r = i * h, j * h, 1.5 / side
        while True:
            near = [((sx - x) ** 2 + (sy - y) ** 2, k) for k, sx, sy in sites_near(x, y, r)]
            if near and math.sqrt(min(near)[0]) <= r:
                return min(near)[1]
            r *= 2

    ids = {(i, j): owner(i % rx, j % rx) for j in range(rx + 1) for i in range(rx + 1)}
    diagonal = h * math.sqrt(2.0) * (1.0 + 1.0 / 65536.0)
    counts = []
    for j in range(rx):
        for i in range(rx):
            corners = {ids[(i, j)], ids[(i + 1, j)], ids[(i, j + 1)], ids[(i + 1, j + 1)]}
            if len(corners) == 1:
                continue
            cx, cy = (i + 0.5) * h, (j + 0.5) * h
            nearest = min(math.dist((cx, cy), (points[k][0] + dx, points[k][1] + dy))
                          for k in corners for dx in (-1, 0, 1) for dy in (-1, 0, 1))
            reach = nearest + diagonal
            candidates = [(k, sx, sy, (sx - cx) ** 2 + (sy - cy) ** 2) for k, sx, sy in sites_near(cx, cy, reach)]
            candidates = [c for c in candidates if c[3] <= reach * reach]
            s0 = min(candidates, key=lambda c: c[3])
            reach0 = math.sqrt(s0[3]) + diagonal
            kept = 0
            for c in candidates:
                if c[3] > reach0 * reach0:
                    continue
                if c is not s0:
                    dx, dy = c[1] - s0[1], c[2] - s0[2]
                    offset = 0.5 * (dx * dx + dy * dy)
                    square = ((i * h, j * h), ((i + 1) * h, j * h), (i * h, (j + 1) * h), ((i + 1) * h, (j + 1) * h))
                    if not any((qx - s0[1]) * dx + (qy - s0[2]) * dy - offset > 0.0 for qx, qy in square):
                        continue
                kept += 1
            counts.append(kept)

    n = len(counts)
    histogram = sorted(collections.Counter(counts).items())
    print('boundary pixels %d, kept candidates: %s, mean %.2f' % (n, histogram, sum(counts) / n))

    def lane_use(groups):  # (clip passes, owner loop): useful over issued
        useful_pairs = issued_pairs = useful_owners = issued_owners = 0
        for g in groups:
            most = max(g)
            useful_pairs += sum(k * (k - 1) for k in g)
            issued_pairs += len(g) * most * (most - 1)
            useful_owners += sum(g)
            issued_owners += len(g) * most
        return useful_pairs / issued_pairs, useful_owners / issued_owners

    in_order = [counts[a:a + 8] for a in range(0, n - 7, 8)]
    shuffled = counts[:]
    random.Random(1).shuffle(shuffled)
    in_random = [shuffled[a:a + 8] for a in range(0, n - 7, 8)]
    print('lane use, clip / owner loop: row order %.2f / %.2f, shuffled %.2f / %.2f' % (lane_use(in_order) + lane_use(in_random)))


if __name__ == '__main__':
    main()
