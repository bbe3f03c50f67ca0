"""Experiment: the wind and the waves as vectors (polar embedding) in the RBF space.

Usage::

    .venv/bin/python validation/rbf_polar.py RESULTS MS1 [MS2 ...]

The paper's space puts a direction and a magnitude side by side: ``(W, theta_wind, Hs, Tp,
theta_wave)``, the directions compared on the circle. The mean load on a line is closer to a
*vector*: the rotor thrust ``T(W)`` along the wind, and a wave load growing with ``Hs`` along
the waves, each projected on the line's azimuth. In the paper's space that projection is a
product of two coordinates, which a Gaussian RBF on 1,000 states in 5-D rebuilds poorly where
it varies fastest (a light line swings from slack to taut as the direction turns). As
vectors, the projection on every line is a *linear* function of the coordinates, and the
direction matters less when the magnitude is small, as it should.

For each system, fits the lifecycle RBF (the schema defaults of ``lifecycle.rbf``) on the stored
training states in these spaces, every coordinate a scalar scaled by its range over the
training states, and prints the validation r on the 225 states:

* ``5d``: the paper's space (the baseline, as ``lifecycle`` fits it);
* ``thrust``: the package's ``thrust`` space, the 5-D space plus ``T(W)`` as a scalar
  (:func:`moorlife.lifecycle.spaces.space_inputs`, normalised as ``lifecycle`` does);
* ``thrust_vec``: ``W, T cos, T sin, Hs, Tp, theta_wave``: the wind as the thrust vector, ``W``
  kept for what depends on the speed itself (turbulence, the pitch control);
* ``both_vec``: ``W, T cos, T sin, Hs cos, Hs sin, Tp``: the waves as a vector too;
* ``both_vec_dirs``: the 5-D space plus the two vectors (9-D).

and two per-output choices among them, each output taking the space of the smallest
leave-one-out RMS on the training states (in the fitted scale, log10 for the damage):
``loo_5d_thr`` between ``5d`` and ``thrust_vec``, ``loo_5d_t`` between ``5d`` and ``thrust`` (what
``lifecycle.rbf.choose: per_output`` can do today), ``loo_all`` among all five.

The validation states never steer anything here: the space is fixed (or chosen by
leave-one-out), and the shapes and smoothing are chosen by leave-one-out on the training states
as ``lifecycle`` does. Measured in ``validation/reconstruction.md``, section 12.
"""

from __future__ import annotations

import sys
import time
import warnings

import numpy as np
import xarray as xr
from rbf_thrust_coordinate import load_study, loo_pick, print_table

from moorlife import lifecycle as lc
from moorlife import names, rbf
from moorlife.io import read_yaml
from moorlife.lifecycle.spaces import ThrustCurve, space_inputs, thrust_at, thrust_curve
from moorlife.space import direction_mask

SPACES = ("5d", "thrust", "thrust_vec", "both_vec", "both_vec_dirs")
#: Per-output choices by leave-one-out RMS on the training states (never the validation states).
PICKS = {"loo_5d_thr": ("5d", "thrust_vec"), "loo_5d_t": ("5d", "thrust"), "loo_all": SPACES}


def vector_points(name: str, x: np.ndarray, curve: ThrustCurve) -> tuple[np.ndarray, np.ndarray]:
    """The points of the vector space ``name`` from the sea states ``x`` (``names.METOCEAN_VARS``
    order): ``(points, is_direction)``. The paper's and the thrust spaces are the package's
    (:func:`moorlife.lifecycle.spaces.space_inputs`)."""
    w, wd, hs, tp, vd = (x[:, names.METOCEAN_VARS.index(v)] for v in ("wind_speed", "wind_dir", "hs", "tp", "wave_dir"))
    thrust = thrust_at(curve, w)  # as the simulator's platform model
    t_vec = [thrust * np.cos(np.deg2rad(wd)), thrust * np.sin(np.deg2rad(wd))]
    h_vec = [hs * np.cos(np.deg2rad(vd)), hs * np.sin(np.deg2rad(vd))]
    if name == "thrust_vec":
        return np.column_stack([w, *t_vec, hs, tp, vd]), np.array([False] * 5 + [True])
    if name == "both_vec":
        return np.column_stack([w, *t_vec, *h_vec, tp]), np.zeros(6, dtype=bool)
    if name == "both_vec_dirs":
        return np.column_stack([x, *t_vec, *h_vec]), np.r_[direction_mask(), np.zeros(4, dtype=bool)]
    raise ValueError(f"unknown space {name!r}")


#: The package's spaces among :data:`SPACES`, normalised by the selection as ``lifecycle`` does.
PACKAGE_SPACES = {"5d": names.RBF_SPACE_PAPER, "thrust": names.RBF_SPACE_THRUST}


def validation_r(results: str, ms: str, cases0: xr.Dataset, curve: ThrustCurve) -> tuple[list[str], dict]:
    """Validation r per output of one system in each space of :data:`SPACES`."""
    s = load_study(results, ms, cases0)
    st, grid, tr, va, x = s.settings, s.grid, s.train, s.validate, s.x
    cols = lc.output_columns(s.sims, names.CASE, st.outputs)
    y = lc.stack_outputs(s.sims, names.CASE, cols)
    isd = np.array([c[0].startswith("damage") for c in cols])
    res, pred, loo = {}, {}, {}
    for name in SPACES:
        if name in PACKAGE_SPACES:
            X, mask, lo, span = space_inputs(PACKAGE_SPACES[name], x, s.lo, s.span, curve)
        else:  # every coordinate scaled by its range over the training states
            (X, mask), lo, span = vector_points(name, x, curve), None, None
        t = time.time()
        m = rbf.fit_rbf(
            X[tr], y[tr], is_direction=mask, log_output=isd, shapes=grid, smoothing=st.smoothing, lo=lo, span=span
        )
        pred[name] = rbf.predict_rbf(m, X[va])
        loo[name] = np.sqrt(np.mean(m.loo_error**2, axis=0))  # in the fitted scale (log10 for damage)
        res[name] = lc.validation_metrics(pred[name], y[va])["r"]
        print(ms, name, "%.0f s" % (time.time() - t), flush=True)
    for label, cands in PICKS.items():  # per output, the candidate with the smallest LOO RMS
        res[label], k = loo_pick(pred, loo, cands, y[va])
        print(ms, label, "picks", "".join(str(v) for v in k), flush=True)
    return [lc._label(c) for c in cols], res


def main(argv: list[str]) -> int:
    warnings.filterwarnings("ignore")
    results = argv[1]
    curve = thrust_curve(read_yaml("config/platform.yaml"))
    cases0 = xr.open_zarr(f"{results}/selection/cases.zarr", consolidated=False).load()
    print("   output".ljust(19), *[k.rjust(13) for k in (*SPACES, *PICKS)])
    for ms in argv[2:]:
        print_table(*validation_r(results, ms, cases0, curve), width=13)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
