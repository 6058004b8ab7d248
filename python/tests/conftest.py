"""Shared fixtures: the CLI built beside the module (BSSRDF_EXE, set by ctest) and a runner for it."""
import json
import os
import subprocess

import pytest


@pytest.fixture(scope="session")
def cli():
    exe = os.environ.get("BSSRDF_EXE")
    if not exe or not os.path.exists(exe):
        pytest.skip("BSSRDF_EXE (the bssrdf executable) not set: run through ctest")

    def run(*args, check=True):
        done = subprocess.run([exe, *map(str, args)], capture_output=True, text=True)
        if check and done.returncode != 0:
            raise AssertionError(f"bssrdf {' '.join(map(str, args))}: exit {done.returncode}: {done.stderr}")
        return done

    run.json = lambda *args: json.loads(run(*args).stdout)
    return run
