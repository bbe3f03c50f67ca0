"""The turbulent thrust: the standard deviation of the rotor thrust under the wind's slow turbulence.

The simulator's rotor thrust is the quasi-static curve ``T(v)`` of the hub wind, so the wind's
turbulence ``u`` makes it fluctuate about ``T(W)``. In a calm sea the slow surge that this
fluctuation drives sets the tension cycles of the lightly loaded lines. Its size

    sigma_T(W) = sd[T(W + u)],   u ~ N(0, sigma_u(W)^2),

rises with ``W`` below rated, dips at rated (where the slope of ``T`` changes sign) and falls
above it: a shape that the mean wind ``W`` and the steady thrust ``T(W)`` (whose peak is at rated)
cannot express (``validation/reconstruction.md`` section 18). ``sigma_u(W)^2`` is the configured
wind spectrum (``simulation.wind``, at the hub height) integrated over the frequencies the hourly
mean leaves out, from ``1 / averaging_time`` to the highest synthesised frequency.

Kernels (numpy in, numpy out): :func:`wind_sd` and :func:`thrust_sd`. The tabulated coordinate
the reconstruction uses is :class:`moorlife.lifecycle.spaces.TurbulentThrust`.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any

import numpy as np
import numpy.typing as npt

from moorlife import environment

__all__ = ["GRID", "N_FREQ", "NODES", "wind_sd", "thrust_sd"]

#: The tabulation of the turbulent thrust (hub wind speed, m/s): every 0.05 m/s up to 45 m/s.
GRID = np.linspace(0.0, 45.0, 901)
#: Quadrature nodes over the turbulence, in units of ``sigma_u`` (161 points over +-4 sd).
NODES = np.linspace(-4.0, 4.0, 161)
#: Frequencies of the trapezoidal integral of the wind spectrum.
N_FREQ = 20000
#: The lowest mean speed (m/s) at which the spectrum is evaluated (the NPD spectrum is 0 at 0).
_U_MIN = 0.1


def wind_sd(speeds: npt.ArrayLike, wind_cfg: Mapping[str, Any], f_min: float, f_max: float) -> np.ndarray:
    """Standard deviation (m/s) of the hub wind over ``[f_min, f_max]`` Hz at each mean speed.

    Parameters
    ----------
    speeds : array_like, shape (n,)
        One-hour mean hub wind speeds, m/s (evaluated at 0.1 m/s at least).
    wind_cfg : mapping
        The ``simulation.wind`` section with the hub ``height`` (m) the NPD spectrum needs
        (:func:`moorlife.environment.wind_spectrum`).
    f_min, f_max : float
        Hz, ``0 <= f_min < f_max``.

    Returns
    -------
    numpy.ndarray, shape (n,)
        ``sqrt(int S(f) df)`` by the trapezoidal rule on :data:`N_FREQ` frequencies.

    Raises
    ------
    ValueError
        On a frequency band that is empty or negative.
    """
    if not 0.0 <= f_min < f_max:
        raise ValueError(f"wind_sd: the band needs 0 <= f_min < f_max, got {f_min!r} to {f_max!r} Hz")
    f = np.linspace(f_min, f_max, N_FREQ)
    spectra = [environment.wind_spectrum(f, max(float(u), _U_MIN), dict(wind_cfg)) for u in np.ravel(speeds)]
    return np.sqrt(np.array([np.trapezoid(s, f) for s in spectra]))


def thrust_sd(
    thrust: Callable[[np.ndarray], np.ndarray],
    speeds: npt.ArrayLike,
    sigma_u: npt.ArrayLike,
    *,
    cap: float = np.inf,
) -> np.ndarray:
    """Standard deviation of ``thrust(min(W, cap) + u)``, ``u ~ N(0, sigma_u(W)^2)``, at each ``W``.

    Parameters
    ----------
    thrust : callable
        The thrust (N) at an array of hub wind speeds (m/s); evaluated at speeds clipped at 0.
    speeds, sigma_u : array_like, shape (n,)
        Mean hub wind speeds and the sd of their turbulence, m/s.
    cap : float
        The mean speed is held at ``cap`` above it, the turbulence being the hour's (the
        operating rotor at cut-out; ``inf``: no cap).

    Returns
    -------
    numpy.ndarray, shape (n,)
        N, by a Gaussian quadrature on :data:`NODES` (normalised weights ``exp(-x^2/2)``).
    """
    w = np.ravel(np.asarray(speeds, dtype=float))
    s = np.ravel(np.asarray(sigma_u, dtype=float))
    if w.shape != s.shape:
        raise ValueError(f"thrust_sd: {w.size} speeds and {s.size} sigma_u values")
    weights = np.exp(-(NODES**2) / 2.0)
    weights /= weights.sum()
    out = np.empty_like(w)
    for i, (wi, si) in enumerate(zip(w, s)):
        t = thrust(np.clip(min(wi, cap) + si * NODES, 0.0, None))
        mean = float((t * weights).sum())
        out[i] = np.sqrt(float(((t - mean) ** 2 * weights).sum()))
    return out
