"""Experiment: how far the stack's weights and the validation r can be trusted, by the bootstrap.

Usage::

    OMP_NUM_THREADS=1 python validation/stack_scatter.py --results results --systems MS1 \\
        --overlay validation/overlays/gp_matern52_wind_all_frozen_sdT_stack.yaml > MS1.md

For each system, the overlay's reconstruction (``lifecycle.rbf.choose: stack``) is fitted once,
as the harness (``reconstruction.py``) fits it, and both parts of the blend are kept whole: the
GP of the paper space (``a``) and of the second space (``b``), each on every output. Then, with
no further fit:

- **the weight's scatter**: the training rows are resampled with replacement (``--boot-train``
  times, seeded) and :func:`moorlife.lifecycle.stack_weights` is taken again on each resample's
  leave-one-out predictions. Reported per output: the weight chosen on all rows, the share of
  resamples that take ``a`` whole (1) or ``b`` whole (0), the mean weight (the bagged weight),
  and the difference of the two spaces' leave-one-out RMS in units over its bootstrap sd (``z``:
  is the leave-one-out's preference larger than its own sampling scatter?);
- **the validation r's scatter**: the 225 validation states are resampled the same way
  (``--boot-valid`` times) and the r of ``a``, ``b``, the chosen blend and the bagged blend are
  taken on each resample. Reported: each r on all states, the sd of the chosen blend's r, the
  share of resamples where it is 0.98 or more, and the paired sd of ``r_a - r_b`` (is the
  validation states' preference larger than their own sampling scatter?).

The bagged weight is chosen on the training states alone (the mean over the training resamples):
the validation states steer nothing. Measured in ``validation/reconstruction.md`` section 31.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from moorlife import lifecycle
from moorlife.lifecycle import fit
from moorlife.lifecycle.validation import pearson_r


def fit_parts(cfg: dict[str, Any], stores: dict[str, Any]) -> dict[str, Any]:
    """The stack's fit, its two parts whole, and the leave-one-out predictions its weights are taken on."""
    from reconstruction import ROOT

    from moorlife.stages import thrust_for

    settings = lifecycle.rbf_settings(cfg["lifecycle"]["rbf"])
    if settings.choose != "stack":
        raise SystemExit(f"stack_scatter.py: the overlay sets lifecycle.rbf.choose = {settings.choose!r}, not 'stack'")
    thrust = thrust_for(settings, ROOT / cfg["platform"], cfg["simulation"]["wind"])
    seen: dict[str, Any] = {}
    original, weights = fit._stack_gp, fit.stack_weights

    def capture(fits: Any, y: Any, cols: Any, logs: Any, candidates: Any, **kw: Any) -> Any:
        seen["loo"] = (y, y - fits[0][1], y - fits[1][1], logs)
        for name, w in (("a", 1.0), ("b", 0.0)):  # each part whole: the blend with the weight 1 or 0
            fit.stack_weights = lambda v, *_, w=w, **kw: (np.full(v.shape[1], w), np.zeros(v.shape[1]))
            seen[name] = original(fits, y, cols, logs, candidates, **kw)
        fit.stack_weights = weights
        return original(fits, y, cols, logs, candidates, **kw)

    fit._stack_gp = capture
    try:
        fitted = lifecycle.fit_reconstruction(stores["cases"], stores["sims"], settings=settings, thrust=thrust)
    finally:
        fit._stack_gp, fit.stack_weights = original, weights
    x, y = fitted.points[fitted.valid], fitted.values[fitted.valid]
    return {
        "labels": [fit._label(c) for c in fitted.cols],
        "loo": seen["loo"],
        "valid": y,
        "pred": {
            k: fit.predict_outputs(m, x) for k, m in (("a", seen["a"]), ("b", seen["b"]), ("stack", fitted.model))
        },
        "candidates": tuple(settings.spaces),
    }


def blend(a: np.ndarray, b: np.ndarray, w: np.ndarray, logs: np.ndarray) -> np.ndarray:
    """``w a + (1 - w) b``, geometric for the ``log10`` outputs (as the stack predicts)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        geo = a**w * b ** (1.0 - w)
    return np.where(logs, geo, w * a + (1.0 - w) * b)


def scatter(parts: dict[str, Any], boot_train: int, boot_valid: int, seed: int) -> pd.DataFrame:
    """Per output: the weight's and the validation r's bootstrap figures (see the module's text)."""
    y, la, lb, logs = (np.asarray(v) for v in parts["loo"])
    rng = np.random.default_rng(seed)
    m = y.shape[0]
    w_all, _ = fit.stack_weights(y, la, lb, logs)
    ws, dz = np.empty((boot_train, y.shape[1])), np.empty((boot_train, y.shape[1]))
    for k in range(boot_train):
        i = rng.integers(0, m, m)
        ws[k], _ = fit.stack_weights(y[i], la[i], lb[i], logs)
        dz[k] = np.sqrt(np.mean((y[i] - la[i]) ** 2, axis=0)) - np.sqrt(np.mean((y[i] - lb[i]) ** 2, axis=0))
    d_all = np.sqrt(np.mean((y - la) ** 2, axis=0)) - np.sqrt(np.mean((y - lb) ** 2, axis=0))
    w_bag = np.round(ws.mean(axis=0), 2)
    s, pa, pb = parts["valid"], parts["pred"]["a"], parts["pred"]["b"]
    pred = {"a": pa, "b": pb, "stack": parts["pred"]["stack"], "bagged": blend(pa, pb, w_bag, logs)}
    check = blend(pa, pb, w_all, logs)
    if not np.allclose(check, pred["stack"], rtol=1e-9, atol=0):
        raise SystemExit("stack_scatter.py: the blend of the parts is not the stack's prediction")
    n = s.shape[0]
    j = rng.integers(0, n, (boot_valid, n))
    rb = {k: pearson_r(p[j], s[j], axis=-2) for k, p in pred.items()}  # (boot_valid, n_out)
    out = pd.DataFrame(index=parts["labels"])
    out["w"] = w_all
    out["P(w=1)"] = (ws >= 1.0).mean(axis=0)
    out["P(w=0)"] = (ws <= 0.0).mean(axis=0)
    out["w_bag"] = w_bag
    out["w_sd"] = ws.std(axis=0)
    out["loo_z"] = d_all / dz.std(axis=0)  # < 0: a's leave-one-out RMS is smaller
    for k, p in pred.items():
        out[f"r_{k}"] = pearson_r(p, s, axis=0)
    out["r_stack_sd"] = rb["stack"].std(axis=0)
    out["P(r_stack>=0.98)"] = (rb["stack"] >= 0.98).mean(axis=0)
    out["r_bagged_sd"] = rb["bagged"].std(axis=0)
    out["P(r_bagged>=0.98)"] = (rb["bagged"] >= 0.98).mean(axis=0)
    diff = rb["a"] - rb["b"]
    out["r_a-r_b"] = out["r_a"] - out["r_b"]
    out["r_a-r_b_sd"] = diff.std(axis=0)
    return out


def main(argv: list[str] | None = None) -> int:
    import reconstruction  # beside this script: sys.path[0]

    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--results", type=Path, default=reconstruction.ROOT / "results")
    p.add_argument("--systems", nargs="+", default=["MS1", "MS2", "MS3", "MS4", "MS5", "MS6"])
    p.add_argument("--overlay", action="append", required=True, help="an overlay setting choose: stack (repeatable)")
    p.add_argument("--boot-train", type=int, default=500)
    p.add_argument("--boot-valid", type=int, default=2000)
    p.add_argument("--seed", type=int, default=20261207)
    a = p.parse_args(argv)
    cfg = reconstruction.study(a.overlay)
    for ms in a.systems:
        stores = reconstruction.load(a.results, ms)
        if stores is None:
            print(f"{ms}: no simulations under {a.results}, skipped", file=sys.stderr)
            continue
        parts = fit_parts(cfg, stores)
        table = scatter(parts, a.boot_train, a.boot_valid, a.seed)
        a_name, b_name = parts["candidates"][0], parts["candidates"][-1]
        print(f"\n### {ms} (a: {a_name}, b: {b_name})\n")
        print(table.to_markdown(floatfmt=".4f"))
        low = table[["r_a", "r_b", "r_stack", "r_bagged"]].min()
        print(f"\nlowest output: {', '.join(f'{k} {v:.4f}' for k, v in low.items())}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
