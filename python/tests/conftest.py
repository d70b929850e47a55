"""Shared fixtures of the Python module's tests (run by CTest, see tests/CMakeLists.txt).

OVERFLIGHT_EXE is the `overflight` program the arrays are compared with;
OVERFLIGHT_SHARED_DATA the folder of real DEMs (tests needing one skip
without it). A run in which tests were skipped and none failed exits 77,
which CTest reports as Skipped rather than Passed.
"""
import os
import subprocess

import pytest

SKIPPED_EXIT_CODE = 77


@pytest.fixture
def overflight_exe():
    return os.environ.get("OVERFLIGHT_EXE", "overflight")


@pytest.fixture
def run_cli(overflight_exe):
    """Runs `overflight ARGS...`; returns the CompletedProcess (text)."""

    def run(*args):
        return subprocess.run([overflight_exe, *map(str, args)], capture_output=True, text=True)

    return run


@pytest.fixture
def shared_file():
    """Path of a file under the shared data folder; skips the test when absent."""

    def path(rel):
        p = os.path.join(os.environ.get("OVERFLIGHT_SHARED_DATA", ""), rel)
        if not os.path.exists(p):
            pytest.skip("shared data not present: " + p)
        return p

    return path


def pytest_sessionfinish(session, exitstatus):
    reporter = session.config.pluginmanager.get_plugin("terminalreporter")
    if exitstatus == 0 and reporter is not None and reporter.stats.get("skipped"):
        session.exitstatus = SKIPPED_EXIT_CODE
