"""moorlife.io.log_to: what a rule's block and its child processes print goes to the rule's log."""

from __future__ import annotations

import subprocess
import sys

import pytest

from moorlife.io import log_to

# as Capytaine does in the BEM's spawned solver processes: its own logging handler on stdout
CHILD = """
import logging, sys
logging.basicConfig(level="WARNING", format="%(message)s", stream=sys.stdout)
logging.getLogger("capytaine").warning("water_depth > 5*wavelength (stdout)")
print("native-like stderr line", file=sys.stderr, flush=True)
"""


def test_child_process_output_goes_to_the_log_not_the_terminal(tmp_path, capfd):
    log = tmp_path / "logs" / "rule.log"
    with log_to(log) as logger:
        logger.info("from the rule")
        subprocess.run([sys.executable, "-c", CHILD], check=True)
    out, err = capfd.readouterr()
    text = log.read_text()
    for line in ("from the rule", "water_depth > 5*wavelength (stdout)", "native-like stderr line"):
        assert line in text
        assert line not in out + err
    print("after the block")
    assert "after the block" in capfd.readouterr().out  # descriptors restored


def test_failure_line_still_reaches_stderr(tmp_path, capfd):
    log = tmp_path / "rule.log"
    with pytest.raises(ValueError, match="bad value"):
        with log_to(log):
            raise ValueError("bad value")
    _, err = capfd.readouterr()
    assert "moorlife error: bad value" in err
    assert "bad value" in log.read_text()


def test_capture_fds_off_leaves_the_terminal(tmp_path, capfd):
    log = tmp_path / "rule.log"
    with log_to(log, capture_fds=False):
        subprocess.run([sys.executable, "-c", "print('on the terminal')"], check=True)
    assert "on the terminal" in capfd.readouterr().out
    assert "on the terminal" not in log.read_text()
