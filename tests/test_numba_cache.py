"""The numbers do not depend on the Numba cache: a cold compile and a warm cache give the same bits.

Numba compiles a kernel afresh when its cache is empty and loads object code when it is warm. A
fresh compile can inline a callee's LLVM IR, a cached callee cannot be inlined; with fast-math
flags (reassociation, contraction into FMA) the two then round differently (measured: about
1e-13 relative on the simulated statistics). The kernels are compiled IEEE-strict, so the cache
history cannot change a bit.

The behavioural test runs one coupled simulation (dynamic and quasi-static lines) in two fresh
processes, with a cold and then a warm cache. With the fast-math flags restored, the dynamic
lines give another digest cold and warm, the quasi-static ones alone do not (checked by hand):
a flag on a kernel that does not change these digests would pass it, so the static test keeps
every kernel free of fast-math flags. (A third history, the platform kernels compiled afresh
against cached mooring kernels, was checked by hand to agree too.)
"""

from __future__ import annotations

import ast
import os
import subprocess
import sys
from pathlib import Path

import moorlife

TESTS = Path(__file__).parent
PKG = Path(moorlife.__file__).parent  # the package under test, as imported

#: Kernels allowed fast-math flags: a leaf kernel (no callee to inline, so no cache history
#: can change its code) whose sums are ordered by the code itself.
FASTMATH_ALLOWED = {("rbf/kernels.py", "_weighted_sum")}

SCRIPT = """
import hashlib, sys
import numpy as np
sys.path.insert(0, {tests!r})
import test_simulate as T
h = hashlib.sha256()
for out in T.short_coupled_runs("MS3").values():
    for k in sorted(out):
        v = np.asarray(out[k])
        if v.dtype.kind in "fiu":
            h.update(k.encode()); h.update(np.ascontiguousarray(v).tobytes())
print(h.hexdigest())
"""


def _digest(cache: Path) -> str:
    env = {**os.environ, "NUMBA_CACHE_DIR": str(cache)}
    run = subprocess.run(
        [sys.executable, "-c", SCRIPT.format(tests=str(TESTS))], env=env, capture_output=True, text=True
    )
    assert run.returncode == 0, run.stderr[-3000:]
    return run.stdout.strip().splitlines()[-1]


def test_cold_and_warm_numba_cache_give_identical_bits(tmp_path):
    cache = tmp_path / "numba"
    cold = _digest(cache)
    assert any(cache.rglob("*.nbi")), "the first run filled no cache"
    assert _digest(cache) == cold


def _fastmath_kernels() -> list[str]:
    """``file:function`` of every njit/jit kernel of moorlife compiled with fast-math flags."""
    found = []
    for path in sorted(PKG.rglob("*.py")):
        rel = path.relative_to(PKG).as_posix()
        for node in ast.walk(ast.parse(path.read_text())):
            if not isinstance(node, ast.FunctionDef):
                continue
            for dec in node.decorator_list:
                target = dec.func if isinstance(dec, ast.Call) else dec
                name = target.attr if isinstance(target, ast.Attribute) else getattr(target, "id", "")
                if name not in {"njit", "jit"} or not isinstance(dec, ast.Call):
                    continue
                flags = [k for k in dec.keywords if k.arg == "fastmath"]
                off = all(isinstance(k.value, ast.Constant) and k.value.value in (False, None) for k in flags)
                if flags and not off and (rel, node.name) not in FASTMATH_ALLOWED:
                    found.append(f"{rel}:{node.name}")
    return found


def test_no_kernel_compiled_with_fastmath():
    assert _fastmath_kernels() == [], "IEEE-strict kernels only (issue 20): remove fastmath"


def test_the_fastmath_scan_sees_a_flag(tmp_path, monkeypatch):
    """The scan is not blind: a kernel given fast-math flags is reported."""
    src = tmp_path / "moorlife" / "mooring"
    src.mkdir(parents=True)
    (src / "k.py").write_text(
        "from numba import njit\nimport numba\n\n"
        '@njit(cache=True, fastmath={"nsz", "arcp", "contract", "afn", "reassoc"})\ndef a(x):\n    return x\n\n'
        "@numba.njit(fastmath=True)\ndef b(x):\n    return x\n\n"
        "@njit(cache=True, fastmath=False)\ndef c(x):\n    return x\n"
    )
    monkeypatch.setattr(sys.modules[__name__], "PKG", tmp_path / "moorlife")
    assert _fastmath_kernels() == ["mooring/k.py:a", "mooring/k.py:b"]
