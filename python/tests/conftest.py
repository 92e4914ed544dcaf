"""A run whose tests were all skipped exits 77, which ctest reports as skipped (not passed)."""
import os
import sys

import pytest

sys.path.insert(0, os.path.dirname(__file__))


def pytest_sessionfinish(session, exitstatus):
    reporter = session.config.pluginmanager.get_plugin("terminalreporter")
    if reporter and exitstatus == 0 and reporter.stats.get("skipped") and not reporter.stats.get("passed"):
        session.exitstatus = 77


@pytest.fixture
def out_dir(request):
    path = os.path.join(os.environ.get("VT_TEST_OUTPUT_DIR", "/tmp/vtouching-python-tests"), request.node.name)
    os.makedirs(path, exist_ok=True)
    return path
