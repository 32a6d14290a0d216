"""The run's check for temporary folders left behind (tests/conftest.py,
``pytest_sessionfinish``) fails a run in pytest-xdist's workers as it does in one process,
and a clean run leaves its temporary folder removed.

Each case is a pytest run of its own on a one-test file, with tests/conftest.py loaded as a
plugin (``-p conftest``) and a temporary folder of its own (``TMPDIR``)."""
import os
import subprocess
import sys
import textwrap

import pytest

TESTS_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
LEFT_NAME = "roadsigns-left-here"
TEST_FILE = textwrap.dedent("""
    import os
    import tempfile


    def test_one():
        if {leave}:
            os.mkdir(os.path.join(tempfile.gettempdir(), "{name}"))
""")


def run_pytest(tmp_path, workers: int, leave: bool):
    """(return code, output, what is left in the run's TMPDIR)."""
    test_file = tmp_path / "test_one.py"
    test_file.write_text(TEST_FILE.format(leave=leave, name=LEFT_NAME))
    run_tmp = tmp_path / "tmp"
    run_tmp.mkdir()
    # not a worker of the outer run (without PYTEST_XDIST_WORKER the run makes its own folder)
    env = {k: v for k, v in os.environ.items() if not k.startswith("PYTEST_")}
    env.update(TMPDIR=str(run_tmp), PYTHONPATH=TESTS_DIR)
    p = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "conftest", "-p", "no:cacheprovider",
                        "-n", str(workers), "--rootdir", str(tmp_path), str(test_file)],
                       cwd=str(tmp_path), env=env, capture_output=True, text=True, timeout=300)
    return p.returncode, p.stdout + p.stderr, sorted(os.listdir(run_tmp))


@pytest.mark.parametrize("workers", [0, 2])
def test_a_folder_left_behind_fails_the_run(tmp_path, workers):
    code, output, _ = run_pytest(tmp_path, workers, leave=True)
    assert code == pytest.ExitCode.TESTS_FAILED, output
    assert "1 passed" in output, output
    line = next(t for t in output.splitlines() if t.startswith("Temporary folders left behind in"))
    expected = [LEFT_NAME] if workers == 0 else [os.path.join(w, LEFT_NAME) for w in ("gw0", "gw1")]
    assert any(line.endswith(e) for e in expected), line


def test_a_clean_run_in_workers_passes_and_removes_its_folder(tmp_path):
    code, output, left = run_pytest(tmp_path, 2, leave=False)
    assert code == pytest.ExitCode.OK, output
    assert "1 passed" in output, output
    assert left == [], left
