"""Shared fixtures: the source tree's examples and the CLI built with the module (the reference for
"equal to the last bit")."""
import json
import os
import subprocess

import pytest

SOURCE = os.environ.get("MACHDYN_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
CLI = os.environ.get("MACHDYN_CLI", "machdyn")


def example(name: str) -> str:
    return os.path.join(SOURCE, "examples", name)


def run_cli(*args, check=True) -> subprocess.CompletedProcess:
    p = subprocess.run([CLI, *map(str, args)], capture_output=True, text=True)
    if check and p.returncode != 0:
        raise AssertionError(f"machdyn {' '.join(map(str, args))} exited {p.returncode}: {p.stderr}")
    return p


def cli_json(*args) -> dict:
    return json.loads(run_cli(*args).stdout)


@pytest.fixture
def tmp(tmp_path):
    return tmp_path
