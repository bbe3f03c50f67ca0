"""Experiment: log(Hs) instead of Hs as the input coordinate of the reconstruction.

Usage::

    OMP_NUM_THREADS=1 python validation/rbf_log_hs.py C [reconstruction.py arguments]
    OMP_NUM_THREADS=1 python validation/rbf_log_hs.py 0 --results results --systems MS1 MS6 \\
        --work DIR --variant loghs0= --variant m52_loghs0=validation/overlays/gp_matern52.yaml

Wave loads grow as a power of Hs, so ``log10`` of the damage should be closer to linear in
``log Hs`` than in Hs, and the storm hours, which span a quarter of the normalised Hs range,
are compressed. This script wraps ``moorlife.lifecycle.adapters.fit_outputs`` and
``predict_outputs`` so that the Hs column of every training, validation and hindcast point,
and the Hs offset and range of the normalisation, become ``log(Hs + C)`` (``C`` in metres,
the first argument), then runs ``validation/reconstruction.py`` with the remaining arguments:
every variant of that run, the RBF or the GP, sees the transformed coordinate. Measured in
``validation/reconstruction.md`` section 17 (not adopted).
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from moorlife import names
from moorlife.lifecycle import adapters

IH = names.METOCEAN_VARS.index("hs")
_FIT, _PREDICT = adapters.fit_outputs, adapters.predict_outputs


def log_hs(points: np.ndarray, c: float) -> np.ndarray:
    """The points with Hs replaced by ``log(Hs + c)`` (Hs floored at 1 mm)."""
    x = np.array(points, dtype=float, copy=True)
    x[:, IH] = np.log(np.clip(x[:, IH], 1e-3, None) + c)
    return x


def patch(c: float) -> None:
    """Route every fit and prediction of the lifecycle adapters through :func:`log_hs`."""

    def fit(points, values, cols, settings, lo=None, span=None, **kw):
        if lo is not None and span is not None:
            lo, span = np.array(lo, dtype=float), np.array(span, dtype=float)
            a, b = np.log(max(lo[IH], 1e-3) + c), np.log(lo[IH] + span[IH] + c)
            lo[IH], span[IH] = a, b - a
        return _FIT(log_hs(points, c), values, cols, settings, lo=lo, span=span, **kw)

    def predict(model, points, **kw):
        return _PREDICT(model, log_hs(points, c), **kw)

    adapters.fit_outputs, adapters.predict_outputs = fit, predict


if __name__ == "__main__":
    patch(float(sys.argv[1]))
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    import reconstruction

    sys.exit(reconstruction.main(sys.argv[2:]))
