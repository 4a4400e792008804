"""Shared fixtures: small generated maps (tests make their own inputs) and the CLI binary."""

import os
import pathlib
import struct
import zlib

import pytest

import frontier

ROOT = pathlib.Path(__file__).resolve().parents[3]


@pytest.fixture(scope="session")
def office():
    """A small office: 60 x 48 cells at 0.25 m."""
    return frontier.Map.generate("office", seed=3, size=(15, 12), resolution=0.25)


@pytest.fixture(scope="session")
def cli():
    """The `frontier` binary: $FRONTIER_BIN, else the workspace's debug or release build
    (CI builds it with `cargo test` before running these tests)."""
    given = os.environ.get("FRONTIER_BIN")
    if given:
        return given
    built = [str(ROOT / "target" / p / "frontier") for p in ("debug", "release")]
    found = [c for c in built if os.access(c, os.X_OK)]
    if not found:
        pytest.fail("no frontier binary: build it (cargo build -p frontier) or set FRONTIER_BIN")
    return max(found, key=os.path.getmtime)


@pytest.fixture(scope="session")
def write_png():
    """A function writing the (h, w) uint8 array ``pixels`` as a greyscale 8-bit PNG."""

    def write(path, pixels):
        h, w = pixels.shape
        raw = b"".join(b"\x00" + pixels[y].tobytes() for y in range(h))

        def chunk(kind, data):
            crc = struct.pack(">I", zlib.crc32(kind + data))
            return struct.pack(">I", len(data)) + kind + data + crc

        header = struct.pack(">IIBBBBB", w, h, 8, 0, 0, 0, 0)
        path.write_bytes(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header)
                         + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))

    return write
