"""The numbers do not depend on the Numba cache: a cold compile and a warm cache give the same bits.

Numba compiles a kernel afresh when its cache is empty and loads object code when it is warm. A
fresh compile can inline a callee's LLVM IR, a cached callee cannot be inlined; with fast-math
flags (reassociation, contraction into FMA) the two then round differently (measured: about
1e-13 relative on the simulated statistics). The kernels are compiled IEEE-strict, so the cache
history cannot change a bit. This test runs one coupled simulation (dynamic and quasi-static
lines) in two fresh processes, with a cold and then a warm cache. (A third history, the platform
kernels compiled afresh against cached mooring kernels, was checked by hand to agree too.)
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

TESTS = Path(__file__).parent

SCRIPT = """
import hashlib, sys
import numpy as np
sys.path.insert(0, {tests!r})
import test_simulate as T
from moorlife import simulate as sim
h = hashlib.sha256()
for kind in ("dynamic", "quasistatic"):
    m = T.moored("MS3", kind)
    out = sim.simulate_batch(T.sea(2), case_ids=np.array([3, 4]), mooring_system="MS3", seed=5, model_inputs=m,
                             sim_cfg={{**T.SIM, "duration": 60.0, "transient": 10.0}}, fatigue_cfg={{}},
                             stats_cfg={{"block": 10.0, "method": "lmoments"}})
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
