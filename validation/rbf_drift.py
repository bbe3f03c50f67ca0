"""Experiment: a piecewise-linear trend in the wind speed beside the RBF's polynomial.

Usage::

    .venv/bin/python validation/rbf_drift.py RESULTS MS1 [MS2 ...]

The damage of the lightly loaded lines peaks in a band of wind speed about 1.5 m/s wide just
above rated (11.4 m/s), where the thrust falls as the wind rises. Among 1,000 states in 5-D the
kernel's length scale along the wind speed is several m/s: no shape parameter of an isotropic
Gaussian resolves the band. The paper's RBF carries a first-degree polynomial fitted jointly
with the kernel weights; :class:`moorlife.rbf.Trend` adds hinges ``max(0, W - k)`` at knots
``k`` dense near rated, optionally times harmonics of the wind direction (the package's
``wind_trend`` space, ``lifecycle.rbf.wind_trend``). The band becomes a trend fitted from every
training state, and the kernel interpolates the rest.

For each system, fits the lifecycle RBF (the schema defaults of ``lifecycle.rbf``: Rippa's shape
search, log10 damage) on the stored training states with each trend of :data:`VARIANTS`, and
prints the validation r on the 225 states, then two per-output choices among the variants by the
leave-one-out RMS on the training states: in the fitted scale (log10 for the damage;
``loo_log``) and in the output's units (``loo_units``). The validation states steer nothing.
Measured in ``validation/reconstruction.md``, section 13.
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

IW, ID, IV = (names.METOCEAN_VARS.index(v) for v in ("wind_speed", "wind_dir", "wave_dir"))
#: The knots of the package's default (``lifecycle.rbf.wind_trend.knots``), and with knots at cut-out too.
BAND = (3.0, 5.0, 7.0, 9.0, 10.5, 11.4, 12.0, 12.7, 13.5, 15.0, 17.5)
CUTOUT = (*BAND, 20.0, 23.0, 25.0, 26.0)
VARIANTS = {
    "paper": None,
    "band": rbf.Trend(IW, BAND),
    "band_dir": rbf.Trend(IW, BAND, ID, 1),  # the package's wind_trend default
    "band_dir2": rbf.Trend(IW, BAND, ID, 2),
    "cutout_dir": rbf.Trend(IW, CUTOUT, ID, 1),
    "band_dir3": rbf.Trend(IW, BAND, ID, 3),
    "band_wave": rbf.Trend(IW, BAND, IV, 1),  # the harmonics of the wave direction instead
    "coarse_dir": rbf.Trend(IW, (3.0, 7.0, 10.5, 11.4, 12.0, 13.0, 15.0, 17.5), ID, 1),
}


def validation_r(results: str, ms: str, cases0: xr.Dataset) -> tuple[list[str], dict]:
    """Validation r per output of one system with each trend, and the two leave-one-out picks."""
    s = load_study(results, ms, cases0)
    st, tr, va, x = s.settings, s.train, s.validate, s.x
    cols = lc.output_columns(s.sims, names.CASE, st.outputs)
    y = lc.stack_outputs(s.sims, names.CASE, cols)
    isd = np.array([c[0].startswith("damage") for c in cols])
    res, pred, loo_log, loo_units = {}, {}, {}, {}
    for name, trend in VARIANTS.items():
        t = time.time()
        m = rbf.fit_rbf(
            x[tr], y[tr], is_direction=s.is_direction, log_output=isd, shapes=s.grid, smoothing=st.smoothing,
            lo=s.lo, span=s.span, trend=trend,
        )  # fmt: skip
        pred[name] = rbf.predict_rbf(m, x[va])
        res[name] = lc.validation_metrics(pred[name], y[va])["r"]
        loo_log[name] = np.sqrt(np.mean(m.loo_error**2, axis=0))
        eu = rbf.loo_error_in_units(y[tr][:, isd], np.log10(y[tr][:, isd]), m.loo_error[:, isd], m.log_factor[isd])
        loo_units[name] = loo_log[name].copy()
        loo_units[name][isd] = np.sqrt(np.mean(eu**2, axis=0))
        print(ms, name, "%.0f s" % (time.time() - t), flush=True)
    for label, score in (("loo_log", loo_log), ("loo_units", loo_units)):
        res[label], k = loo_pick(pred, score, list(VARIANTS), y[va])
        print(ms, label, "picks", "".join(str(v) for v in k), flush=True)
    return [lc._label(c) for c in cols], res


def main(argv: list[str]) -> int:
    warnings.filterwarnings("ignore")
    results = argv[1]
    cases0 = xr.open_zarr(f"{results}/selection/cases.zarr", consolidated=False).load()
    print("   output".ljust(19), *[k.rjust(11) for k in (*VARIANTS, "loo_log", "loo_units")])
    for ms in argv[2:]:
        print_table(*validation_r(results, ms, cases0), width=11)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
