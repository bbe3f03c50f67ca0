"""The package's GP on one damage output: the subsample's draw, all states, and D^(2/m) (issue 22).

    OMP_NUM_THREADS=1 python validation/gp_draws.py --results results MS6:M2 MS1:M1 --draws 0 1 2 3 --all-states
    OMP_NUM_THREADS=1 python validation/gp_draws.py --results results MS6:M2 --power

For each ``SYSTEM:LINE``, ``moorlife.gp.fit_gp`` (Matérn 5/2, as
``validation/overlays/gp_matern52.yaml``) on the study's training states of ``damage_sn`` of that
line, the scalars scaled as the package scales them (``lifecycle._selection_scaling``), and the
validation r on the 225 validation states against their one record (linear units, as
``lifecycle.validation_metrics``; also in ``log10`` units). Printed per fit:

- ``--draws``: ``log10 D`` with the hyperparameters on 200 states drawn with each seed
  (``gp.seed``; 0 is the default draw);
- ``--all-states``: ``log10 D`` with the hyperparameters on all training states;
- ``--power``: ``D^(2/m)`` (``m`` 3, the slope of both of ``config.yaml``'s chain curves) on a
  linear scale with the sea-gated wind term (``gp.wind_term``), its hyperparameters on all states
  (``joint``) and with the plain kernel's 200-state length scales (``frozen``); back-transformed
  by ``max(., 0)^(m/2)``, the count of negative predictions and the fitted sea gate printed;
- ``--lambdas L [L ...]``: the transform by likelihood. For each Box-Cox power ``L`` (0:
  ``log10``; otherwise ``D^L``, back-transformed by ``max(., 0)^(1/L)``), the gated wind term
  with the ``frozen`` start fitted to the transformed damage, and printed: the log marginal
  likelihood of the 1,000 training values in damage units (the GP's, at its fitted
  hyperparameters, plus the Jacobian ``sum log |dg/dD|``), the leave-one-out log predictive
  density in damage units (the closed-form leave-one-out mean and variance, plus the same
  Jacobian), the validation r, and on the store's truth window (``truth.zarr``) the per-hour r
  and the window sum's error. The two likelihoods see the training states alone;
- ``--worst N``: the N validation states with the largest errors of the last fit of each output
  (of ``--draws``, ``--all-states`` or ``--power``).

Section 22 of ``validation/reconstruction.md`` has the figures.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

from moorlife import gp, lifecycle
from moorlife.lifecycle.fit import wave_height_column, wind_columns
from moorlife.space import direction_mask

sys.path.insert(0, str(Path(__file__).resolve().parent))
import reconstruction as rec  # noqa: E402  (the harness's store loader)

SLOPE = 3.0


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("outputs", nargs="+", metavar="SYSTEM:LINE")
    p.add_argument("--results", type=Path, default=Path("results"))
    p.add_argument("--draws", type=int, nargs="*", default=[])
    p.add_argument("--all-states", action="store_true")
    p.add_argument("--power", action="store_true")
    p.add_argument("--lambdas", type=float, nargs="*", default=[])
    p.add_argument("--worst", type=int, default=0)
    a = p.parse_args(argv)
    mask = direction_mask()
    for spec in a.outputs:
        ms, _, line = spec.partition(":")
        st = rec.load(a.results, ms)
        if st is None or not line:
            p.error(f"{spec!r}: expected SYSTEM:LINE with simulations under {a.results}")
        role = st["cases"]["role"].values.astype(object).astype(str)
        x = lifecycle._points(st["cases"], "case")
        tr, va = role == "train", role == "validate"
        lo, span = lifecycle._selection_scaling(st["cases"])
        y = st["sims"]["damage_sn"].sel(line=line).values.astype(float)
        base = dict(is_direction=mask, lo=lo, span=span, covariance="matern52")
        term = dict(additive_columns=wind_columns(mask), gate_column=wave_height_column(mask), additive_subsample=0)
        fits = [(f"log, 200 states, seed {s}", dict(subsample=200, seed=s, log_output=True), None) for s in a.draws]
        if a.all_states:
            fits.append(("log, all states", dict(subsample=0, log_output=True), None))
        if a.power:
            fits += [
                (f"D^(2/{SLOPE:g}) + wind term, {start}", dict(subsample=200, additive_start=start, **term), start)
                for start in ("joint", "frozen")
            ]
        for name, kw, power in fits:
            t = time.process_time()
            if power is None:
                m = gp.fit_gp(x[tr], y[tr], **kw, **base)
                pred, neg = gp.predict_gp(m, x[va])[:, 0], 0
            else:
                m = gp.fit_gp(x[tr], y[tr] ** (2 / SLOPE), **kw, **base)
                z = gp.predict_gp(m, x[va])[:, 0]
                pred, neg = np.clip(z, 0.0, None) ** (SLOPE / 2), int((z < 0).sum())
            r = np.corrcoef(pred, y[va])[0, 1]
            gate = "" if m.wind_gate is None else f"sea gate {m.wind_gate[0]:.3f}, "
            rl = f"{np.corrcoef(np.log10(pred), np.log10(y[va]))[0, 1]:.4f}" if np.all(pred > 0) else "n/a"
            print(
                f"{ms} {line} {name}: validation r {r:.4f} (log10 units {rl}), negatives {neg}, {gate}"
                f"{time.process_time() - t:.0f} CPU-s",
                flush=True,
            )
        if a.lambdas:
            _by_likelihood(st, x, y, tr, va, a.lambdas, ms, line, {**base, **term})
        if a.worst and fits:
            e = pred - y[va]
            order = np.argsort(-np.abs(e))
            print(f"  squared error of the {a.worst} worst: {np.sum(e[order[: a.worst]] ** 2) / np.sum(e**2):.2f}")
            for i in order[: a.worst]:
                w, wd, hs, tp, ad = x[va][i]
                print(
                    f"  W {w:.1f} m/s from {wd:.0f}, Hs {hs:.2f} m, Tp {tp:.1f} s from {ad:.0f}: {y[va][i]:.3e}, predicted {pred[i]:.3e}"
                )
    return 0


def _box_cox(lam: float, d: np.ndarray):
    """The values fitted, the back-transform of the prediction and ``log |dg/dD|`` at ``d``.

    ``lam`` 0: the package's ``log10`` output (``log_output``, its noise back-transform included);
    otherwise ``D^lam`` on a linear scale, back-transformed by ``max(., 0)^(1/lam)``.
    """
    if lam == 0:
        return d, (lambda z: z), -np.log(d) - np.log(np.log(10.0))
    return d**lam, (lambda z: np.clip(z, 0.0, None) ** (1.0 / lam)), np.log(lam) + (lam - 1.0) * np.log(d)


def _by_likelihood(st, x, y, tr, va, lambdas, ms, line, kw) -> None:
    """``--lambdas``: the likelihoods in damage units, the validation r and the truth window per power."""
    truth = st["truth"]
    if truth is not None:  # the window's hours and their simulated damage, once for every power
        hours = lifecycle._points(st["hindcast"].isel(time=truth["hindcast_index"].values), "time")
        tt = truth["damage_sn"].sel(line=line).values
    rows = []
    for lam in lambdas:
        t = time.process_time()
        fitted, back, jac = _box_cox(lam, y[tr])
        m = gp.fit_gp(x[tr], fitted, subsample=200, additive_start="frozen", log_output=lam == 0, **kw)
        yt = np.log10(fitted) if lam == 0 else fitted  # the values the GP sees
        sig = m.signal_var[0]
        lml = -0.5 * (yt - m.mean[0]) @ m.weights[:, 0] / sig - np.log(np.diag(m.chol[0])).sum()
        lml += -0.5 * yt.size * np.log(2 * np.pi * sig) + jac.sum()
        lv = m.loo_var[:, 0]
        lpd = np.sum(-0.5 * m.loo_error[:, 0] ** 2 / lv - 0.5 * np.log(2 * np.pi * lv) + jac)
        r = np.corrcoef(back(gp.predict_gp(m, x[va])[:, 0]), y[va])[0, 1]
        window = ""
        if truth is not None:
            ph = back(gp.predict_gp(m, hours)[:, 0])
            window = f", truth window per-hour r {np.corrcoef(ph, tt)[0, 1]:.4f}, sum {100 * (ph.sum() / tt.sum() - 1):+.1f} %"
        rows.append((lam, lml, lpd))
        print(
            f"{ms} {line} Box-Cox {lam:.3f}: log likelihood in damage units {lml:.1f}, leave-one-out "
            f"log density {lpd:.1f}, validation r {r:.4f}{window}, {time.process_time() - t:.0f} CPU-s",
            flush=True,
        )
    best = max(rows, key=lambda q: q[2])[0]
    print(
        f"{ms} {line}: the leave-one-out density picks {best:.3f}, the likelihood {max(rows, key=lambda q: q[1])[0]:.3f}"
    )


if __name__ == "__main__":
    raise SystemExit(main())
