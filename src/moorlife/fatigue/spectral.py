"""Spectral (frequency-domain) damage estimates: narrow-band and Dirlik."""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt


def spectral_moments(frequency: npt.ArrayLike, psd: npt.ArrayLike, orders=(0, 1, 2, 4)) -> np.ndarray:
    """Spectral moments ``m_n = integral f**n S(f) df`` (trapezoidal rule).

    Parameters
    ----------
    frequency : array_like, shape (nf,)
        Frequencies in Hz, increasing.
    psd : array_like, shape (..., nf)
        One-sided power spectral density, unit**2 / Hz.
    orders : sequence of float

    Returns
    -------
    ndarray, shape (norders, ...)
    """
    f = np.asarray(frequency, dtype=float)
    s = np.asarray(psd, dtype=float)
    return np.stack([np.trapezoid(f**n * s, f, axis=-1) for n in orders])


def narrowband_damage(m0: npt.ArrayLike, m2: npt.ArrayLike, duration: float, a: float, m: float) -> np.ndarray:
    """Closed-form narrow-band (Rayleigh) Miner damage of a Gaussian process.

    ``D = nu0 * T * (2 sqrt(2 m0))**m * Gamma(1 + m/2) / a``, ``nu0 = sqrt(m2/m0)``
    (Bendat 1964): cycles at the mean up-crossing rate, ranges twice a Rayleigh
    amplitude.

    Parameters
    ----------
    m0, m2 : array_like
        Spectral moments (unit**2, unit**2/s**2) of the load in the S-N curve's unit.
    duration : float
        s.
    a, m : float
        S-N curve ``N = a S**-m``.

    Returns
    -------
    ndarray
        Damage over ``duration``.
    """
    m0 = np.asarray(m0, dtype=float)
    nu0 = np.sqrt(np.asarray(m2, dtype=float) / m0)
    return nu0 * duration * (2.0 * np.sqrt(2.0 * m0)) ** m * math.gamma(1.0 + m / 2.0) / a


def _dirlik_coefficients(frequency: npt.ArrayLike, psd: npt.ArrayLike) -> tuple[np.ndarray, ...]:
    m0, m1, m2, m4 = spectral_moments(frequency, psd, (0, 1, 2, 4))
    xm = m1 / m0 * np.sqrt(m2 / m4)
    g = m2 / np.sqrt(m0 * m4)
    d1 = 2.0 * (xm - g**2) / (1.0 + g**2)
    r = (g - xm - d1**2) / (1.0 - g - d1 + d1**2)
    d2 = (1.0 - g - d1 + d1**2) / (1.0 - r)
    d3 = 1.0 - d1 - d2
    q = 1.25 * (g - d3 - d2 * r) / d1
    return m0, np.sqrt(m4 / m2), d1, d2, d3, q, r


def dirlik_pdf(ranges: npt.ArrayLike, frequency: npt.ArrayLike, psd: npt.ArrayLike) -> np.ndarray:
    """Dirlik (1985) probability density of rainflow ranges of a Gaussian process.

    Parameters
    ----------
    ranges : array_like, shape (nr,)
        Ranges ``S`` (unit of the load).
    frequency : array_like, shape (nf,)
        Hz.
    psd : array_like, shape (nf,)
        One-sided PSD of the load per Hz.

    Returns
    -------
    ndarray, shape (nr,)
        ``p(S)`` in 1/unit; integrates to 1 over ``S >= 0``.
    """
    m0, _, d1, d2, d3, q, r = _dirlik_coefficients(frequency, psd)
    z = np.asarray(ranges, dtype=float) / (2.0 * np.sqrt(m0))
    dens = d1 / q * np.exp(-z / q) + d2 * z / r**2 * np.exp(-(z**2) / (2.0 * r**2)) + d3 * z * np.exp(-(z**2) / 2.0)
    return dens / (2.0 * np.sqrt(m0))


def dirlik_damage(frequency: npt.ArrayLike, psd: npt.ArrayLike, duration: float, a: float, m: float) -> np.ndarray:
    """Dirlik (1985) spectral estimate of rainflow Miner damage of a Gaussian process.

    Parameters
    ----------
    frequency : array_like, shape (nf,)
        Hz.
    psd : array_like, shape (..., nf)
        One-sided PSD of the load (in the S-N curve's unit) per Hz.
    duration : float
        s.
    a, m : float
        S-N curve ``N = a S**-m``.

    Returns
    -------
    ndarray, shape (...)
        Damage over ``duration``.

    Notes
    -----
    With ``x_m = m1/m0 sqrt(m2/m4)``, ``gamma = m2/sqrt(m0 m4)``, ``Z = S / (2 sqrt(m0))``
    the range density is a mixture of an exponential and two Rayleigh terms with weights
    ``D1, D2, D3`` and scales ``Q, R, 1``; the damage is
    ``nu_p T / a (2 sqrt m0)**m [D1 Q**m Gamma(1+m) + sqrt(2)**m Gamma(1+m/2) (D2 |R|**m + D3)]``
    with ``nu_p = sqrt(m4/m2)`` the rate of peaks.
    """
    m0, nu_p, d1, d2, d3, q, r = _dirlik_coefficients(frequency, psd)
    moment = d1 * q**m * math.gamma(1.0 + m) + np.sqrt(2.0) ** m * math.gamma(1.0 + m / 2.0) * (
        d2 * np.abs(r) ** m + d3
    )
    return nu_p * duration / a * (2.0 * np.sqrt(m0)) ** m * moment
