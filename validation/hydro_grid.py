"""Would a coarser BEM frequency grid keep the simulator's inputs? (issue 23, target 1, lever 3)

    .venv/bin/python validation/hydro_grid.py results/hydro/platform.nc [--every 2 3]

No BEM is run: a coefficient at a frequency does not depend on the grid it is solved in, so
the grid of every ``k``-th frequency of a platform.nc is the BEM on that coarser grid. The
reference is the same platform.nc cut to the coarse grid's range (both end at the coarse grid's
last frequency, so that only the spacing differs: the retardation kernel tapers the damping
over the last 10 % of the range). Printed, for each ``k``:

- the retardation kernel ``K(t)`` as the simulator makes it (``moorlife.hydro.retardation_kernel``,
  0-60 s at 0.05 s, ``simulation.radiation_memory``): the largest change of the diagonal terms
  over their largest ``|K|``, and of all 36 over the largest ``|K|`` of all;
- the natural periods with the frequency-dependent added mass (``natural_periods``, what the
  decay tests see) and Ogilvie's infinite-frequency added mass from ``K``;
- linear interpolation (as ``moorlife.simulate.forcing``) of the excitation (every heading)
  and the mean drift at the frequencies left out, against their BEM values, over each
  quantity's peak in 0.2-1.5 rad/s.
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

from moorlife import hydro
from moorlife.io import read_yaml
from moorlife.io.platform import open_platform_nc

ROOT = Path(__file__).resolve().parents[1]


def _kernel(omega, B):
    t = np.arange(0.0, 60.0 + 0.025, 0.05)
    return t, hydro.retardation_kernel(omega, B, t)


def _interp_error(w_coarse, v_coarse, w_left_out, v_left_out, peak):
    """max |linear interpolation - value| / peak, per last axis."""
    flat_c = v_coarse.reshape(len(w_coarse), -1)
    got = np.stack([np.interp(w_left_out, w_coarse, flat_c[:, j]) for j in range(flat_c.shape[1])], axis=1)
    err = np.abs(got - v_left_out.reshape(len(w_left_out), -1)).reshape(v_left_out.shape)
    return np.max(err.reshape(-1, err.shape[-1]), axis=0) / np.where(peak > 0, peak, np.inf)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("platform", help="a platform.nc of the default grid")
    ap.add_argument("--every", type=int, nargs="+", default=[2, 3])
    a = ap.parse_args()
    ds = open_platform_nc(a.platform)
    pcfg = read_yaml(ROOT / "config/platform.yaml")
    w = ds["omega"].values
    A, B = ds["added_mass"].values, ds["damping"].values
    X, D = ds["excitation"].values, ds["drift"].values
    M, mtot, cg = hydro.system_mass_properties(pcfg, "platform.yaml")
    C = (
        ds["hydrostatic_stiffness"].values
        + hydro.gravity_stiffness(mtot, cg, float(ds.attrs["g"]))
        + np.diag(np.asarray(pcfg["mooring_stiffness_diag"], dtype=float))
    )
    band = (w >= 0.2 - 1e-9) & (w <= 1.5 + 1e-9)
    peak_X = np.max(np.abs(X[band]), axis=(0, 1))
    peak_D = np.max(np.abs(D[band]), axis=(0, 1))
    print(f"{a.platform}: {w.size} frequencies {w[0]:g}-{w[-1]:g} rad/s, step {w[1] - w[0]:.4f}\n")
    print(
        "| grid | frequencies | K(t) change / max of the term: K11, K33, K55 (worst diagonal) | all 36 / max of all "
        "| T surge, heave, pitch with A(w_n) (s) "
        "| A_inf (Ogilvie) A11, A33, A55 | X left out / peak (worst dof) | drift left out / peak (Fx, Fy, Mz) |"
    )
    print("|---|---|---|---|---|---|---|---|")
    for k in [1, *a.every]:
        n = 1 + (w.size - 1) // k * k  # the reference: same range as the coarse grid
        ref = slice(0, n)
        sub = slice(0, n, k)
        t, K_ref = _kernel(w[ref], B[ref])
        _, K = _kernel(w[sub], B[sub])
        dK = np.max(np.abs(K - K_ref), axis=0)
        diag = np.diagonal(dK) / np.max(np.abs(np.diagonal(K_ref, axis1=1, axis2=2)), axis=0)
        allt = np.max(dK) / np.max(np.abs(K_ref))
        T = hydro.natural_periods(M, w[sub], A[sub], C)
        Ainf = hydro.added_mass_infinite_ogilvie(w[sub], A[sub], t, K)
        left = np.setdiff1d(np.arange(n), np.arange(n)[sub])
        if left.size:
            eX = _interp_error(w[sub], X[sub], w[left], X[left], peak_X)
            eD = _interp_error(w[sub], D[sub], w[left], D[left], peak_D)
            xs, ds_ = f"{eX.max():.1e} (X{int(np.argmax(eX)) + 1})", f"{eD[0]:.1e}, {eD[1]:.1e}, {eD[5]:.1e}"
        else:
            xs = ds_ = ""
        print(
            f"| every {k} (step {w[k] - w[0]:.3f}, to {w[n - 1]:.2f}) | {w[sub].size} "
            f"| {diag[0]:.1e}, {diag[2]:.1e}, {diag[4]:.1e} (worst {diag.max():.1e}) | {allt:.1e} "
            f"| {T[0]:.2f}, {T[1]:.2f}, {T[2]:.2f} | {Ainf[0, 0]:.4e}, {Ainf[2, 2]:.4e}, {Ainf[4, 4]:.4e} | {xs} | {ds_} |"
        )


if __name__ == "__main__":
    main()
