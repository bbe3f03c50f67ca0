"""What the infinite-depth Green function changes, frequency by frequency (validation/hydro.md, Deep water).

    .venv/bin/python validation/hydro_deep_water.py [--mesh coarse|fine] [--omega MIN:MAX:N] [--jobs J]

Solves the ``hydro`` rule's BEM (``moorlife.hydro.bem_from_settings``: config/config.yaml's
hydro section and config/platform.yaml, the chosen mesh resolution, 15-degree headings) on the
frequency grid ``MIN:MAX:N`` twice: every frequency in the finite depth of platform.yaml
(``hydro.deep_water_kh: null``), then every frequency in infinite depth. Prints one markdown row a
frequency: ``k h``, the change of A11, A33, A55, B11, B33, B55, X1, X3, X5 (heading 0) and the
largest change over all 36 terms of A and of B, over every dof and heading of X and of the mean
drift (surge, sway, yaw), each normalised as validation/hydro.md normalises its errors: by the
peak of the WAMIT ``marin_semi`` curve over 0.2-1.5 rad/s (A_ij, B_ij by
``sqrt(peak_ii peak_jj)``; X by the peak over every heading). WAMIT's ``.12d`` has one heading
and no yaw drift, so the mean drift (surge, sway, yaw, every heading) is normalised by the peak
over the band and headings of the committed coarse-mesh fixture ``tests/data/platform_coarse.nc``
(Fx and Fy by the horizontal-force peak). The last row is the infinite-frequency added mass.
``--save DIR`` keeps both datasets as NetCDF. Also prints the CPU time of both solves (the solver processes'),
whose ratio is what the threshold buys on these frequencies.
"""

from __future__ import annotations

import argparse
import resource
import time
from pathlib import Path

import numpy as np

from moorlife import hydro
from moorlife.io import read_study_config, read_yaml
from moorlife.io.platform import open_platform_nc, write_platform_nc
from moorlife.io.wamit import read_wamit_dataset

ROOT = Path(__file__).resolve().parents[1]
WAMIT = "/work/shared/reference/oc4/marin_semi"
BAND = (0.2, 1.5)
NINE = (("A", 0), ("A", 2), ("A", 4), ("B", 0), ("B", 2), ("B", 4), ("X", 0), ("X", 2), ("X", 4))


def _children_cpu() -> float:
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def solve(settings: dict, deep_water_kh: float | None, jobs: int):
    s = dict(settings)
    s.pop("deep_water_kh", None)
    if deep_water_kh is not None:
        s["deep_water_kh"] = deep_water_kh
    c0, t0 = _children_cpu(), time.perf_counter()
    ds = hydro.bem_from_settings(s, n_jobs=jobs)
    return ds, _children_cpu() - c0, time.perf_counter() - t0


def scales(wamit, fixture) -> dict[str, np.ndarray]:
    """Peaks over the band: A and B ``(6, 6)`` (geometric mean of the WAMIT diagonal peaks), X ``(6,)``
    (WAMIT), drift ``(3,)`` surge, sway, yaw (the fixture's)."""
    w = wamit["omega"].values
    band = (w >= BAND[0] - 1e-9) & (w <= BAND[1] + 1e-9)
    out = {}
    for key, var in (("A", "added_mass"), ("B", "damping")):
        d = np.max(np.abs(np.diagonal(wamit[var].values[band], axis1=1, axis2=2)), axis=0)
        out[key] = np.sqrt(np.outer(d, d))
    out["X"] = np.max(np.abs(wamit["excitation"].values[band]), axis=(0, 1))
    wf = fixture["omega"].values
    dr = np.abs(fixture["drift"].values[(wf >= BAND[0] - 1e-9) & (wf <= BAND[1] + 1e-9)])
    fxy = dr[..., :2].max()
    out["drift"] = np.array([fxy, fxy, dr[..., 5].max()])
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--mesh", default="coarse", help="hydro.mesh.resolution (coarse | fine)")
    ap.add_argument("--omega", default="0.3:1.0:15", help="MIN:MAX:N, rad/s, equally spaced")
    ap.add_argument("--jobs", type=int, default=2, help="BEM worker processes")
    ap.add_argument("--wamit", default=WAMIT, help="WAMIT prefix of the normalising peaks")
    ap.add_argument("--save", default=None, help="directory for finite.nc and infinite.nc")
    a = ap.parse_args()
    cfg = read_study_config(ROOT / "config/config.yaml", [], schema=ROOT / "workflow/schemas/config.schema.yaml")
    pcfg = read_yaml(ROOT / "config/platform.yaml")
    hcfg = {**cfg["hydro"], "mesh": {**cfg["hydro"]["mesh"], "resolution": a.mesh}, "heading_step": 15.0}
    settings = hydro.bem_settings(hcfg, pcfg)
    lo, hi, n = a.omega.split(":")
    settings["omega"] = {"min": float(lo), "max": float(hi), "n": int(n)}
    env = pcfg["environment"]
    wamit = read_wamit_dataset(a.wamit, rho=env["rho_water"], g=env["gravity"])
    sc = scales(wamit, open_platform_nc(ROOT / "tests/data/platform_coarse.nc"))

    fin, cpu_f, wall_f = solve(settings, None, a.jobs)
    inf, cpu_i, wall_i = solve(settings, 1e-12, a.jobs)  # every frequency k h > 1e-12: all deep
    assert inf.attrs["infinite_depth_frequencies"] == fin.sizes["omega"]
    if a.save:
        Path(a.save).mkdir(parents=True, exist_ok=True)
        write_platform_nc(fin, Path(a.save) / "finite.nc")
        write_platform_nc(inf, Path(a.save) / "infinite.nc")
    w = fin["omega"].values
    kh = hydro.wavenumber(w, env["water_depth"], env["gravity"]) * env["water_depth"]
    ih0 = int(np.argmin(np.abs(fin["heading"].values)))
    d = {
        "A": np.abs(inf["added_mass"].values - fin["added_mass"].values) / sc["A"],
        "B": np.abs(inf["damping"].values - fin["damping"].values) / sc["B"],
        "X": np.abs(inf["excitation"].values - fin["excitation"].values) / sc["X"],
        "drift": np.abs(inf["drift"].values - fin["drift"].values)[..., [0, 1, 5]] / sc["drift"],
    }
    print(
        f"{a.mesh} mesh ({fin.attrs['panels']} panels), {w.size} frequencies, "
        f"{fin.sizes['heading']} headings; changes infinite - finite depth, / WAMIT peak in {BAND[0]}-{BAND[1]} rad/s\n"
    )
    head = [f"{k}{j + 1}{j + 1}" if k != "X" else f"X{j + 1}" for k, j in NINE]
    print("| omega (rad/s) | k h | " + " | ".join(head) + " | all A | all B | all X | drift Fx | Fy | Mz |")
    print("|---" * (len(head) + 8) + "|")
    for i in range(w.size):
        nine = [d[k][i, j, j] if k != "X" else d["X"][i, ih0, j] for k, j in NINE]
        rest = [d["A"][i].max(), d["B"][i].max(), d["X"][i].max(), *d["drift"][i].max(axis=0)]
        print(f"| {w[i]:.2f} | {kh[i]:.2f} | " + " | ".join(f"{v:.1e}" for v in (*nine, *rest)) + " |")
    dinf = np.abs(inf["added_mass_inf"].values - fin["added_mass_inf"].values) / sc["A"]
    print(
        f"| inf | inf | {dinf[0, 0]:.1e} | {dinf[2, 2]:.1e} | {dinf[4, 4]:.1e} | | | | | | | {dinf.max():.1e} | | | | | |"
    )
    print(
        f"\nsolver CPU: finite depth {cpu_f:.1f} s, infinite depth {cpu_i:.1f} s, ratio {cpu_f / cpu_i:.2f} "
        f"(wall {wall_f:.1f} s, {wall_i:.1f} s; both include the infinite-frequency solve)"
    )


if __name__ == "__main__":
    main()
