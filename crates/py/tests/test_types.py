"""The type stubs and annotations users' type checkers read: the native module's stubs
(`_native.pyi`) against the built extension (mypy's `stubtest`), and the package's Python
modules and examples against those stubs (mypy, set up in pyproject.toml)."""

import pathlib
import subprocess
import sys

import pytest

pytest.importorskip("mypy")

PACKAGE = pathlib.Path(__file__).resolve().parents[1]


def run(args, cwd):
    """Runs `python -m <args>` in `cwd`; returns its exit code and output."""
    done = subprocess.run(
        [sys.executable, "-m", *args],
        cwd=cwd,
        capture_output=True,
        text=True,
        timeout=600,
    )
    return done.returncode, done.stdout + done.stderr


def test_native_stubs_match_the_extension(tmp_path):
    # In an empty folder: stubtest keeps its cache in the working directory.
    code, out = run(["mypy.stubtest", "frontier._native"], tmp_path)
    assert code == 0, out


def test_package_and_examples_type_check(tmp_path):
    code, out = run(["mypy", "--cache-dir", str(tmp_path / "mypy-cache")], PACKAGE)
    assert code == 0, out
