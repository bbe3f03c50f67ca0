"""Exploratory (issue 22): weights on the scalar coordinates of the RBF, chosen by leave-one-out.

    OMP_NUM_THREADS=1 python validation/rbf_anisotropic.py RESULTS MS1 [MS2 ...] [--sweeps 2] [--criterion log]

For each system with ``RESULTS/{ms}/simulations.zarr``, and each damage output of the S-N curve
(one per line), a Gaussian RBF with a linear tail on ``log10`` of the damage, as the paper's
method, in two metrics:

- isotropic: the paper's normalised 5-D space (scalars by their range, each direction as
  ``(cos, sin) / pi``, the chord distance), ``q0`` by leave-one-out;
- weighted: each scalar coordinate (wind speed, Hs, Tp) multiplied by a weight, the weights
  found by coordinate search (factors 0.5, 0.7, 1.4, 2 per coordinate and sweep, a step kept
  when it lowers the leave-one-out RMSE by 0.5 %: of the damage in its units, or with
  ``--criterion log`` of its log10), ``q0`` again by
  leave-one-out at every step.

Both are fitted on the training states only (the closed-form leave-one-out of Rippa on the
augmented system); the validation states are predicted once at the end. Prints per output the
leave-one-out RMSE, the validation r (of the damage, and of its log10), the weights and the
CPU time of the search. A plain numpy implementation, independent of ``moorlife.rbf``: the
isotropic column checks it against the package's ``choose: global`` r within the embedding's
difference (chord distance here, the folded angle there).
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np

from moorlife import lifecycle as lc
from moorlife import names
from moorlife.io import open_zarr

FACTORS = (0.5, 0.7, 1.4, 2.0)
SHAPES = np.geomspace(0.05, 1.0, 10)
IS_DIRECTION = np.array([v in names.DIRECTION_VARS for v in names.METOCEAN_VARS])


def features(x: np.ndarray, lo: np.ndarray, span: np.ndarray, w: np.ndarray) -> np.ndarray:
    """Scalars ``w (x - lo) / span``; directions ``(cos, sin) / pi``."""
    cols = []
    for j in range(x.shape[1]):
        if IS_DIRECTION[j]:
            a = np.deg2rad(x[:, j])
            cols += [np.cos(a) / np.pi, np.sin(a) / np.pi]
        else:
            cols.append(w[j] * (x[:, j] - lo[j]) / span[j])
    return np.column_stack(cols)


def _sq(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return np.maximum((a * a).sum(1)[:, None] + (b * b).sum(1)[None, :] - 2.0 * a @ b.T, 0.0)


def fit_loo(z: np.ndarray, y: np.ndarray, q: float) -> tuple[np.ndarray, np.ndarray]:
    """Coefficients and leave-one-out residuals (Rippa) of the Gaussian RBF with a linear tail."""
    n = z.shape[0]
    p = np.column_stack([np.ones(n), z])
    a = np.block([[np.exp(-_sq(z, z) / (2 * q * q)), p], [p.T, np.zeros((p.shape[1], p.shape[1]))]])
    ai = np.linalg.inv(a)
    c = ai[:, :n] @ y
    return c, c[:n] / np.diag(ai)[:n]


def predict(z: np.ndarray, c: np.ndarray, q: float, zn: np.ndarray) -> np.ndarray:
    n = z.shape[0]
    return np.exp(-_sq(zn, z) / (2 * q * q)) @ c[:n] + np.column_stack([np.ones(len(zn)), zn]) @ c[n:]


def best_shape(z: np.ndarray, ly: np.ndarray, criterion: str = "units") -> tuple[float, float, np.ndarray]:
    """``(LOO RMSE, q0, coefficients)`` of the best ``q0`` of :data:`SHAPES`.

    ``criterion``: ``"units"``, the RMSE of the back-transformed residuals (the damage's units);
    ``"log"``, of the log10 residuals.
    """
    best = (np.inf, 0.0, np.empty(0))
    for q in SHAPES:
        c, loo = fit_loo(z, ly, q)
        if criterion == "log":
            e = float(np.sqrt(np.mean(loo**2)))
        else:
            e = float(np.sqrt(np.mean((10**ly - 10 ** (ly - np.clip(loo, -3, 3))) ** 2)))
        if e < best[0]:
            best = (e, float(q), c)
    return best


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("results", type=Path)
    ap.add_argument("systems", nargs="+")
    ap.add_argument("--sweeps", type=int, default=2)
    ap.add_argument("--criterion", choices=("units", "log"), default="units")
    ap.add_argument("--start", default="1,1,1", help="initial weights of W, Hs, Tp (with --sweeps 0: fixed)")
    args = ap.parse_args()
    cases0 = open_zarr(args.results / "selection" / "cases.zarr")
    print(
        "| system | output | LOO iso | LOO weighted | r iso | r weighted | log r iso | log r weighted "
        "| weights (W, Hs, Tp) | search CPU-s |"
    )
    print("|---|---|---|---|---|---|---|---|---|---|")
    for ms in args.systems:
        sims = open_zarr(args.results / ms / "simulations.zarr")
        ids = np.intersect1d(cases0[names.CASE].values, sims[names.CASE].values)
        cases, sims = cases0.sel({names.CASE: ids}), sims.sel({names.CASE: ids})
        role = np.array([str(v) for v in cases["role"].values])
        tr, va = role == "train", role == "validate"
        x = lc._points(cases, names.CASE)
        lo, span = lc._selection_scaling(cases)
        cols = lc.output_columns(sims, names.CASE, ["damage_sn"])
        y = lc.stack_outputs(sims, names.CASE, cols)
        scalars = np.flatnonzero(~IS_DIRECTION)
        for j, col in enumerate(cols):
            ly = np.log10(np.maximum(y[:, j], np.min(y[y[:, j] > 0, j])))
            t0 = time.process_time()
            w = np.ones(x.shape[1])
            e0, q0, c0 = best_shape(features(x[tr], lo, span, w), ly[tr], args.criterion)
            w[scalars] = [float(v) for v in args.start.split(",")]
            e, q, c = best_shape(features(x[tr], lo, span, w), ly[tr], args.criterion)
            for _ in range(args.sweeps):
                for k in scalars:
                    for f in FACTORS:
                        w2 = w.copy()
                        w2[k] *= f
                        e2, q2, c2 = best_shape(features(x[tr], lo, span, w2), ly[tr], args.criterion)
                        if e2 < 0.995 * e:
                            e, q, c, w = e2, q2, c2, w2
            cpu = time.process_time() - t0
            p0 = 10 ** predict(
                features(x[tr], lo, span, np.ones(x.shape[1])), c0, q0, features(x[va], lo, span, np.ones(x.shape[1]))
            )
            p1 = 10 ** predict(features(x[tr], lo, span, w), c, q, features(x[va], lo, span, w))
            yt = y[va, j]
            r0, r1 = np.corrcoef(p0, yt)[0, 1], np.corrcoef(p1, yt)[0, 1]
            l0, l1 = (np.corrcoef(np.log10(p), np.log10(np.maximum(yt, 1e-300)))[0, 1] for p in (p0, p1))
            print(
                f"| {ms} | {lc._label(col)} | {e0:.3g} | {e:.3g} | {r0:.4f} | {r1:.4f} | {l0:.4f} | {l1:.4f} "
                f"| {', '.join(f'{w[k]:.2f}' for k in scalars)} | {cpu:.0f} |",
                flush=True,
            )


if __name__ == "__main__":
    main()
