"""Mesh convergence of the OC4 added mass: panels along against panels around (validation/hydro.md 0b).

    .venv/bin/python validation/hydro_convergence.py [--no-braces] SIZE:AROUND [SIZE:AROUND ...]

e.g. ``1.2:1 1.2:2 0.85:1``. Each case meshes the `config/platform.yaml` hull with
``hull_panels(members, SIZE, around=AROUND)`` (lid on, 3-fold symmetry, as the ``hydro`` rule)
and solves the surge and heave radiation problems at infinite frequency, at 0.06 rad/s (the
surge decay) and at 1.2 rad/s (the heave damping peak). It prints one markdown row a case with
A11, A33 and B33 against WAMIT's ``marin_semi`` values (rho 1025 kg/m3; the four figures are
copied below so that the script needs only the repository). Several minutes a case at 1 m panels on one core.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

from moorlife import hydro
from moorlife.io import read_yaml

ROOT = Path(__file__).resolve().parents[1]
OMEGAS = (np.inf, 0.06, 1.2)
# WAMIT marin_semi.1 (OpenFAST r-test), redimensionalised with rho = 1025 kg/m3:
# A11 at PER = 0 (infinite frequency) and at the 104.72 s row (0.06 rad/s); A33 the same rows.
# B33 at 1.2 rad/s from the same file (validation/hydro.md section 1).
WAMIT = {"A11_inf": 6.487e6, "A11_0.06": 8.752e6, "A33_inf": 1.4699e7, "B33_1.2": 6.139e5}


def solve_case(members, panel_size: float, around: float) -> dict[str, float]:
    """A11, A33 at each of ``OMEGAS`` and B33 at 1.2 rad/s for one mesh."""
    import capytaine as cpt

    body = hydro.capytaine_body(members, panel_size, rotational_symmetry=3, lid=True, around=around)
    kw = dict(water_depth=200.0, rho=1025.0, g=9.80665)
    out: dict[str, float] = {"panels": float(body.mesh.nb_faces)}
    solver = cpt.BEMSolver()
    for w in OMEGAS:
        surge, heave = solver.solve_all(
            [cpt.RadiationProblem(body=body, omega=w, radiating_dof=d, **kw) for d in ("Surge", "Heave")],
            progress_bar=False,
        )
        tag = "inf" if np.isinf(w) else f"{w:g}"
        out[f"A11_{tag}"] = float(surge.added_masses["Surge"])
        out[f"A33_{tag}"] = float(heave.added_masses["Heave"])
        if np.isfinite(w):
            out[f"B33_{tag}"] = float(heave.radiation_dampings["Heave"])
    return out


def main(argv: list[str]) -> None:
    no_braces = "--no-braces" in argv
    cases = [tuple(float(x) for x in a.split(":")) for a in argv if not a.startswith("--")]
    members = hydro.members_from_config(read_yaml(ROOT / "config/platform.yaml"), "config/platform.yaml")
    if no_braces:
        members = [m for m in members if m.kind != "brace"]
    print(f"hull: {'columns only' if no_braces else 'columns and braces'}")
    print(
        "| panel size (m) | around | panels | A11(inf) (kg) | vs WAMIT | A11(0.06) (kg) | vs WAMIT "
        "| A33(inf) (kg) | vs WAMIT | B33(1.2) (N s/m) | vs WAMIT | time (s) |"
    )
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for size, around in cases:
        t0 = time.time()
        r = solve_case(members, size, around)
        rel = {k: 100.0 * (r[k] / WAMIT[k] - 1.0) for k in WAMIT}
        print(
            f"| {size:g} | {around:g} | {r['panels']:.0f} | {r['A11_inf']:.4e} | {rel['A11_inf']:+.1f} % "
            f"| {r['A11_0.06']:.4e} | {rel['A11_0.06']:+.1f} % | {r['A33_inf']:.4e} | {rel['A33_inf']:+.1f} % "
            f"| {r['B33_1.2']:.4e} | {rel['B33_1.2']:+.1f} % | {time.time() - t0:.0f} |",
            flush=True,
        )


if __name__ == "__main__":
    main(sys.argv[1:])
