"""Shared fixtures of the Python package's tests: the `capstan` binary and its `--json`."""

import json
import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]

# Keys that are wall times: the one thing a Python call and a CLI run cannot share.
TIMINGS = {"setup_seconds", "solve_seconds", "seconds"}


def _binary() -> pathlib.Path:
    env = os.environ.get("CAPSTAN_BIN")
    if env:
        return pathlib.Path(env)
    exe = ROOT / "target" / "debug" / "capstan"
    if not exe.exists():
        subprocess.run(["cargo", "build", "--bin", "capstan"], cwd=ROOT, check=True)
    return exe


@pytest.fixture(scope="session")
def cli():
    """`cli("contact", "--set", "k=v")` -> the parsed `--json` object of the capstan binary."""
    exe = _binary()

    def run(*args):
        out = subprocess.run(
            [str(exe), "--quiet", *args, "--json"], capture_output=True, text=True, cwd=ROOT
        )
        assert out.returncode == 0, out.stderr
        return json.loads(out.stdout)

    return run


def without_timings(value):
    """`value` with every wall-time key removed, at any depth."""
    if isinstance(value, dict):
        return {k: without_timings(v) for k, v in value.items() if k not in TIMINGS}
    if isinstance(value, list):
        return [without_timings(v) for v in value]
    return value
