"""Experiment: the thrust coordinate projected on one line, ``sigma_T(W) cos(theta_wind - theta_line)``.

Usage::

    OMP_NUM_THREADS=1 python validation/rbf_line_thrust.py BEARING -- [reconstruction.py arguments]
    OMP_NUM_THREADS=1 python validation/rbf_line_thrust.py 30 -- --results results --systems MS1 \\
        --work DIR --variant m52_sdT_M1=validation/overlays/gp_matern52_sdT.yaml

The slow surge that the turbulent thrust drives moves the platform along the wind, and a line
feels it through the projection of that motion on its own bearing: most when the wind comes
from the line's anchor (the line upwind, taut and stiff), least across it. The Gaussian process
of the package has the wind direction and ``sigma_T(W)`` (``lifecycle.rbf.thrust.statistic:
turbulent_sd``) as separate coordinates; this script replaces the thrust coordinate of every
variant of the run by their product with the line's bearing (degrees clockwise from north,
platform to anchor; ``mooring.line_bearings``: M1 30, M2 270, M3 150), signed, so that the
upwind and downwind sides stay apart:

    c = sigma_T(W) cos(wind_dir - BEARING),   normalised over [-max sigma_T, +max sigma_T]

(``max`` over the space's wind range); with ``--fold``, ``|cos|``, normalised over
``[0, max sigma_T]`` (the up- and downwind sides together). The sign of the signed form does not
matter (the GP's distance is symmetric), so a bearing off by 180 deg gives the same fit. Every output of the run sees that line's coordinate, so
only the damage of that line is read from it. Measured in ``validation/reconstruction.md``
section 19 (not adopted).
"""

from __future__ import annotations

import argparse
import sys
from typing import Any

import numpy as np

from moorlife import names
from moorlife.lifecycle import fit, spaces

_ORIGINAL = spaces.space_inputs


def patch(bearing: float, fold: bool = False) -> None:
    """Route the ``"thrust"`` space of the fit and of the predictions through the projected coordinate."""
    iwd = names.METOCEAN_VARS.index("wind_dir")

    def projected(name: str, points: Any, lo: Any, span: Any, curve: Any = None, weights: Any = None) -> Any:
        x6, mask, lo6, span6 = _ORIGINAL(name, points, lo, span, curve, weights)
        if name != names.RBF_SPACE_THRUST:
            return x6, mask, lo6, span6
        if not isinstance(curve, spaces.TurbulentThrust):
            raise ValueError("rbf_line_thrust.py: the variant needs lifecycle.rbf.thrust.statistic: turbulent_sd")
        x = np.asarray(points, dtype=float)
        x6 = x6.copy()
        c = np.cos(np.deg2rad(x[:, iwd] - bearing))
        x6[:, 5] *= np.abs(c) if fold else c
        if lo6 is not None:
            top = float(lo6[5] + span6[5])
            lo6, span6 = lo6.copy(), span6.copy()
            lo6[5], span6[5] = (0.0, top) if fold else (-top, 2.0 * top)
        return x6, mask, lo6, span6

    spaces.space_inputs = projected
    fit.space_inputs = projected


if __name__ == "__main__":
    import reconstruction  # beside this script: sys.path[0]

    mine, rest = reconstruction.split_argv(sys.argv[1:])
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("bearing", type=float, help="the line's bearing, deg clockwise from north, platform to anchor")
    p.add_argument("--fold", action="store_true", help="|cos|: the up- and downwind sides together")
    a = p.parse_args(mine)
    patch(a.bearing, a.fold)
    sys.exit(reconstruction.main(rest))
