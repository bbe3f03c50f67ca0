"""Covariance families of the Gaussian process: the squared exponential and two Matérn kernels.

Every family is a unit-amplitude correlation of the scaled distance ``r = |(a - b) / l|``:

- ``gaussian``: ``exp(-r^2 / 2)`` (infinitely smooth; scikit-learn's ``RBF``);
- ``matern52``: ``(1 + t + t^2 / 3) exp(-t)``, ``t = sqrt(5) r`` (twice differentiable;
  ``Matern(nu=2.5)``);
- ``matern32``: ``(1 + t) exp(-t)``, ``t = sqrt(3) r`` (once differentiable; ``Matern(nu=1.5)``).

The Matérn kernels let a sample path bend faster than the squared exponential at the same length
scale, as the damage of a lightly loaded line does across rated wind. Every caller (the training
matrix, the prediction's rows, the latent variance) evaluates the exponential with the same
:func:`moorlife.rbf.kernels.exp_parts`; the prediction's compiled rows sum the squared distance
in their own order, so they agree with :func:`correlation` to rounding, not bit for bit.
"""

from __future__ import annotations

import numba as nb
import numpy as np
import numpy.typing as npt

from moorlife.rbf.kernels import exp_parts
from moorlife.space import sq_dist_block

__all__ = ["GP_COVARIANCES", "covariance_code", "correlation", "gate"]

#: Covariance families, in the order of their integer codes (:func:`covariance_code`).
GP_COVARIANCES: tuple[str, ...] = ("gaussian", "matern52", "matern32")
#: The ``nu`` of scikit-learn's ``Matern`` for each Matérn family.
MATERN_NU: dict[str, float] = {"matern52": 2.5, "matern32": 1.5}


def covariance_code(covariance: str) -> int:
    """The integer code of a covariance family (its index in :data:`GP_COVARIANCES`).

    Raises
    ------
    ValueError
        On an unknown family.
    """
    if covariance not in GP_COVARIANCES:
        raise ValueError(f"unknown GP covariance {covariance!r}; expected one of {list(GP_COVARIANCES)}")
    return GP_COVARIANCES.index(covariance)


@nb.njit(cache=True, inline="always")
def exponent(d2: float, code: int) -> float:  # pragma: no cover - numba
    """The argument of the exponential at the squared scaled distance ``d2`` (<= 0)."""
    if code == 0:
        return -0.5 * d2
    if code == 1:
        return -np.sqrt(5.0 * d2)
    return -np.sqrt(3.0 * d2)


@nb.njit(cache=True, inline="always")
def prefactor(arg: float, code: int) -> float:  # pragma: no cover - numba
    """The polynomial in front of the exponential, from its argument ``-t``."""
    if code == 0:
        return 1.0
    t = -arg
    if code == 1:
        return 1.0 + t + t * t / 3.0
    return 1.0 + t


@nb.njit(parallel=True, cache=True)
def _correlation_block(d2: np.ndarray, code: int, out: np.ndarray, tmp: np.ndarray) -> None:  # pragma: no cover - numba
    # the same operations, for code 0, as moorlife.rbf.kernels._gaussian_block with q0^2 = 2
    n, m = d2.shape
    bits = tmp.view(np.int64)
    for i in nb.prange(n):
        for j in range(m):
            d2[i, j] = exponent(d2[i, j], code)  # in place: the exponent's argument
            out[i, j], tmp[i, j] = exp_parts(max(d2[i, j], -708.0))
        for j in range(m):
            bits[i, j] = ((bits[i, j] & 0xFFFFFFFF) + 1023) << 52
        for j in range(m):
            a = d2[i, j]
            out[i, j] = out[i, j] * tmp[i, j] * prefactor(a, code) if a >= -708.0 else 0.0


def correlation(za: np.ndarray, zb: np.ndarray, length_scale: np.ndarray, covariance: str = "gaussian") -> np.ndarray:
    """The unit-amplitude correlation of embedded points (rows of ``za``, ``zb``).

    Parameters
    ----------
    za : numpy.ndarray, shape (n, p)
    zb : numpy.ndarray, shape (m, p)
    length_scale : numpy.ndarray, shape (p,)
    covariance : {"gaussian", "matern52", "matern32"}
        The family (module docstring).

    Returns
    -------
    numpy.ndarray, shape (n, m)
    """
    code = covariance_code(covariance)
    inv = 1.0 / np.asarray(length_scale, dtype=float)
    a = np.ascontiguousarray(za * inv)
    b_t = np.ascontiguousarray((zb * inv).T)
    d2 = np.empty((a.shape[0], b_t.shape[1]))
    sq_dist_block(a, b_t, np.zeros(a.shape[1], dtype=np.bool_), d2)
    out = np.empty_like(d2)
    _correlation_block(d2, code, out, np.empty_like(d2))
    return out


def gate(hs: npt.ArrayLike, scale: npt.ArrayLike) -> np.ndarray:
    """The sea gate ``exp(-hs / scale)`` of the GP's additive wind term (:mod:`moorlife.gp.kernels`).

    Parameters
    ----------
    hs : array_like
        The embedded (range-normalised) significant wave height, 0 at the bottom of the
        normalisation.
    scale : array_like
        In the same units (``inf``: no gate, 1 everywhere); broadcast against ``hs``.

    Returns
    -------
    numpy.ndarray
    """
    return np.exp(-np.asarray(hs, dtype=float) / np.asarray(scale, dtype=float))
