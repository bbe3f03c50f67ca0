"""Experiment: the rotor thrust T(W) as a sixth RBF coordinate (beyond the paper's 5-D space).

Usage::

    .venv/bin/python validation/rbf_thrust_coordinate.py RESULTS MS1 [MS5 ...]

For each system, fits the lifecycle RBF (default settings) on the stored training states in the
paper's 5-D space and in 6-D spaces that add ``T(W)`` (the NREL 5 MW thrust of the hub wind,
``config/platform.yaml``) scaled to a range of 1 (``6d_T``) or 0.5 (``6d_T0.5``), and prints the
validation r on the 225 states. Motivation: the damage of the lines away from the waves peaks
in a narrow band of wind speed just above rated (11.4-12.5 m/s), narrower than any useful shape
parameter in W; in T(W) that band is the maximum of one coordinate.
"""

from __future__ import annotations

import sys
import time
import warnings
from typing import NamedTuple

import numpy as np
import xarray as xr

from moorlife import lifecycle as lc
from moorlife import names, rbf, turbine
from moorlife.io import read_yaml

#: The spaces compared: name and the range of T(W) in scaled units (None: the paper's 5-D space).
SPACES = (("5d", None), ("6d_T", 1.0), ("6d_T0.5", 0.5))


class Study(NamedTuple):
    """One system's stored states in the paper's space, for the experiments' own fits."""

    settings: lc.RBFSettings  # the schema defaults of lifecycle.rbf
    grid: np.ndarray  # Rippa's shape grid
    sims: xr.Dataset  # the simulated states that are also in the selection
    train: np.ndarray  # boolean masks of the roles
    validate: np.ndarray
    x: np.ndarray  # the 5-D points, with the selection's scaling lo, span
    lo: np.ndarray
    span: np.ndarray
    is_direction: np.ndarray


def load_study(results: str, ms: str, cases0: xr.Dataset) -> Study:
    """The stores of system ``ms`` under ``results`` aligned with the selection ``cases0``."""
    st = lc.RBFSettings.from_config(None, source="lifecycle.rbf")  # the schema defaults
    sims = xr.open_zarr(f"{results}/{ms}/simulations.zarr", consolidated=False).load()
    dim = names.CASE
    common = np.intersect1d(cases0[dim].values, sims[dim].values)
    cases, sims = cases0.sel({dim: common}), sims.sel({dim: common})
    role = np.array([str(v) for v in cases["role"].astype(object).values])
    lo, span = lc._selection_scaling(cases)
    return Study(
        settings=st,
        grid=rbf.shape_grid(st.grid_min, st.grid_max, st.grid_n),
        sims=sims,
        train=role == "train",
        validate=role == "validate",
        x=lc._points(cases, dim),
        lo=lo,
        span=span,
        is_direction=np.array([v.endswith("dir") for v in names.METOCEAN_VARS]),
    )


def loo_pick(pred: dict, score: dict, cands, y_val: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Per output, the candidate of ``cands`` with the smallest ``score`` (a leave-one-out RMS on the
    training states): the validation r of the picked predictions ``pred[c]``, and the picks."""
    k = np.argmin(np.stack([score[c] for c in cands]), axis=0)
    p = np.column_stack([pred[cands[kj]][:, j] for j, kj in enumerate(k)])
    return lc.validation_metrics(p, y_val)["r"], k


def print_table(labels: list[str], res: dict, width: int) -> None:
    """One row per output (the S-N damage only: T-N is the same for m = 3), then the min and the mean."""
    for j, lab in enumerate(labels):
        if "_tn" in lab:
            continue
        print("  ", lab.ljust(16), *[f"{res[k][j]:{width}.4f}" for k in res])
    print("   min".ljust(19), *[f"{res[k].min():{width}.4f}" for k in res])
    print("   mean".ljust(19), *[f"{res[k].mean():{width}.4f}" for k in res], flush=True)


def validation_r(results: str, ms: str, cases0: xr.Dataset, ws: np.ndarray, ct: np.ndarray) -> tuple[list[str], dict]:
    """Validation r per output of one system in each space of :data:`SPACES`."""
    s = load_study(results, ms, cases0)
    st, grid, tr, va, x, lo, span, mask = s.settings, s.grid, s.train, s.validate, s.x, s.lo, s.span, s.is_direction
    cols = lc.output_columns(s.sims, names.CASE, st.outputs)
    y = lc.stack_outputs(s.sims, names.CASE, cols)
    isd = np.array([c[0].startswith("damage") for c in cols])
    thrust = turbine.thrust(x[:, 0], ws, ct)
    tmax = turbine.thrust(np.linspace(0, 30, 3001), ws, ct).max()
    res = {}
    for name, w in SPACES:
        if w is None:
            X, m_, l_, s_ = x, mask, lo, span
        else:
            X = np.column_stack([x, thrust])
            m_, l_, s_ = np.r_[mask, False], np.r_[lo, 0.0], np.r_[span, tmax / w]
        t = time.time()
        m = rbf.fit_rbf(
            X[tr], y[tr], is_direction=m_, log_output=isd, shapes=grid, smoothing=st.smoothing, lo=l_, span=s_
        )
        res[name] = lc.validation_metrics(rbf.predict_rbf(m, X[va]), y[va])["r"]
        print(ms, name, "%.0f s" % (time.time() - t), flush=True)
    return [lc._label(c) for c in cols], res


def main(argv: list[str]) -> int:
    warnings.filterwarnings("ignore")
    results = argv[1]
    ws, ct = turbine.ct_table(read_yaml("config/platform.yaml")["turbine"])
    cases0 = xr.open_zarr(f"{results}/selection/cases.zarr", consolidated=False).load()
    for ms in argv[2:]:
        labels, res = validation_r(results, ms, cases0, ws, ct)
        for j, lab in enumerate(labels):
            if "_tn" in lab:
                continue
            print("  ", lab.ljust(16), *[f"{res[k][j]:.4f}" for k in res])
        print("   min", *[f"{res[k].min():.4f}" for k in res], "mean", *[f"{res[k].mean():.4f}" for k in res])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
