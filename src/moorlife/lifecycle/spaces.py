"""The candidate input spaces of the reconstruction: the paper's 5-D space, with the thrust, weighted, or with a trend.

``"paper"``
    The normalised 5-D sea-state space of the selection (:mod:`moorlife.space`): wind speed
    and direction, Hs, Tp, wave direction.
``"thrust"``
    The same plus a sixth scalar coordinate, the steady rotor thrust ``T(W)`` at the hour's
    hub wind speed (:func:`moorlife.turbine.thrust` with the Ct table, air density, rotor and
    cut-in/cut-out ramps of ``platform.yaml``, as the simulator uses them), normalised like
    the other scalars: ``(T - lo_T) / span_T`` with ``lo_T`` and ``span_T`` the minimum and
    range of ``T`` over the wind speeds of the space's own wind range
    (``[lo_W, lo_W + span_W]``, the hindcast's range when the selection's normalisation is
    used). The damage of the lines away from the waves peaks in a narrow band of wind speed
    just above rated, narrower than any useful shape parameter in ``W``; in ``T(W)`` that band
    is the maximum of one coordinate. With ``lifecycle.rbf.thrust.statistic: turbulent_sd`` the
    coordinate is instead the turbulent thrust ``sigma_T(W)`` (:class:`TurbulentThrust`,
    :mod:`moorlife.lifecycle.turbulence`), normalised the same way.
``"weighted"``
    The paper's 5-D space with each scalar coordinate (wind speed, Hs, Tp) multiplied by a
    weight (``lifecycle.rbf.weights``): ``w (x - lo) / span``, i.e. the span divided by the
    weight; directions as in the paper space. A weight above 1 shortens the RBF's length
    scale along that coordinate: the anisotropic metric that the damage's fast variation with
    wind speed asks for (``validation/reconstruction.md`` section 8).
``"wind_trend"``
    The paper's 5-D space, with the RBF's first-degree polynomial extended by a piecewise-linear
    function of the wind speed times harmonics of the wind direction
    (:class:`moorlife.rbf.Trend`, ``lifecycle.rbf.wind_trend``): the band of wind speed above
    rated becomes a trend fitted from every training state (:func:`space_trend`).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
import numpy.typing as npt

from moorlife import environment, names, turbine
from moorlife.lifecycle import turbulence
from moorlife.rbf.trend import Trend
from moorlife.space import direction_mask, scaling_from

__all__ = [
    "ThrustCurve",
    "TurbulentThrust",
    "thrust_curve",
    "turbulent_thrust",
    "thrust_at",
    "space_inputs",
    "space_points",
    "space_trend",
]

#: Wind-speed step (m/s) of the scan that finds the thrust range of a wind range.
_SCAN_STEP = 0.01


@dataclass(frozen=True)
class ThrustCurve:
    """The steady rotor thrust of the turbine as a function of the hub wind speed.

    Attributes
    ----------
    wind_speed, ct : numpy.ndarray, shape (n,)
        The thrust-coefficient table.
    rho_air, rotor_area : float
        kg/m3, m2.
    cut_in, cut_out, shutdown_ramp, startup_ramp : float
        m/s (:func:`moorlife.turbine.thrust`).
    """

    wind_speed: np.ndarray
    ct: np.ndarray
    rho_air: float
    rotor_area: float
    cut_in: float
    cut_out: float
    shutdown_ramp: float
    startup_ramp: float


def thrust_curve(platform_cfg: Mapping, source: str = "platform.yaml") -> ThrustCurve:
    """The :class:`ThrustCurve` of ``platform.yaml`` (its ``turbine`` and ``environment`` blocks).

    The same values as the simulator's platform model (:func:`moorlife.hydro.load_platform_model`).

    Raises
    ------
    ValueError
        On an invalid Ct table (naming the file and field).
    """
    tcfg = platform_cfg["turbine"]
    ws, ct = turbine.ct_table(tcfg, source)
    env = platform_cfg.get("environment", {}) or {}
    radius = float(tcfg["rotor_radius"])
    return ThrustCurve(
        wind_speed=ws,
        ct=ct,
        rho_air=float(env.get("rho_air", 1.225)),
        rotor_area=float(np.pi * radius**2),
        cut_in=float(tcfg["cut_in"]),
        cut_out=float(tcfg["cut_out"]),
        shutdown_ramp=float(tcfg.get("shutdown_ramp", 1.0)),
        startup_ramp=float(tcfg.get("startup_ramp", 1.0)),
    )


@dataclass(frozen=True)
class TurbulentThrust:
    """The turbulent thrust ``sigma_T(W)`` of a :class:`ThrustCurve`, tabulated (:func:`turbulent_thrust`).

    Attributes
    ----------
    curve : ThrustCurve
        The steady curve it was computed from (its knots enter the coordinate's range scan).
    wind_speed, sd : numpy.ndarray, shape (n,)
        Hub wind speeds (m/s, :data:`moorlife.lifecycle.turbulence.GRID`) and ``sigma_T`` there (N),
        linearly interpolated between them.
    """

    curve: ThrustCurve
    wind_speed: np.ndarray
    sd: np.ndarray


#: The thrust coordinate of the ``"thrust"`` space: the steady ``T(W)`` or the turbulent ``sigma_T(W)``.
ThrustCoordinate = ThrustCurve | TurbulentThrust


def turbulent_thrust(curve: ThrustCurve, wind_cfg: Mapping[str, Any], averaging_time: float) -> TurbulentThrust:
    """The turbulent thrust of the operating rotor (:mod:`moorlife.lifecycle.turbulence`).

    ``sigma_T(W)``, the sd of ``T(min(W, cut_out) + u)`` with ``T`` the operating rotor's curve
    (``Ct`` held at its last tabulated value, no shutdown ramp) and ``u`` the turbulence of the
    configured wind spectrum (at the hour's mean speed ``W``) between ``1 / averaging_time`` and
    ``simulation.wind.f_max``. The shutdown's drop to zero thrust within ``shutdown_ramp`` would
    put a spike of ``sigma_T`` at cut-out (174 kN at 25 m/s for the NREL 5 MW, against 65 kN at
    most below) among the storm hours; the operating rotor has none.

    Parameters
    ----------
    curve : ThrustCurve
    wind_cfg : mapping
        ``simulation.wind`` with the hub ``height`` (m).
    averaging_time : float
        s, the hindcast's averaging time (``lifecycle.rbf.thrust.averaging_time``).
    """
    f_max = environment.wind_settings(wind_cfg).f_max
    su = turbulence.wind_sd(turbulence.GRID, wind_cfg, 1.0 / float(averaging_time), f_max)
    operating = replace(curve, cut_out=1e3, shutdown_ramp=0.0)
    sd = turbulence.thrust_sd(lambda v: thrust_at(operating, v), turbulence.GRID, su, cap=curve.cut_out)
    return TurbulentThrust(curve=curve, wind_speed=turbulence.GRID.copy(), sd=sd)


def thrust_at(curve: ThrustCoordinate, wind_speed: npt.ArrayLike) -> np.ndarray:
    """The thrust coordinate (N) at hub wind speeds ``W`` (m/s): ``T(W)``, or ``sigma_T(W)`` when tabulated."""
    if isinstance(curve, TurbulentThrust):
        return np.interp(np.asarray(wind_speed, dtype=float), curve.wind_speed, curve.sd)
    return turbine.thrust(
        wind_speed,
        curve.wind_speed,
        curve.ct,
        rho_air=curve.rho_air,
        rotor_area=curve.rotor_area,
        cut_in=curve.cut_in,
        cut_out=curve.cut_out,
        shutdown_ramp=curve.shutdown_ramp,
        startup_ramp=curve.startup_ramp,
    )


def _thrust_range(curve: ThrustCoordinate, w_lo: float, w_hi: float) -> tuple[float, float]:
    """Minimum and range of the coordinate for ``W`` in ``[w_lo, w_hi]`` (a 0.01 m/s scan plus the Ct table's nodes)."""
    n = max(2, int(np.ceil((w_hi - w_lo) / _SCAN_STEP)) + 1)
    base = curve.curve if isinstance(curve, TurbulentThrust) else curve
    knots = [base.wind_speed, [base.cut_in, base.cut_out, base.cut_out + base.shutdown_ramp]]
    w = np.concatenate([np.linspace(w_lo, w_hi, n), *knots])
    t = thrust_at(curve, w[(w >= w_lo) & (w <= w_hi)])
    lo = float(t.min())
    span = float(t.max()) - lo
    return lo, span if span > 0 else 1.0


def space_points(name: str, points: npt.ArrayLike, curve: ThrustCoordinate | None = None) -> np.ndarray:
    """The coordinates of sea states ``points`` (n, 5) in the space ``name``, physical units.

    What a fitted model in that space is evaluated at (its normalisation, weights included, is
    the model's own): the points themselves, or with the thrust ``T(W)`` as a sixth column.
    """
    if name in (names.RBF_SPACE_WEIGHTED, names.RBF_SPACE_WIND_TREND):
        return np.asarray(points, dtype=float)
    return space_inputs(name, points, None, None, curve)[0]


def space_trend(name: str, knots: Sequence[float], harmonics: int) -> Trend | None:
    """The trend columns of the space ``name`` beside the RBF's polynomial (None but for ``"wind_trend"``).

    Parameters
    ----------
    name : str
        A space of ``names.RBF_SPACES``.
    knots : sequence of float
        Knots of the wind speed (m/s), strictly increasing (``lifecycle.rbf.wind_trend.knots``).
    harmonics : int
        Harmonics of the wind direction multiplying each hinge.

    Returns
    -------
    moorlife.rbf.Trend or None
        On the wind speed and the wind direction of the points in ``names.METOCEAN_VARS`` order.
    """
    if name != names.RBF_SPACE_WIND_TREND:
        return None
    return Trend(
        column=names.METOCEAN_VARS.index("wind_speed"),
        knots=tuple(float(k) for k in knots),
        direction=names.METOCEAN_VARS.index("wind_dir"),
        harmonics=int(harmonics),
    )


def space_inputs(
    name: str,
    points: npt.ArrayLike,
    lo: npt.ArrayLike | None,
    span: npt.ArrayLike | None,
    curve: ThrustCoordinate | None = None,
    weights: npt.ArrayLike | None = None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray | None, np.ndarray | None]:
    """The inputs of an RBF in the candidate space ``name``.

    Parameters
    ----------
    name : {"paper", "thrust", "weighted", "wind_trend"}
    points : array_like, shape (n, 5)
        Sea states in ``names.METOCEAN_VARS`` order (physical units).
    lo, span : array_like (5,) or None
        The normalisation of the paper space (None: the fit's training points).
    curve : ThrustCurve or TurbulentThrust, optional
        Required for ``"thrust"``: the steady thrust ``T(W)``, or the turbulent ``sigma_T(W)``.
    weights : array_like, shape (5,), optional
        Required for ``"weighted"``: the weight of each coordinate in ``names.METOCEAN_VARS``
        order (positive; those of the directions are ignored).

    Returns
    -------
    points : numpy.ndarray, shape (n, 5) or (n, 6)
    is_direction : numpy.ndarray of bool
    lo, span : numpy.ndarray or None
        The normalisation extended by the thrust's (None if the 5-D one is None, so that the
        fit normalises every coordinate by the training range). ``"weighted"``: always given,
        the spans (by default the training range of ``points``) divided by the weights.

    Raises
    ------
    ValueError
        On an unknown space, ``"thrust"`` without a curve, or ``"weighted"`` without positive
        weights.
    """
    x = np.asarray(points, dtype=float)
    mask = direction_mask()
    if name in (names.RBF_SPACE_PAPER, names.RBF_SPACE_WIND_TREND):  # the trend is the fit's (space_trend)
        return x, mask, None if lo is None else np.asarray(lo, float), None if span is None else np.asarray(span, float)
    if name == names.RBF_SPACE_WEIGHTED:
        if weights is None:
            raise ValueError("the 'weighted' input space needs the weights of lifecycle.rbf.weights")
        w = np.asarray(weights, dtype=float)
        if w.shape != mask.shape or not np.all(np.isfinite(w) & (w > 0)):
            raise ValueError(f"the 'weighted' space needs {mask.size} positive weights, got {w.tolist()}")
        lo_d, span_d = scaling_from(x, mask)
        lo_w = lo_d if lo is None else np.asarray(lo, float).copy()
        span_w = (span_d if span is None else np.asarray(span, float)) / np.where(mask, 1.0, w)
        return x, mask, lo_w, span_w
    if name != names.RBF_SPACE_THRUST:
        raise ValueError(f"unknown RBF input space {name!r}; expected one of {list(names.RBF_SPACES)}")
    if curve is None:
        raise ValueError("the 'thrust' input space needs the turbine's thrust curve (platform.yaml)")
    iw = names.METOCEAN_VARS.index("wind_speed")
    x6 = np.column_stack([x, thrust_at(curve, x[:, iw])])
    if lo is None or span is None:
        return x6, np.r_[mask, False], None, None
    lo5, span5 = np.asarray(lo, float), np.asarray(span, float)
    t_lo, t_span = _thrust_range(curve, float(lo5[iw]), float(lo5[iw] + span5[iw]))
    return x6, np.r_[mask, False], np.r_[lo5, t_lo], np.r_[span5, t_span]
