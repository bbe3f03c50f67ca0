"""The compiled Gaussian kernel, the weighted sums of prediction and the polynomial trend basis.

Numba kernels, float64; every row is computed by one thread in a fixed order, so the numbers
do not depend on chunk size or thread count.
"""

from __future__ import annotations

import numba as nb
import numpy as np
import numpy.typing as npt

__all__ = ["exp_parts", "gaussian", "polynomial_basis"]


# exp(-t) for the kernel block: Cody-Waite reduction t = k ln2 + r, |r| <= ln2 / 2, a
# degree-13 Taylor polynomial (truncation < 1e-17) and 2^k assembled from the bits of the
# rounding shifter. Written as plain loops so LLVM vectorises them (libm exp does not);
# within 1 ulp of numpy.exp, exactly 0 below exp(-708) (tests/test_rbf.py checks both).
_LN2_HI = 6.93147180369123816490e-01
_LN2_LO = 1.90821492927058770002e-10
_INV_LN2 = 1.44269504088896338700e00
_SHIFTER = 6755399441055744.0  # 1.5 * 2**52: x + SHIFTER rounds x to an integer in the low bits


@nb.njit(inline="always", cache=True)
def exp_parts(x: float) -> tuple[float, float]:  # pragma: no cover - numba
    """``exp(x)`` for ``-708 <= x <= 0``, in two parts: ``exp(x) = p * 2**k``.

    ``p`` is the degree-13 Taylor polynomial of ``exp(r)`` on the reduced argument
    ``r = x - k ln 2`` (``|r| <= ln 2 / 2``, Cody-Waite split of ``ln 2``). ``t = x / ln 2 +
    1.5 * 2**52`` carries the integer ``k`` in its low bits: a caller turns it into ``2**k`` in
    place (``bits = ((bits & 0xFFFFFFFF) + 1023) << 52`` on its int64 view) and multiplies. The
    three passes (parts, exponent bits, product) vectorise, where ``np.exp`` per element does
    not; every caller of this one function gets the same bits.
    """
    t = x * _INV_LN2 + _SHIFTER
    k = t - _SHIFTER
    r = (x - k * _LN2_HI) - k * _LN2_LO
    p = 1.6059043836821613e-10
    p = p * r + 2.08767569878681e-09
    p = p * r + 2.505210838544172e-08
    p = p * r + 2.755731922398589e-07
    p = p * r + 2.7557319223985893e-06
    p = p * r + 2.48015873015873e-05
    p = p * r + 0.0001984126984126984
    p = p * r + 0.001388888888888889
    p = p * r + 0.008333333333333333
    p = p * r + 0.041666666666666664
    p = p * r + 0.16666666666666666
    p = p * r + 0.5
    p = p * r + 1.0
    p = p * r + 1.0
    return p, t


@nb.njit(parallel=True, cache=True)
def _gaussian_block(
    d2: np.ndarray, inv_q2: float, out: np.ndarray, tmp: np.ndarray
) -> None:  # pragma: no cover - numba
    n, m = d2.shape
    bits = tmp.view(np.int64)
    for i in nb.prange(n):
        for j in range(m):
            out[i, j], tmp[i, j] = exp_parts(max(-d2[i, j] * inv_q2, -708.0))
        for j in range(m):
            bits[i, j] = ((bits[i, j] & 0xFFFFFFFF) + 1023) << 52
        for j in range(m):
            out[i, j] = out[i, j] * tmp[i, j] if d2[i, j] * inv_q2 <= 708.0 else 0.0


def gaussian(d2: npt.ArrayLike, shape: float) -> np.ndarray:
    """The Gaussian kernel ``exp(-r^2 / q0^2)`` on squared distances (the fast path).

    Parameters
    ----------
    d2 : array_like, shape (n, m)
        Squared normalised distances (non-negative).
    shape : float
        ``q0``.

    Returns
    -------
    numpy.ndarray, shape (n, m)
    """
    a = np.ascontiguousarray(np.atleast_2d(np.asarray(d2, dtype=float)))
    out = np.empty_like(a)
    _gaussian_block(a, 1.0 / (shape * shape), out, np.empty_like(a))
    return out


@nb.njit(parallel=True, cache=True, fastmath=True)
def _weighted_sum(
    k: np.ndarray, w_t: np.ndarray, cols: np.ndarray, out: np.ndarray
) -> None:  # pragma: no cover - numba
    # out[i, cols[o]] += sum_j k[i, j] * w_t[o, j]; each row by one thread in a fixed order, so
    # the numbers do not depend on the thread count (multi-threaded BLAS may change the last bit).
    n, m = k.shape
    for i in nb.prange(n):
        for o in range(w_t.shape[0]):
            acc = 0.0
            for j in range(m):
                acc += k[i, j] * w_t[o, j]
            out[i, cols[o]] += acc


def polynomial_basis(z: npt.ArrayLike, is_direction: npt.ArrayLike) -> np.ndarray:
    """First-degree trend basis on normalised points.

    Parameters
    ----------
    z : array_like, shape (n, d)
        Normalised points.
    is_direction : array_like of bool, shape (d,)

    Returns
    -------
    numpy.ndarray, shape (n, 1 + n_scalar + 2 * n_direction)
        Columns ``1``, each scalar, then ``cos(pi z)`` and ``sin(pi z)`` of each direction
        (``z`` in units of 180 deg).
    """
    z = np.asarray(z, dtype=float)
    isdir = np.asarray(is_direction, dtype=bool)
    cols = [np.ones((z.shape[0], 1)), z[:, ~isdir]]
    if isdir.any():
        ang = np.pi * z[:, isdir]
        cols += [np.cos(ang), np.sin(ang)]
    return np.hstack(cols)
