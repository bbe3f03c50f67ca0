"""Readers of WAMIT numeric outputs (``.1``, ``.3``, ``.hst``, ``.12d``), redimensionalised.

WAMIT writes nondimensional values with the length scale ``ULEN`` (L), density ``rho`` and
gravity ``g`` (WAMIT User Manual v7, section 4.1)::

    A_ij = rho L^k Abar_ij          k = 3 (i, j <= 3), 4 (one rotation), 5 (both rotations)
    B_ij = rho L^k omega Bbar_ij    same k
    X_i  = rho g A L^m Xbar_i       m = 2 (force), 3 (moment)         (.2/.3, per amplitude A)
    C_ij = rho g L^k Cbar_ij        k = 2 (3,3), 3 (3,4/3,5), 4 (rotations)
    F_i  = rho g A^2 L^m Fbar_i     m = 1 (force), 2 (moment)          (.12d/.12s, per A^2)

The first column is the wave period in s (WAMIT ``IPERIN = 1``, the default and what OpenFAST
expects). In the ``.1`` file two limits carry marker periods: ``PER = 0`` (zero period) is the
*infinite-frequency* added mass and ``PER = -1`` (infinite period) the *zero-frequency* one. On
the OC4 ``marin_semi.1`` the ``PER = -1`` rows equal the 0.01 rad/s values (A11 8.74e6 kg) and
the ``PER = 0`` rows equal the infinite-frequency limit of the finite-frequency data by
Ogilvie's relation (A11 6.49e6 kg, within 0.1 %).
Headings are propagation angles in degrees (WAMIT ``BETA``). WAMIT's phase convention,
``exp(+i omega t)``, is moorlife's: the complex values are used as they are.
"""

from __future__ import annotations

import logging
import os
from pathlib import Path

import numpy as np
import xarray as xr

__all__ = [
    "read_wamit_1",
    "read_wamit_3",
    "read_wamit_hst",
    "read_wamit_12d",
    "read_wamit_dataset",
]

log = logging.getLogger(__name__)


def _exponent(i: np.ndarray, j: np.ndarray, base: int) -> np.ndarray:
    # number of rotational indices (dof 4-6) among i, j
    return base + (i >= 4).astype(int) + (j >= 4).astype(int)


def _load(path: Path, ncols: int, what: str, skip_header: bool = False, pad: int | None = None) -> np.ndarray:
    """Numeric rows of a WAMIT file, ``(nrows, pad or ncols)``; short optional columns are NaN."""
    if not path.exists():
        raise FileNotFoundError(f"{path}: no such WAMIT {what} file")
    rows = []
    with path.open("r", encoding="utf-8", errors="replace") as fh:
        for n, line in enumerate(fh, start=1):
            parts = line.split()
            if not parts:
                continue
            try:
                vals = [float(p) for p in parts]
            except ValueError:
                if n == 1 and skip_header:
                    continue
                raise ValueError(f"{path}: line {n}: not numeric: {line.strip()[:80]!r}") from None
            if len(vals) < ncols:
                raise ValueError(f"{path}: line {n}: expected at least {ncols} columns, got {len(vals)}")
            width = pad or ncols
            rows.append((vals + [np.nan] * width)[:width])
    if not rows:
        raise ValueError(f"{path}: empty WAMIT {what} file")
    out = np.asarray(rows, dtype=float)
    if np.any(np.isinf(out[:, :ncols])) or np.any(np.isnan(out[:, :ncols])):
        bad = int(np.flatnonzero(~np.all(np.isfinite(out[:, :ncols]), axis=1))[0])
        raise ValueError(f"{path}: data row {bad + 1} has a non-finite value: {out[bad].tolist()}")
    return out


def _dof_index(col: np.ndarray, path: Path, name: str) -> np.ndarray:
    idx = col.astype(int)
    bad = np.flatnonzero((idx < 1) | (idx > 6) | (idx != col))
    if bad.size:
        raise ValueError(f"{path}: data row {bad[0] + 1}: {name} = {col[bad[0]]:g} is not a rigid-body dof 1-6")
    return idx


def read_wamit_1(path, *, rho: float = 1025.0, g: float = 9.80665, ulen: float = 1.0):
    """Added mass and damping from a WAMIT ``.1`` file.

    Returns
    -------
    omega : ``(nw,)`` rad/s, increasing (finite, non-zero frequencies only);
    added_mass : ``(nw, 6, 6)``; damping : ``(nw, 6, 6)``;
    added_mass_inf : ``(6, 6)`` or None (``PER = 0`` rows); added_mass_zero : ``(6, 6)`` or None
    (``PER = -1`` rows).
    """
    p = Path(path)
    raw = _load(p, 4, ".1", pad=5)  # PER I J Abar [Bbar]; Bbar absent on PER <= 0 rows
    per, i, j = raw[:, 0], _dof_index(raw[:, 1], p, "I"), _dof_index(raw[:, 2], p, "J")
    scale = rho * ulen ** _exponent(i, j, 3)
    limits = {}
    for marker in (-1.0, 0.0):
        sel = per == marker
        if np.any(sel):
            m = np.zeros((6, 6))
            m[i[sel] - 1, j[sel] - 1] = raw[sel, 3] * scale[sel]
            limits[marker] = m
    fin = per > 0
    bad = np.flatnonzero(fin & np.isnan(raw[:, 4]))
    if bad.size:
        raise ValueError(f"{p}: data row {bad[0] + 1}: finite-period rows need 5 columns (PER I J Abar Bbar)")
    bad = np.flatnonzero((per < 0) & (per != -1.0))
    if bad.size:
        raise ValueError(f"{p}: data row {bad[0] + 1}: PER = {per[bad[0]]} (only -1 = zero frequency is allowed)")
    periods = np.unique(per[fin])[::-1]  # decreasing period = increasing omega
    omega = 2.0 * np.pi / periods
    iw = np.searchsorted(-periods, -per[fin])
    A = np.zeros((omega.size, 6, 6))
    B = np.zeros((omega.size, 6, 6))
    A[iw, i[fin] - 1, j[fin] - 1] = raw[fin, 3] * scale[fin]
    B[iw, i[fin] - 1, j[fin] - 1] = raw[fin, 4] * scale[fin] * omega[iw]
    return omega, A, B, limits.get(0.0), limits.get(-1.0)


def read_wamit_3(path, *, rho: float = 1025.0, g: float = 9.80665, ulen: float = 1.0):
    """First-order excitation from a WAMIT ``.3`` (or ``.2``) file.

    Returns
    -------
    omega : ``(nw,)`` rad/s increasing; headings : ``(nh,)`` rad in ``[0, 2 pi)`` increasing
    (a heading given twice modulo 360 deg, e.g. -180 and 180, is kept once);
    excitation : ``(nw, nh, 6)`` complex per unit amplitude, exp(+i omega t).
    """
    p = Path(path)
    raw = _load(p, 7, ".3")
    per, beta, i = raw[:, 0], raw[:, 1], _dof_index(raw[:, 2], p, "I")
    if np.any(per <= 0):
        bad = int(np.flatnonzero(per <= 0)[0])
        raise ValueError(f"{p}: data row {bad + 1}: PER = {per[bad]} must be > 0")
    m = np.where(i >= 4, 3, 2)
    val = (raw[:, 5] + 1j * raw[:, 6]) * rho * g * ulen**m
    periods = np.unique(per)[::-1]
    omega = 2.0 * np.pi / periods
    hdeg = np.mod(beta, 360.0)
    heads = np.unique(np.round(hdeg, 9))
    X = np.full((omega.size, heads.size, 6), np.nan + 0j)
    iw = np.searchsorted(-periods, -per)
    ih = np.searchsorted(heads, np.round(hdeg, 9))
    X[iw, ih, i - 1] = val
    miss = np.argwhere(np.isnan(X.real))
    if miss.size:
        w, h, d = miss[0]
        raise ValueError(f"{p}: no value for period {periods[w]:.6g} s, heading {heads[h]:.6g} deg, dof {d + 1}")
    return omega, np.deg2rad(heads), X


def read_wamit_hst(path, *, rho: float = 1025.0, g: float = 9.80665, ulen: float = 1.0) -> np.ndarray:
    """Hydrostatic restoring ``(6, 6)`` from a WAMIT ``.hst`` file (buoyancy and waterplane)."""
    p = Path(path)
    raw = _load(p, 3, ".hst")
    i, j = _dof_index(raw[:, 0], p, "I"), _dof_index(raw[:, 1], p, "J")
    k = _exponent(i, j, 2)
    C = np.zeros((6, 6))
    C[i - 1, j - 1] = raw[:, 2] * rho * g * ulen**k
    return C


def read_wamit_12d(path, *, rho: float = 1025.0, g: float = 9.80665, ulen: float = 1.0):
    """Mean drift coefficients from the diagonal of a WAMIT ``.12d`` (or ``.12s``/``.8``-like) QTF.

    Keeps the rows with ``PER_i == PER_j`` and ``BETA_1 == BETA_2`` (the mean drift), real part.

    Returns
    -------
    omega : ``(nw,)`` rad/s increasing; headings : ``(nh,)`` rad in ``[0, 2 pi)``;
    drift : ``(nw, nh, 6)`` N/m^2 (N m/m^2); dofs absent from the file are 0.
    """
    p = Path(path)
    raw = _load(p, 9, ".12d", skip_header=True)
    diag = raw[(raw[:, 0] == raw[:, 1]) & (raw[:, 2] == raw[:, 3])]
    if diag.size == 0:
        raise ValueError(f"{p}: no diagonal (PER_i = PER_j, BETA_1 = BETA_2) rows: no mean drift")
    i = _dof_index(diag[:, 4], p, "I")
    m = np.where(i >= 4, 2, 1)
    val = diag[:, 7] * rho * g * ulen**m
    periods = np.unique(diag[:, 0])[::-1]
    omega = 2.0 * np.pi / periods
    hdeg = np.mod(diag[:, 2], 360.0)
    heads = np.unique(np.round(hdeg, 9))
    D = np.zeros((omega.size, heads.size, 6))
    D[np.searchsorted(-periods, -diag[:, 0]), np.searchsorted(heads, np.round(hdeg, 9)), i - 1] = val
    return omega, np.deg2rad(heads), D


def _drift_on_grid(omega, headings, d_omega, d_heads, D) -> np.ndarray:
    """Drift on the excitation grid: linear in omega (0 below the file's range, held above);
    in heading on the circle, or -- with a single heading -- rotated with the waves."""
    out = np.zeros((omega.size, headings.size, 6))
    Dw = np.stack(
        [
            [np.interp(omega, d_omega, D[:, h, k], left=0.0, right=D[-1, h, k]) for k in range(6)]
            for h in range(d_heads.size)
        ],
        axis=-1,
    )  # (6, nw, nh_d) -> reorder
    Dw = np.moveaxis(Dw, 0, -1)  # (nw, nh_d, 6)
    if d_heads.size == 1:
        log.warning(
            "WAMIT .12d has one heading (%.1f deg): horizontal drift rotated with the waves "
            "for other headings (an approximation for a near-axisymmetric hull)",
            np.rad2deg(d_heads[0]),
        )
        rot = headings - d_heads[0]
        fx, fy = Dw[:, 0, 0], Dw[:, 0, 1]
        out[..., 0] = fx[:, None] * np.cos(rot) - fy[:, None] * np.sin(rot)
        out[..., 1] = fx[:, None] * np.sin(rot) + fy[:, None] * np.cos(rot)
        out[..., 2:] = Dw[:, 0, None, 2:]
        return out
    from moorlife.hydro import interp_heading

    for ih, h in enumerate(headings):
        out[:, ih] = interp_heading(d_heads, Dw, h)
    return out


def read_wamit_dataset(
    prefix: str | os.PathLike[str],
    *,
    rho: float = 1025.0,
    g: float = 9.80665,
    ulen: float = 1.0,
    water_depth: float = float("nan"),
) -> xr.Dataset:
    """Read ``<prefix>.1``, ``.3``, ``.hst`` (and ``.12d`` if present) as a ``platform.nc`` dataset.

    WAMIT files do not record the water depth: pass the one of the run (``water_depth``, m).

    The ``.1`` and ``.3`` frequency grids must agree; ``A_inf`` must be in the ``.1``
    (``PER = 0`` rows).
    """
    from moorlife.hydro import platform_dataset

    prefix = str(prefix)
    w1, A, B, a_inf, _ = read_wamit_1(prefix + ".1", rho=rho, g=g, ulen=ulen)
    w3, heads, X = read_wamit_3(prefix + ".3", rho=rho, g=g, ulen=ulen)
    C = read_wamit_hst(prefix + ".hst", rho=rho, g=g, ulen=ulen)
    if a_inf is None:
        raise ValueError(f"{prefix}.1: no infinite-frequency rows (PER = 0); rerun WAMIT with them")
    if w1.shape != w3.shape or not np.allclose(w1, w3, rtol=1e-4):
        raise ValueError(f"{prefix}.1 and {prefix}.3: frequency grids differ ({w1.size} vs {w3.size} values)")
    drift = None
    src = f"WAMIT {prefix}.1/.3/.hst"
    if Path(prefix + ".12d").exists():
        dw, dh, D = read_wamit_12d(prefix + ".12d", rho=rho, g=g, ulen=ulen)
        drift = _drift_on_grid(w1, heads, dw, dh, D)
        src += "/.12d"
    attrs = {
        "source": src,
        "ulen": float(ulen),
        "drift_method": "WAMIT .12d diagonal (mean drift)" if drift is not None else "none",
    }
    return platform_dataset(
        w1,
        heads,
        A,
        a_inf,
        B,
        X,
        C,
        drift if drift is not None else np.zeros(X.shape),
        water_depth=float(water_depth),
        rho=rho,
        g=g,
        attrs=attrs,
    )
