"""Numba's cache is keyed by the package's whole source (``moorlife._numba_cache``).

Numba invalidates a cached kernel only when its own file changes (numba/numba#1833): a kernel
that calls one of another module would keep the old code. The package's cache directory is
named by a digest of all its source, so an edit anywhere starts a fresh cache.
"""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
from pathlib import Path

import numba

import moorlife
from moorlife import _numba_cache as nc

CALLER = """
from numba import njit
from pkg.callee import g

@njit(cache=True)
def f(x):
    return g(x) + 1.0
"""


def _write_package(root: Path, value: float) -> None:
    pkg = root / "pkg"
    pkg.mkdir(exist_ok=True)
    (pkg / "__init__.py").write_text(
        "from pathlib import Path\nfrom moorlife import _numba_cache\n"
        "CACHE = _numba_cache.pin(Path(__file__).resolve().parent)\n"
    )
    (pkg / "callee.py").write_text(f"from numba import njit\n\n@njit(cache=True)\ndef g(x):\n    return x * {value}\n")
    (pkg / "caller.py").write_text(textwrap.dedent(CALLER))


def _run(root: Path) -> str:
    env = {k: v for k, v in os.environ.items() if k != "NUMBA_CACHE_DIR"}
    env["PYTHONPATH"] = os.pathsep.join([str(root), *sys.path])
    code = "import pkg; from pkg.caller import f; print(f(2.0), pkg.CACHE)"
    return subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True).stdout


def test_an_edit_of_a_called_module_is_not_served_from_the_cache(tmp_path):
    _write_package(tmp_path, 3.0)
    value, cache = _run(tmp_path).split()
    assert float(value) == 7.0
    assert any(Path(cache).rglob("*.nbi")), "the kernels were not cached"
    # the same size, a new value: only the callee's module changes
    _write_package(tmp_path, 5.0)
    value2, cache2 = _run(tmp_path).split()
    assert float(value2) == 11.0
    assert cache2 != cache
    # unchanged source: the same directory, served from the cache
    assert _run(tmp_path).split() == [value2, cache2]


def test_the_digest_follows_every_source_file(tmp_path):
    (tmp_path / "sub").mkdir()
    (tmp_path / "a.py").write_text("A = 1\n")
    (tmp_path / "sub" / "b.py").write_text("B = 1\n")
    (tmp_path / "notes.txt").write_text("not source\n")
    d0 = nc.source_digest(tmp_path)
    (tmp_path / "notes.txt").write_text("still not source\n")
    assert nc.source_digest(tmp_path) == d0
    (tmp_path / "sub" / "b.py").write_text("B = 2\n")
    assert nc.source_digest(tmp_path) != d0


def test_cache_dir_respects_numba_cache_dir_and_an_unwritable_package(tmp_path, monkeypatch):
    tag = nc.PREFIX + nc.source_digest(tmp_path)
    assert nc.cache_dir(tmp_path) == tmp_path / "__pycache__" / tag
    assert nc.cache_dir(tmp_path, "/scratch/nb") == Path("/scratch/nb") / tag
    # a child process that inherited the pinned directory keeps it
    assert nc.cache_dir(tmp_path, f"/scratch/nb/{tag}") == Path("/scratch/nb") / tag
    monkeypatch.setattr(nc.os, "access", lambda *a: False)
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    assert nc.cache_dir(tmp_path) == tmp_path / "xdg" / "moorlife" / tag


def test_the_package_pins_numba_to_its_source():
    assert numba.config.CACHE_DIR == str(moorlife.NUMBA_CACHE_DIR)
    assert Path(moorlife.NUMBA_CACHE_DIR).name == nc.PREFIX + nc.source_digest(Path(moorlife.__file__).parent)
