"""Pilot (not in the package): an additive GP for the line damage, wind part plus full part (issue 22).

    OMP_NUM_THREADS=1 python validation/gp_additive.py --results results --systems MS1 MS2 MS3 \\
        --lines M1 M3 --variants log pow_add pow_addT > additive.md

Why: a line's tension variance is nearly the sum of a wind-driven slow part and a wave part,
and the damage of a chain curve of slope ``m`` goes as the range to the power ``m``, so
``D^(2/m)`` is nearly additive in a wind-only and a wave term. A product kernel in ``log10 D``
(the package's GP) cannot make the damage flat in Hs where the wind dominates and steep where
the waves do (``validation/state_scans.py`` shows both on MS1's M1).

Every variant is scikit-learn's ``GaussianProcessRegressor`` on the study's training states of
``damage_sn`` of each line (L-BFGS-B, no restart, seed 0), the directions embedded on the circle,
the scalars scaled by their training range, the values standardised:

- ``log``: ``log10 D`` (floored at a tenth of the smallest positive value), Matérn 5/2 with one
  length scale per coordinate, plus a white noise; back-transformed by ``10^`` (no bias factor).
  The reference, close to the package's ``gp.covariance: matern52``;
- ``pow_add``: ``D^(2/m)``, a Matérn 5/2 on the wind speed and direction alone plus a Matérn 5/2
  on every coordinate, plus a white noise; back-transformed by ``max(., 0)^(m/2)``;
- ``pow_addT``: as ``pow_add``, the wind part also sees the steady rotor thrust ``T(W)``
  (``config/platform.yaml``'s curve).
- ``log_add``: ``log10 D`` with the kernel of ``pow_add``.

Printed per system, line and variant: the validation r (the 225 validation states against their
one record, as ``lifecycle.validation_metrics``), the closed-form leave-one-out RMS error in the
damage's units (the training states only: the criterion of a per-output choice), the CPU time of
the fit, and where
``results/{ms}/truth.zarr`` exists, the per-hour r of the truth window and its damage sum
against the truth's (%), and the storm hours' part (``Hs >= --storm-hs``): their number, their
share of the squared error, their reconstructed sum over the truth's, and the per-hour r of the
other hours.
"""

from __future__ import annotations

import argparse
import copy
import sys
import time
from pathlib import Path

import numpy as np

from moorlife import names
from moorlife.gp import chord_embed, embedded_names
from moorlife.space import Space, direction_mask, fit_space

sys.path.insert(0, str(Path(__file__).resolve().parent))
import reconstruction as rec  # noqa: E402

M = 3.0  # the slope of config.yaml's chain curves (S-N and T-N)


def _projected(cols: list[int]):
    """A Matérn 5/2 kernel on some columns of the inputs (one length scale each)."""
    from sklearn.gaussian_process.kernels import Kernel, Matern

    class Projected(Kernel):
        def __init__(self, base, cols):
            self.base, self.cols = base, cols

        @property
        def hyperparameters(self):
            return self.base.hyperparameters

        @property
        def theta(self):
            return self.base.theta

        @theta.setter
        def theta(self, theta):
            self.base.theta = theta

        @property
        def bounds(self):
            return self.base.bounds

        def get_params(self, deep=True):
            return {"base": self.base, "cols": self.cols}

        def clone_with_theta(self, theta):
            out = copy.deepcopy(self)
            out.theta = theta
            return out

        def __call__(self, X, Y=None, eval_gradient=False):
            return self.base(X[:, self.cols], None if Y is None else Y[:, self.cols], eval_gradient=eval_gradient)

        def diag(self, X):
            return self.base.diag(X[:, self.cols])

        def is_stationary(self):
            return True

    return Projected(Matern(length_scale=np.full(len(cols), 0.3), length_scale_bounds=(1e-2, 1e2), nu=2.5), cols)


#: The embedded coordinates (``moorlife.gp.chord_embed``'s order) of the wind-only term, then
#: the steady thrust, appended last by :func:`features`.
WIND = ("wind_speed", "cos_wind_dir", "sin_wind_dir")
COLUMNS = (*embedded_names(names.METOCEAN_VARS, direction_mask()), "thrust")


def kernel(kind: str):
    from sklearn.gaussian_process.kernels import ConstantKernel as C
    from sklearn.gaussian_process.kernels import WhiteKernel

    full = C(1.0, (1e-3, 1e3)) * _projected(list(range(len(COLUMNS) - 1)))
    noise = WhiteKernel(0.01, (1e-6, 1.0))
    wind = {"log": None, "log_add": WIND, "pow_add": WIND, "pow_addT": (*WIND, "thrust")}[kind]
    if wind is None:
        return full + noise
    return C(1.0, (1e-3, 1e3)) * _projected([COLUMNS.index(c) for c in wind]) + full + noise


def features(points: np.ndarray, space: Space, curve, t_scale: float) -> np.ndarray:
    """The GP's embedding of the package (:func:`moorlife.gp.chord_embed`: the scalars by the
    training range, each direction on a circle of radius 1/pi), then ``T(W) / t_scale``."""
    from moorlife import lifecycle

    return np.column_stack([chord_embed(points, space), lifecycle.thrust_at(curve, points[:, 0]) / t_scale])


def _loo_rms(g, f: np.ndarray, zs: np.ndarray, back, y: np.ndarray) -> float:
    """Closed-form leave-one-out RMS error in the damage's units (training states only).

    With ``K`` the fitted kernel's matrix on the training states (its white noise included),
    the residual of state ``i`` left out is ``[K^-1 z]_i / [K^-1]_ii`` in the standardised
    transformed units (Rasmussen & Williams 2006, eq. 5.12); its prediction is back-transformed
    and compared with the state's damage, as the package's per-output choice does."""
    k_inv = np.linalg.inv(g.kernel_(f))
    loo = zs - (k_inv @ zs) / np.diag(k_inv)
    return float(np.sqrt(np.mean((back(loo) - y) ** 2)))


def _print_scan(work: Path, line: str, xs: np.ndarray, _, pred: dict) -> None:
    """Every variant at the scan points beside the mean of their three records."""
    recs = [rec._open(work / f"validation_seed{k}.zarr")["damage_sn"].sel(line=line).values for k in (2, 3, 4)]
    mean = np.mean(recs, axis=0)
    print("\n| wind_speed | wind_dir | hs | tp | wave_dir | mean of 3 records | " + " | ".join(pred) + " |")
    print("|---|---|---|---|---|---|" + "---|" * len(pred))
    for i in range(xs.shape[0]):
        row = [f"{v:.2f}" for v in xs[i]] + [f"{mean[i]:.3e}"] + [f"{q[i]:.3e}" for q in pred.values()]
        print("| " + " | ".join(row) + " |")


def main(argv: list[str] | None = None) -> int:
    from sklearn.gaussian_process import GaussianProcessRegressor

    from moorlife import lifecycle
    from moorlife.io.platform import read_platform_config

    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--results", type=Path, default=rec.ROOT / "results")
    p.add_argument("--systems", nargs="+", default=["MS1", "MS2", "MS3"])
    p.add_argument("--lines", nargs="+", default=["M1", "M2", "M3"])
    p.add_argument("--variants", nargs="+", default=["log", "pow_add", "pow_addT"])
    p.add_argument("--storm-hs", type=float, default=5.0, help="Hs (m) of the truth's storm hours (default 5)")
    p.add_argument(
        "--scans",
        type=Path,
        help="also predict at the scan points of validation/state_scans.py's --work (first system and line)",
    )
    a = p.parse_args(argv)
    for v in a.variants:
        kernel(v)  # an unknown variant stops here, before any fit
    cfg = rec.study([])
    platform = rec.ROOT / cfg["platform"]
    curve = lifecycle.thrust_curve(read_platform_config(platform), str(platform))
    print(
        "| system | line | variant | validation r | leave-one-out RMS | fit CPU-s | truth per-hour r | truth sum % "
        f"| storm hours (Hs >= {a.storm_hs} m) | their share of the squared error | their sum / truth's "
        "| per-hour r without them |"
    )
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for ms in a.systems:
        st = rec.load(a.results, ms)
        if st is None:
            print(f"{ms}: no simulations under {a.results}, skipped", file=sys.stderr)
            continue
        role = st["cases"]["role"].values.astype(object).astype(str)
        tr, va = role == "train", role == "validate"
        x = lifecycle._points(st["cases"], "case")
        space = fit_space(x[tr], direction_mask())
        t_scale = np.ptp(lifecycle.thrust_at(curve, x[tr, 0]))
        f = features(x, space, curve, t_scale)
        hours, scan = None, None
        if a.scans is not None and ms == a.systems[0]:
            xs = lifecycle._points(rec._open(a.scans / "cases.zarr"), "case")
            scan = (xs, features(xs, space, curve, t_scale), {})
        if st["truth"] is not None:
            idx = st["truth"]["hindcast_index"].values
            hours = features(lifecycle._points(st["hindcast"].isel(time=idx), "time"), space, curve, t_scale)
        for line in a.lines:
            y = st["sims"]["damage_sn"].sel(line=line).values.astype(float)
            for v in a.variants:
                if v.startswith("log"):
                    z = np.log10(np.maximum(y, 0.1 * y[y > 0].min()))
                    back = lambda q: 10.0**q  # noqa: E731
                else:
                    z = np.maximum(y, 0.0) ** (2.0 / M)
                    back = lambda q: np.maximum(q, 0.0) ** (M / 2.0)  # noqa: E731
                mu, sd = z[tr].mean(), z[tr].std()
                t0 = time.process_time()
                g = GaussianProcessRegressor(kernel(v), n_restarts_optimizer=0, random_state=0)
                g.fit(f[tr], (z[tr] - mu) / sd)
                cpu = time.process_time() - t0
                r = np.corrcoef(back(g.predict(f[va]) * sd + mu), y[va])[0, 1]
                loo = _loo_rms(g, f[tr], (z[tr] - mu) / sd, lambda q: back(q * sd + mu), y[tr])  # noqa: B023
                truth = " | " * 5
                if hours is not None:
                    t = st["truth"]["damage_sn"].sel(line=line).values
                    q = back(g.predict(hours) * sd + mu)
                    storm = st["truth"]["hs"].values >= a.storm_hs
                    e2 = (q - t) ** 2
                    truth = (
                        f"{np.corrcoef(q, t)[0, 1]:.4f} | {100 * (q.sum() / t.sum() - 1):+.1f} | "
                        f"{int(storm.sum())} | {e2[storm].sum() / e2.sum():.2f} | "
                        f"{q[storm].sum() / t[storm].sum():.3f} | {np.corrcoef(q[~storm], t[~storm])[0, 1]:.4f}"
                    )
                print(f"| {ms} | {line} | {v} | {r:.4f} | {loo:.3e} | {cpu:.1f} | {truth} |", flush=True)
                if scan is not None and line == a.lines[0]:
                    scan[2][v] = back(g.predict(scan[1]) * sd + mu)
        if scan is not None:
            _print_scan(a.scans, a.lines[0], *scan)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
