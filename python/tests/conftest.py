import os
import pathlib
import subprocess

import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]


def _tool():
    path = pathlib.Path(os.environ.get("BLUETILE_BINARY", REPO / "build" / "bluetile"))
    if not path.is_file():
        pytest.fail(f"the bluetile tool is not at {path}: build it first (./setup.sh build) or set BLUETILE_BINARY")
    return path


@pytest.fixture(scope="session")
def tool():
    """Runs the bluetile tool; returns the CompletedProcess, which must have exited 0 unless check=False."""
    path = _tool()

    def run(*args, check=True):
        result = subprocess.run([str(path), *map(str, args)], capture_output=True, text=True,
                                stdin=subprocess.DEVNULL)
        if check and result.returncode != 0:
            raise AssertionError(f"bluetile {' '.join(map(str, args))} failed: {result.stderr}")
        return result

    return run
