"""Rotor thrust of the NREL 5 MW turbine from a thrust-coefficient table (methodology step 3).

``T = 0.5 rho_a A Ct(v_rel) v_rel^2``, with ``v_rel`` the wind speed relative to the moving
rotor (hub), the platform pitch natural band removed from ``v_rel`` by a notch filter, and the
thrust ramped linearly from its cut-out value to zero over ``shutdown_ramp`` (25 -> 26 m/s) and
from zero to its cut-in value over ``startup_ramp`` below cut-in.

The Ct table and its source live in ``config/platform.yaml`` (``turbine.ct_table``); see the
comment there for why the NREL/turbine-models aero-elastic table was chosen over the FLORIS one.

The filter is a continuous-time linear system ``dz/dt = A z + B u``, ``y = C z + D u``
(:class:`LinearFilter`); :func:`discretise` gives its exact zero-order-hold step for a fixed
time step, so the integrator can carry its two states alongside the platform's.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

__all__ = [
    "ct_table",
    "thrust_coefficient",
    "thrust",
    "LinearFilter",
    "notch_filter",
    "filter_response",
    "discretise",
    "filter_signal",
    "relative_wind",
]


def ct_table(turbine_cfg: Mapping, source: str = "platform.yaml") -> tuple[np.ndarray, np.ndarray]:
    """Validate and return ``(wind_speed (n,), ct (n,))`` from the ``turbine`` block.

    Raises
    ------
    ValueError
        Naming the file, the field and the first bad row.
    """
    tab = turbine_cfg.get("ct_table")
    if not isinstance(tab, Mapping) or "wind_speed" not in tab or "ct" not in tab:
        raise ValueError(f"{source}: turbine.ct_table must have 'wind_speed' and 'ct' lists")
    ws = np.asarray(tab["wind_speed"], dtype=float)
    ct = np.asarray(tab["ct"], dtype=float)
    if ws.ndim != 1 or ws.shape != ct.shape or ws.size < 2:
        raise ValueError(
            f"{source}: turbine.ct_table: wind_speed ({ws.size}) and ct ({ct.size}) must be equal-length lists of >= 2"
        )
    bad = np.flatnonzero(~np.isfinite(ct) | (ct < 0))
    if bad.size:
        raise ValueError(f"{source}: turbine.ct_table.ct[{bad[0]}] = {ct[bad[0]]:g} must be finite and >= 0")
    bad = np.flatnonzero(np.diff(ws) <= 0)
    if bad.size:
        raise ValueError(f"{source}: turbine.ct_table.wind_speed must increase; row {bad[0] + 1} = {ws[bad[0] + 1]:g}")
    return ws, ct


def thrust_coefficient(v: npt.ArrayLike, wind_speed: np.ndarray, ct: np.ndarray) -> np.ndarray:
    """Ct at wind speeds ``v`` (m/s): linear in the table, held at its end values outside."""
    return np.interp(np.asarray(v, dtype=float), wind_speed, ct)


def thrust(
    v_rel: npt.ArrayLike,
    wind_speed: np.ndarray,
    ct: np.ndarray,
    *,
    rho_air: float = 1.225,
    rotor_area: float = np.pi * 63.0**2,
    cut_in: float = 3.0,
    cut_out: float = 25.0,
    shutdown_ramp: float = 1.0,
    startup_ramp: float = 1.0,
) -> np.ndarray:
    """Rotor thrust ``0.5 rho A Ct(v) v^2`` along the wind, N.

    Between ``cut_out`` and ``cut_out + shutdown_ramp`` the thrust falls linearly from
    ``T(cut_out)`` to 0; between ``cut_in - startup_ramp`` and ``cut_in`` it rises linearly from 0
    to ``T(cut_in)``; outside ``[cut_in - startup_ramp, cut_out + shutdown_ramp]`` it is 0.
    Negative ``v_rel`` (rotor faster than the wind) gives 0.

    Parameters
    ----------
    v_rel : array_like
        Relative (filtered) rotor wind speed, m/s, any shape.

    Returns
    -------
    numpy.ndarray
        Same shape as ``v_rel``, N.
    """
    v = np.asarray(v_rel, dtype=float)
    q = 0.5 * rho_air * rotor_area

    def t_of(u):
        return q * thrust_coefficient(u, wind_speed, ct) * u**2

    out = np.where((v >= cut_in) & (v <= cut_out), t_of(np.clip(v, cut_in, cut_out)), 0.0)
    if shutdown_ramp > 0:
        f = (cut_out + shutdown_ramp - v) / shutdown_ramp
        out = np.where((v > cut_out) & (v < cut_out + shutdown_ramp), f * t_of(cut_out), out)
    if startup_ramp > 0:
        f = (v - (cut_in - startup_ramp)) / startup_ramp
        out = np.where((v < cut_in) & (v > cut_in - startup_ramp), f * t_of(cut_in), out)
    return out


@dataclass(frozen=True)
class LinearFilter:
    """Continuous-time SISO filter ``dz/dt = A z + B u``, ``y = C z + D u``.

    Attributes
    ----------
    A : ``(n, n)``; B : ``(n,)``; C : ``(n,)``; D : float.
    """

    A: np.ndarray
    B: np.ndarray
    C: np.ndarray
    D: float


def notch_filter(centre: float, quality: float = 1.0) -> LinearFilter:
    """Second-order notch (band-stop) ``H(s) = (s^2 + w0^2) / (s^2 + (w0/Q) s + w0^2)``.

    ``|H| = 0`` at ``w0``, ``-3 dB`` at the edges of a band of width ``w0 / Q``, ``H -> 1`` far
    from it (DC and high frequency pass unchanged: the mean wind and turbulence are kept).
    Realisation: ``H = 1 - (w0/Q) s / (s^2 + (w0/Q) s + w0^2)`` in controllable form,
    states ``z = (z1, z1')``.

    Parameters
    ----------
    centre : float
        ``w0``, rad/s (platform pitch natural frequency).
    quality : float
        ``Q = w0 / bandwidth``.
    """
    if not (centre > 0 and quality > 0):
        raise ValueError(f"notch_filter: centre ({centre}) and quality ({quality}) must be > 0")
    w0, bw = float(centre), float(centre) / float(quality)
    A = np.array([[0.0, 1.0], [-(w0**2), -bw]])
    return LinearFilter(A=A, B=np.array([0.0, 1.0]), C=np.array([0.0, -bw]), D=1.0)


def filter_response(filt: LinearFilter, omega: npt.ArrayLike) -> np.ndarray:
    """Complex frequency response ``H(i w)`` at ``omega`` (rad/s)."""
    w = np.atleast_1d(np.asarray(omega, dtype=float))
    n = filt.A.shape[0]
    return np.array([filt.C @ np.linalg.solve(1j * wi * np.eye(n) - filt.A, filt.B) + filt.D for wi in w])


def discretise(filt: LinearFilter, dt: float) -> tuple[np.ndarray, np.ndarray]:
    """Exact zero-order-hold step: ``z[k+1] = Ad z[k] + Bd u[k]`` (output ``C z + D u``).

    Returns
    -------
    Ad : ``(n, n)``; Bd : ``(n,)``.
    """
    from scipy.linalg import expm

    n = filt.A.shape[0]
    M = np.zeros((n + 1, n + 1))
    M[:n, :n] = filt.A * dt
    M[:n, n] = filt.B * dt
    E = expm(M)
    return E[:n, :n], E[:n, n]


def filter_signal(filt: LinearFilter, u: npt.ArrayLike, dt: float, z0: npt.ArrayLike | None = None) -> np.ndarray:
    """Run the filter over a sampled signal ``u (nt,)`` (zero-order hold), starting at rest
    or at ``z0``; with ``z0=None`` the state starts at the steady state of ``u[0]``."""
    u = np.asarray(u, dtype=float)
    Ad, Bd = discretise(filt, dt)
    z = np.linalg.solve(-filt.A, filt.B * u[0]) if z0 is None else np.asarray(z0, dtype=float)
    y = np.empty_like(u)
    for k, uk in enumerate(u):
        y[k] = filt.C @ z + filt.D * uk
        z = Ad @ z + Bd * uk
    return y


def relative_wind(wind: npt.ArrayLike, hub_velocity: npt.ArrayLike, wind_direction: npt.ArrayLike) -> np.ndarray:
    """Rotor-normal relative wind ``v_rel = U - v_hub . d`` (nacelle aligned with the wind).

    Parameters
    ----------
    wind : ``(...)`` hub-height wind speed, m/s.
    hub_velocity : ``(..., 3)`` hub velocity, m/s.
    wind_direction : ``(..., 2)`` unit vector (x, y) of the direction the wind blows *to*
        (:func:`moorlife.conventions.flow_vector`).
    """
    v = np.asarray(hub_velocity, dtype=float)
    d = np.asarray(wind_direction, dtype=float)
    return np.asarray(wind, dtype=float) - np.einsum("...k,...k->...", v[..., :2], d)
