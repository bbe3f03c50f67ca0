"""Experiment: rebuild each line's damage as sigma^m times a ratio (beyond the paper's method).

Usage::

    .venv/bin/python validation/rbf_std_scaled.py RESULTS MS1 [MS5 ...] [--m 3]

The hourly damage of a line scales with its tension standard deviation to the power of the
curve's slope ``m`` (narrow-band: ``D ~ nu sigma^m``). The hypothesis tested: the tension std
rebuilds better than the damage, and the ratio is smooth, so the light lines' damage would
rebuild better as their product (measured: it does not, ``validation/reconstruction.md``
section 11). For each system and line this prints the validation r on the 225 states of:

- ``paper``: ``log10 D`` interpolated (the package's default fit, shapes by Rippa);
- ``scaled``: ``log10 sigma`` and ``log10 (D / sigma^m)`` interpolated apart, each with its own
  shape by Rippa, multiplied back;
- ``scaled_lin``: the same with ``sigma`` interpolated linearly;
- ``sigma``: the validation r of the tension std itself.

A Gaussian RBF is linear in its data, so ``scaled`` differs from ``paper`` only through the two
factors' own shapes, and ``scaled_lin`` through the linear interpolation of ``sigma``.
Nothing here is fitted on the validation states.
"""

from __future__ import annotations

import argparse
import warnings

import numpy as np
import xarray as xr
from rbf_thrust_coordinate import load_study

from moorlife import lifecycle as lc
from moorlife import names, rbf


def run(results: str, ms: str, cases0: xr.Dataset, m: float) -> list[tuple]:
    st = load_study(results, ms, cases0)
    sims, tr, va, x, dim = st.sims, st.train, st.validate, st.x, names.CASE
    kw = {
        "is_direction": st.is_direction,
        "shapes": st.grid,
        "smoothing": st.settings.smoothing,
        "lo": st.lo,
        "span": st.span,
    }
    lines = [str(v) for v in sims[names.LINE].values]
    d = sims["damage_sn"].transpose(dim, names.LINE).values
    s = sims["tension_std"].transpose(dim, names.LINE).values
    ratio = d / s**m
    out = []

    def fit(y, log):
        return rbf.predict_rbf(rbf.fit_rbf(x[tr], y[tr], log_output=log, **kw), x[va])

    p_paper = fit(d, True)
    p_slog = fit(s, True)
    p_slin = fit(s, False)
    p_ratio = fit(ratio, True)
    for j, line in enumerate(lines):
        r = {
            "paper": lc.validation_metrics(p_paper[:, j], d[va, j])["r"][0],
            "scaled": lc.validation_metrics(p_slog[:, j] ** m * p_ratio[:, j], d[va, j])["r"][0],
            "scaled_lin": lc.validation_metrics(np.clip(p_slin[:, j], 1e-9, None) ** m * p_ratio[:, j], d[va, j])["r"][
                0
            ],
            "sigma": lc.validation_metrics(p_slin[:, j], s[va, j])["r"][0],
        }
        cv = np.std(np.log10(ratio[tr, j])) / np.std(np.log10(d[tr, j]))
        out.append((ms, line, r, cv))
    return out


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("results")
    p.add_argument("systems", nargs="+")
    p.add_argument("--m", type=float, default=3.0, help="the S-N slope (DNV studless chain: 3)")
    a = p.parse_args(argv)
    warnings.filterwarnings("ignore")
    cases0 = xr.open_zarr(f"{a.results}/selection/cases.zarr", consolidated=False).load()
    print("| system | line | paper | scaled | scaled_lin | sigma | sd log ratio / sd log D (train) |")
    print("|---|---|---|---|---|---|---|")
    for ms in a.systems:
        for ms_, line, r, cv in run(a.results, ms, cases0, a.m):
            cells = " | ".join(f"{r[k]:.4f}" for k in ("paper", "scaled", "scaled_lin", "sigma"))
            print(f"| {ms_} | {line} | {cells} | {cv:.2f} |", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
