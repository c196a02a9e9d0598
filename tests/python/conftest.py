"""Fixtures of the Python package's tests: the package, the command line beside it, and
helpers to compare the two.

CTest runs these with PYTHONPATH and GRASPSYNTH_BINARY set (tests/CMakeLists.txt); run by hand
(`/usr/bin/python3 -m pytest tests/python`) they find build/python and build/apps/graspsynth
of this checkout."""

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
if "graspsynth" not in sys.modules and not os.environ.get("PYTHONPATH"):
    sys.path.insert(0, str(REPO / "build" / "python"))

import graspsynth  # noqa: E402


@pytest.fixture(scope="session")
def gs():
    return graspsynth


@pytest.fixture(scope="session")
def repo():
    return REPO


@pytest.fixture(scope="session")
def cli():
    """Runs the graspsynth command; returns the CompletedProcess (text), raising on a status
    other than the expected one."""
    binary = os.environ.get("GRASPSYNTH_BINARY", str(REPO / "build" / "apps" / "graspsynth"))

    def run(*args, stdin=None, expect=0):
        done = subprocess.run([binary, *map(str, args)], input=stdin, capture_output=True,
                              text=True, check=False)
        if expect is not None and done.returncode != expect:
            raise AssertionError(f"graspsynth {' '.join(map(str, args))} exited "
                                 f"{done.returncode}:\n{done.stderr}")
        return done

    return run


def load_json(path):
    with open(path, encoding="utf-8") as f:
        return json.load(f)
