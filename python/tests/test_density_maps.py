"""Density maps through the Python module (relax(density_map=...), stipple) against the tool on
the same image, bit for bit: the image is a grey PNG written here with the standard library,
read by the tool with --transfer linear --no-invert, so that its densities are the array's."""
import struct
import zlib

import numpy as np
import pytest

import pybluetile as bt


def write_grey_png(path, rows):
    """An 8-bit greyscale PNG of `rows` (a 2-D uint8 array, row 0 at the top)."""
    height, width = rows.shape
    raw = b"".join(b"\x00" + rows[r].astype(np.uint8).tobytes() for r in range(height))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    header = struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0)
    path.write_bytes(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw))
                     + chunk(b"IEND", b""))


# A map that is 0 and 1 only, so that the tool's 8-bit decoding and NumPy's float64 agree exactly:
# a dense disc on a faint-free background with a dense band along the bottom, 24 x 16 (wider than
# tall, to exercise the aspect ratio).
def sample_map():
    y, x = np.mgrid[0:16, 0:24]
    disc = (x - 8) ** 2 + (y - 6) ** 2 < 30
    band = y >= 13
    return (disc | band).astype(np.uint8)


def load_points(path):
    return np.loadtxt(path, comments="#", ndmin=2)[:, :2]


def test_relax_with_a_density_map_matches_the_tool(tool, tmp_path):
    grey = sample_map()
    write_grey_png(tmp_path / "map.png", grey * 255)
    out = tmp_path / "relaxed.txt"
    tool("relax", "--density-map", tmp_path / "map.png", "--transfer", "linear", "--no-invert", "--count", 200,
         "--iterations", 6, "--seed", 3, "--output", out)
    density = grey.astype(np.float64)
    points = bt.relax(count=200, iterations=6, seed=3, density_map=density)
    assert points.shape == (200, 2)
    assert np.array_equal(points, load_points(out))
    # Bounded cells and another weight exponent, as --bounded --weight-exponent 1.
    tool("relax", "--density-map", tmp_path / "map.png", "--transfer", "linear", "--no-invert", "--count", 120,
         "--iterations", 4, "--seed", 8, "--bounded", "--weight-exponent", 1, "--output", tmp_path / "b.txt")
    bounded = bt.relax(count=120, iterations=4, seed=8, density_map=density, bounded=True, weight_exponent=1.0)
    assert np.array_equal(bounded, load_points(tmp_path / "b.txt"))
    # The points follow the map: none where it is 0 (a texel of the 24 x 16 map over the unit square).
    column = np.minimum((points[:, 0] * 24).astype(int), 23)
    row = 15 - np.minimum((points[:, 1] * 16).astype(int), 15)
    assert np.mean(grey[row, column] == 1) > 0.97


def test_history_counts_the_sites_without_density_as_the_log(tool, tmp_path):
    # Uniform starts on a map that is 0 outside a disc and a band: the sites whose cells have no
    # density stay put, counted in the log's zero_density column (the history had no such key).
    grey = sample_map()
    write_grey_png(tmp_path / "map.png", grey * 255)
    start = bt.random_points(200, seed=5)
    np.savetxt(tmp_path / "start.txt", start, fmt="%.17g")
    tool("relax", "--input", tmp_path / "start.txt", "--density-map", tmp_path / "map.png", "--transfer", "linear",
         "--no-invert", "--iterations", 3, "--output", tmp_path / "out.txt", "--log", tmp_path / "log.csv")
    log = np.loadtxt(tmp_path / "log.csv", delimiter=",", skiprows=1)
    points, history = bt.relax(start, iterations=3, density_map=grey.astype(np.float64), history=True)
    assert np.array_equal(points, load_points(tmp_path / "out.txt"))
    assert np.array_equal(history["zero_density"], log[:, 6]) and history["zero_density"].min() > 10
    assert history["zero_density"].dtype == history["coincident"].dtype


def test_stipple_matches_the_tool(tool, tmp_path):
    grey = sample_map()
    write_grey_png(tmp_path / "map.png", grey * 255)
    out = tmp_path / "dots.txt"
    tool("stipple", "--image", tmp_path / "map.png", "--transfer", "linear", "--no-invert", "--count", 150,
         "--iterations", 8, "--seed", 4, "--output", out)
    points, info = bt.stipple(grey.astype(np.float32), count=150, iterations=8, seed=4, info=True)
    assert np.array_equal(points, load_points(out))
    # The drawing spans the map's aspect ratio, its longer side 1: 24 x 16 gives 1 x 2/3.
    assert info["width"] == 1.0 and info["height"] == pytest.approx(16 / 24, abs=0)
    assert np.all(points[:, 0] >= 0) and np.all(points[:, 0] < 1)
    assert np.all(points[:, 1] >= 0) and np.all(points[:, 1] < info["height"])
    assert info["iterations"] == 8
    # Dots that just touch where the map is densest: half the hexagonal spacing of 150 dots over
    # the dense area (the map's mean of 1s times the domain's area).
    dense_area = grey.mean() * info["width"] * info["height"]
    assert info["dot_radius"] == pytest.approx(0.5 * np.sqrt(2 / (np.sqrt(3) * 150 / dense_area)), rel=1e-12)
    # Periodic cells, as --periodic.
    tool("stipple", "--image", tmp_path / "map.png", "--transfer", "linear", "--no-invert", "--count", 60,
         "--iterations", 3, "--seed", 2, "--periodic", "--output", tmp_path / "p.txt")
    assert np.array_equal(bt.stipple(grey.astype(np.float64), count=60, iterations=3, seed=2, periodic=True),
                          load_points(tmp_path / "p.txt"))


def test_density_map_arguments_are_checked():
    with pytest.raises(ValueError, match=r"density_map: expected a 2-D array of shape \(rows, columns\)"):
        bt.stipple(np.ones(5), count=10)
    with pytest.raises(TypeError, match="density_map: expected float64 or float32, got int64"):
        bt.stipple(np.ones((4, 4), dtype=np.int64), count=10)
    with pytest.raises(ValueError, match="density_map: values must be finite and >= 0, got -1.* at row 1, column 2"):
        m = np.ones((3, 3))
        m[1, 2] = -1
        bt.relax(count=10, density_map=m)
    with pytest.raises(ValueError, match="count: expected 1 to 100000000, got 0"):
        bt.stipple(np.ones((4, 4)), count=0)
    with pytest.raises(ValueError, match="weight_exponent: expected 0 to 8, got 9"):
        bt.stipple(np.ones((4, 4)), count=10, weight_exponent=9)
    with pytest.raises(ValueError, match="weight_exponent: expected 0 to 8, got nan"):
        bt.relax(count=10, density_map=np.ones((2, 2)), weight_exponent=float("nan"))
    # A map that is zero everywhere is the library's error, with the tool's wording.
    with pytest.raises(bt.Error, match="zero"):
        bt.stipple(np.zeros((4, 4)), count=10)
