"""Experiment: the turbulent thrust's standard deviation sigma_T(W) as the thrust coordinate.

Usage::

    OMP_NUM_THREADS=1 python validation/rbf_thrust_sd.py MODE [--f-min HZ] [--f-max HZ] -- \\
        [reconstruction.py arguments]
    OMP_NUM_THREADS=1 python validation/rbf_thrust_sd.py operating -- --results results \\
        --systems MS1 MS2 --work DIR --variant m52_sdT=validation/overlays/gp_matern52_thrust.yaml

The simulator's rotor thrust is the quasi-static curve ``T(v)`` of the (filtered, relative) hub
wind, and the wind's slow turbulence ``u`` makes it fluctuate. In a calm sea the slow surge that
this fluctuation drives sets the tension cycles of the lightly loaded lines, and it is not a
smooth function of the mean wind speed: with ``u ~ N(0, sigma_u(W)^2)``, the standard deviation
of ``T(W + u)`` rises with ``W`` below rated, dips at rated (where the slope of ``T`` changes
sign) and falls above it. The paper's space holds ``W`` only, and the thrust space ``T(W)``,
whose peak is at rated, folds the two sides of the dip together.

This script replaces ``moorlife.lifecycle.spaces.thrust_at`` (the extra coordinate of the
``thrust`` space and of ``lifecycle.rbf.gp.thrust``) by ``sigma_T(W)``, then runs
``validation/reconstruction.py`` with the arguments after ``--``: every variant of that run
that uses the thrust coordinate sees ``sigma_T`` instead. ``sigma_u(W)^2`` is the configured
wind spectrum (``simulation.wind`` of ``config/config.yaml``, at the hub height of the
platform) integrated from ``--f-min`` (default: one hour, the hindcast's averaging time) to
``--f-max`` (default ``simulation.wind.f_max``); the mean over ``u`` is a 161-point Gaussian
quadrature over +-4 sigma_u, tabulated every 0.05 m/s from 0 to 45 m/s.

MODE:

- ``full``: the simulator's thrust curve, shutdown ramp included. Across the ramp
  (``cut_out`` to ``cut_out + shutdown_ramp``) the thrust drops to zero within 1 m/s, so
  ``sigma_T`` has a spike there (174 kN at 25 m/s against 65 kN at most below).
- ``operating``: the operating rotor without the shutdown (``Ct`` held at its last tabulated
  value), evaluated at ``min(W, cut_out)``: no spike, and the storm hours above cut-out share
  the value at cut-out.

Measured in ``validation/reconstruction.md`` section 18 (not adopted). The ``operating`` mode
at the default band is now in the package, ``lifecycle.rbf.thrust.statistic: turbulent_sd``
(:func:`moorlife.lifecycle.turbulent_thrust`, the same table to the bit): this script keeps the
``full`` mode and other bands, on the package's kernels (:mod:`moorlife.lifecycle.turbulence`).
"""

from __future__ import annotations

import argparse
import dataclasses
import sys
from pathlib import Path
from typing import Any

import numpy as np

from moorlife.lifecycle import spaces, turbulence

ROOT = Path(__file__).resolve().parents[1]
_THRUST_AT = spaces.thrust_at
GRID = turbulence.GRID


def thrust_sd_table(curve: spaces.ThrustCurve, su: np.ndarray, mode: str) -> np.ndarray:
    """``sigma_T`` (N) at every speed of :data:`GRID`, given ``sigma_u`` there."""
    if mode == "operating":
        operating = dataclasses.replace(curve, cut_out=1e3, shutdown_ramp=0.0)
        return turbulence.thrust_sd(lambda v: _THRUST_AT(operating, v), GRID, su, cap=curve.cut_out)
    return turbulence.thrust_sd(lambda v: _THRUST_AT(curve, v), GRID, su)


def patch(mode: str, f_min: float | None, f_max: float | None) -> None:
    """Route the thrust coordinate of :mod:`moorlife.lifecycle.spaces` through ``sigma_T``."""
    from moorlife.io.platform import read_platform_config

    sys.path.insert(0, str(Path(__file__).resolve().parent))
    import reconstruction

    cfg = reconstruction.study([])
    platform = read_platform_config(ROOT / cfg["platform"])
    wind_cfg = {**cfg["simulation"]["wind"], "height": float(platform["turbine"]["hub_height"])}
    lo = 1.0 / 3600.0 if f_min is None else f_min
    hi = float(wind_cfg["f_max"]) if f_max is None else f_max
    su = turbulence.wind_sd(GRID, wind_cfg, lo, hi)
    # every thrust coordinate of the run is this platform's: one table, checked at each call
    own = spaces.thrust_curve(platform, str(ROOT / cfg["platform"]))
    table = thrust_sd_table(own, su, mode)
    at = [4.0, 8.0, 10.0, 11.4, 12.0, 13.0, 15.0, 20.0, 25.0]
    print(
        f"sigma_T ({mode}, {lo:.3g}-{hi:.3g} Hz): "
        + ", ".join(f"{w:g} m/s {np.interp(w, GRID, su):.2f} m/s {np.interp(w, GRID, table) / 1e3:.1f} kN" for w in at),
        file=sys.stderr,
    )

    def thrust_sd(curve: spaces.ThrustCurve, wind_speed: Any) -> np.ndarray:
        same = all(
            np.array_equal(getattr(curve, f.name), getattr(own, f.name)) for f in dataclasses.fields(spaces.ThrustCurve)
        )
        if not same:
            raise ValueError(
                f"rbf_thrust_sd.py: a thrust curve other than {cfg['platform']}'s; its table is not this one"
            )
        return np.interp(np.asarray(wind_speed, dtype=float), GRID, table)

    spaces.thrust_at = thrust_sd


if __name__ == "__main__":
    import reconstruction  # beside this script: sys.path[0]

    mine, rest = reconstruction.split_argv(sys.argv[1:])
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("mode", choices=["full", "operating"])
    p.add_argument("--f-min", type=float, default=None, help="Hz (default 1/3600)")
    p.add_argument("--f-max", type=float, default=None, help="Hz (default simulation.wind.f_max)")
    a = p.parse_args(mine)
    patch(a.mode, a.f_min, a.f_max)
    sys.exit(reconstruction.main(rest))
