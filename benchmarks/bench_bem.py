"""Benchmark: the cost of the hydro rule's BEM and of each Capytaine lever (issue 23, target 1).

Two modes, both on the default study's mesh (config/config.yaml: 1.2 m panels, 3-fold
symmetry, lid; 24 headings) unless ``--mesh coarse``:

1. Levers, on a few frequencies (default 0.6 and 1.2 rad/s)::

       nice -n 5 .venv/bin/python benchmarks/bench_bem.py --omega 0.6 1.2

   Each variant solves one frequency's 6 radiation and 24 diffraction problems in a fresh
   spawned process, single-threaded, as the ``hydro`` rule does (``moorlife.hydro.run_bem``:
   the body is built in this process and sent), and reports that process's CPU time
   (``RUSAGE_CHILDREN``: start, import, Green function, solves, Kochin functions) and the
   largest change of A, B and X against the baseline, normalised by the baseline's largest
   value of each (6 x 6 or dof) term at that frequency.
   Variants:

   - ``finite``: the study before issue 23, every frequency in the finite depth
     (``water_depth`` 200 m), Capytaine's default engine (LU factorisation of the one
     influence matrix of a frequency, reused by all 30 problems);
   - ``infinite``: the same problems with the infinite-depth Green function
     (``hydro.deep_water_kh``: what the threshold buys on a frequency above it);
   - ``no_lu_reuse``: finite depth, a fresh LU factorisation for every problem (the matrices
     stay cached): what LU reuse across headings buys (``--no-lu-reuse-problems`` limits the
     problems of this variant, which is slow; its cost for all 30 is then estimated from the
     extra factorisations it did, see ``levers``);
   - ``gmres``: finite depth, Capytaine's GMRES instead of LU (no factorisation at all);
   - ``float32``: finite depth, the single-precision Green function and solve;
   - ``mirror``: the hydro rule since issue 23 (``hydro.mesh.mirror_symmetry``), finite
     depth: the mesh laid out along the three mirror planes and solved with the dihedral
     symmetry (``moorlife.hydro.bem._solve_frequency``: Green function on a sixth of the
     panels, the influence matrix factorised by irreducible blocks, 5 of the 24 headings
     solved and the others moved);
   - ``mirror_infinite``: the same in infinite depth (a frequency above ``deep_water_kh``);
   - ``mirror_rotation``: the panels of ``mirror`` solved with the rotation alone and every
     heading (Capytaine's block-circulant solve, the path of the variants above): the
     reference of ``mirror``'s exactness (``--variants mirror_rotation mirror``).

   The variants up to ``float32`` use the mesh and the rotational symmetry of before issue 23
   (``mirror_symmetry: false``), whatever the study config says.

   The machine may be loaded: compare the ratios of one run, not absolute times.

2. The whole BEM of the hydro rule (``--full``), as the lead measures target 1 (<= 8 min on
   2 cores)::

       nice -n 5 .venv/bin/python benchmarks/bench_bem.py --full --jobs 2 \\
           --reference results/hydro/platform.nc --save /tmp/platform_deep.nc

   runs ``moorlife.hydro.bem_from_settings`` on the study's hydro params (with
   ``--deep-water-kh`` to override the threshold, ``null`` for every frequency in finite depth,
   and ``--no-mirror`` for ``hydro.mesh.mirror_symmetry: false``, the rule before it)
   and prints its wall and CPU time; with ``--reference`` (a platform.nc of the same mesh, e.g.
   one made before the threshold) the largest change of every coefficient, normalised by the
   reference's peak over 0.2-1.5 rad/s as validation/hydro.md does.
"""

from __future__ import annotations

import argparse
import multiprocessing
import resource
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
VARIANTS = ("finite", "infinite", "no_lu_reuse", "gmres", "float32", "mirror", "mirror_infinite", "mirror_rotation")


def _children_cpu() -> float:
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def _settings(mesh: str, deep_water_kh: str | None = "default", mirror: bool | None = None) -> dict:
    from moorlife import hydro
    from moorlife.io import read_study_config, read_yaml

    cfg = read_study_config(ROOT / "config/config.yaml", [], schema=ROOT / "workflow/schemas/config.schema.yaml")
    hcfg = {**cfg["hydro"], "mesh": {**cfg["hydro"]["mesh"], "resolution": mesh}}
    if deep_water_kh != "default":
        hcfg["deep_water_kh"] = None if deep_water_kh in (None, "null") else float(deep_water_kh)
    if mirror is not None:
        hcfg["mesh"]["mirror_symmetry"] = mirror
    return hydro.bem_settings(hcfg, read_yaml(ROOT / "config/platform.yaml"))


def _no_lu_reuse_engine():
    """Capytaine's default engine, but factorising the matrix for every right-hand side."""
    from capytaine.bem.engines import DefaultMatrixEngine
    from capytaine.tools.block_circulant_matrices import lu_decompose

    class NoLUReuse(DefaultMatrixEngine):
        def linear_solver(self, A, b):
            return lu_decompose(A).solve(b)

    return NoLUReuse()


def _body(settings: dict, variant: str):
    """The variant's Capytaine body, built in the calling process as the hydro rule does."""
    from moorlife import hydro
    from moorlife.hydro.dihedral import same_panels

    body = hydro.capytaine_body(
        hydro.members_from_config({"members": settings["members"]}, "bench"),
        float(settings["panel_size"]),
        rotational_symmetry=settings.get("rotational_symmetry"),
        mirror_symmetry=variant.startswith("mirror"),
        lid=settings["irregular_frequency_removal"],
    )
    return same_panels(body, rotation=True) if variant == "mirror_rotation" else body


def _solve_variant(body, settings: dict, omega: float, variant: str, n_problems: int | None):
    """One frequency's problems in this (fresh) process; A, B (6,6), X (nh,6), the number of
    problems solved, the CPU of the solve and the number of hull panels."""
    import capytaine as cpt
    from capytaine.bem.airy_waves import froude_krylov_force
    from capytaine.bem.engines import DefaultMatrixEngine
    from capytaine.green_functions.delhommeau import Delhommeau
    from capytaine.post_pro.kochin import compute_kochin
    from threadpoolctl import threadpool_limits

    from moorlife import hydro
    from moorlife.hydro.bem import _solve_frequency
    from moorlife.hydro.dihedral import dihedral_order, heading_orbits

    env = settings["environment"]
    depth = np.inf if variant.endswith("infinite") else float(env["water_depth"])
    kw = dict(water_depth=depth, rho=float(env["rho_water"]), g=float(env["gravity"]))
    headings = hydro.heading_grid(settings["heading_step"])
    if variant.startswith("mirror"):  # the hydro rule's own frequency solve
        theta = np.linspace(0.0, 2.0 * np.pi, int(settings["kochin_directions"]) + 1)
        n = dihedral_order(body)
        n_solved = 6 + (heading_orbits(headings, n)[0].size if n else headings.size)
        t0 = time.process_time()
        A, B, F, _, _ = _solve_frequency(body, omega, headings, theta, kw)
        return A, B, F, n_solved, time.process_time() - t0, int(body.mesh.nb_faces)
    dofs = list(body.dofs)
    problems = [cpt.RadiationProblem(body=body, omega=omega, radiating_dof=d, **kw) for d in dofs]
    problems += [cpt.DiffractionProblem(body=body, omega=omega, wave_direction=b, **kw) for b in headings]
    if variant == "no_lu_reuse" and n_problems:
        problems = problems[:n_problems]
    if variant == "no_lu_reuse":
        engine = _no_lu_reuse_engine()
    elif variant == "gmres":
        engine = DefaultMatrixEngine(linear_solver="gmres")
    elif variant == "float32":
        engine = DefaultMatrixEngine(green_function=Delhommeau(floating_point_precision="float32"))
    else:
        engine = DefaultMatrixEngine()
    theta = np.linspace(0.0, 2.0 * np.pi, int(settings["kochin_directions"]) + 1)
    A, B = np.full((6, 6), np.nan), np.full((6, 6), np.nan)
    X = np.full((headings.size, 6), np.nan, dtype=complex)
    t0 = time.process_time()
    with threadpool_limits(limits=1):
        results = cpt.BEMSolver(engine=engine).solve_all(
            problems, keep_details=True, n_jobs=1, n_threads=1, progress_bar=False
        )
        for r in results:
            if hasattr(r, "exception"):  # Capytaine's Failed*Result: the variant cannot solve this
                raise RuntimeError(f"{variant} failed: {r.exception}")
            if isinstance(r.problem, cpt.RadiationProblem):
                j = dofs.index(r.radiating_dof)
                A[:, j] = [r.added_masses[d] for d in dofs]
                B[:, j] = [r.radiation_dampings[d] for d in dofs]
            else:
                ih = int(np.argmin(np.abs(headings - r.problem.wave_direction)))
                fk = froude_krylov_force(r.problem)
                X[ih] = [r.forces[d] + fk[d] for d in dofs]
            compute_kochin(r, theta)  # as run_bem does, for the drift
    return A, B, X, len(problems), time.process_time() - t0, int(body.mesh.nb_faces)


def _max_change(now: np.ndarray, ref: np.ndarray, matrix: bool) -> float:
    """Largest |now - ref|: a (6, 6) matrix term by ``sqrt(|ref_ii ref_jj|)``, an excitation
    ``(nh, 6)`` term by the peak of its dof over the headings (the problems solved only)."""
    if matrix:
        d = np.abs(np.diag(ref))
        scale = np.sqrt(np.outer(d, d))
    else:
        scale = np.broadcast_to(np.nanmax(np.abs(ref), axis=0), ref.shape)
    ok = np.isfinite(now) & np.isfinite(ref) & (scale > 0)
    return float(np.max(np.abs(now - ref)[ok] / scale[ok])) if ok.any() else float("nan")


def _in_fresh_process(fn, *args):
    ctx = multiprocessing.get_context("spawn")
    c0, t0 = _children_cpu(), time.perf_counter()
    with ProcessPoolExecutor(max_workers=1, mp_context=ctx, max_tasks_per_child=1) as pool:
        out = pool.submit(fn, *args).result()
    return out, _children_cpu() - c0, time.perf_counter() - t0


def levers(a) -> None:
    settings = _settings(a.mesh)
    n_all = 6 + hydro_headings(settings)
    print(
        f"mesh {a.mesh} ({settings['panel_size']} m panels), {n_all} problems a frequency; CPU s of the solver process\n"
    )
    print(
        "| omega (rad/s) | variant | problems | CPU (s) | solve CPU (s) | CPU for all problems (s) | vs the first | max change A | B | X |"
    )
    print("|---|---|---|---|---|---|---|---|---|---|")
    bodies = {v: _body(settings, v) for v in a.variants}
    for w in a.omega:
        base = None
        for v in a.variants:
            try:
                (A, B, X, n, solve_cpu, faces), cpu, wall = _in_fresh_process(
                    _solve_variant, bodies[v], settings, float(w), v, a.no_lu_reuse_problems
                )
            except RuntimeError as exc:
                print(f"| {w:g} | {v} | {str(exc).splitlines()[0]} | | | | | | | |", flush=True)
                continue
            scaled = cpu  # the variant on every problem
            if base is not None and v == "no_lu_reuse" and n < n_all:
                # no LU reuse on n of the problems: its extra cost over the baseline (which
                # solves all of them with one factorisation) is n - 1 factorisations, and each
                # further problem adds one more (the baseline's per-problem cost, a triangular
                # solve, neglected): an estimate
                scaled = cpu + (n_all - n) * (solve_cpu - base[4]) / max(n - 1, 1)
            if base is None:
                base = (A, B, X, scaled, solve_cpu)
            rel = [_max_change(A, base[0], True), _max_change(B, base[1], True), _max_change(X, base[2], False)]
            print(
                f"| {w:g} | {v} | {n} | {cpu:.1f} | {solve_cpu:.1f} | {scaled:.1f} | {scaled / base[3]:.2f} "
                f"| {rel[0]:.1e} | {rel[1]:.1e} | {rel[2]:.1e} |",
                flush=True,
            )


def hydro_headings(settings: dict) -> int:
    from moorlife import hydro

    return int(hydro.heading_grid(settings["heading_step"]).size)


def full(a) -> None:
    from moorlife import hydro
    from moorlife.io.platform import open_platform_nc, write_platform_nc

    settings = _settings(a.mesh, a.deep_water_kh, False if a.no_mirror else None)
    if a.grid:  # a check of the script on a few frequencies
        lo, hi, n = a.grid.split(":")
        settings["omega"] = {"min": float(lo), "max": float(hi), "n": int(n)}
    c0, t0 = _children_cpu(), time.perf_counter()
    ds = hydro.bem_from_settings(settings, n_jobs=a.jobs)
    wall, cpu = time.perf_counter() - t0, _children_cpu() - c0
    print(
        f"hydro BEM, mesh {a.mesh} ({ds.attrs['panels']} panels), {ds.sizes['omega']} frequencies x "
        f"{ds.sizes['heading']} headings, deep_water_kh {settings.get('deep_water_kh')}, "
        f"mirror_symmetry {bool(settings.get('mirror_symmetry'))} "
        f"({ds.attrs.get('infinite_depth_frequencies', 0)} frequencies in infinite depth), {a.jobs} jobs: "
        f"wall {wall / 60:.1f} min, solver CPU {cpu / 60:.1f} min (target 1: <= 8 min wall on 2 cores)"
    )
    if a.save:
        write_platform_nc(ds, a.save)
    if not a.reference:
        return
    ref = open_platform_nc(a.reference)
    w = ref["omega"].values
    band = (w >= 0.2 - 1e-9) & (w <= 1.5 + 1e-9)
    print("\n| variable | term | max change / reference peak in 0.2-1.5 rad/s | at omega (rad/s) |")
    print("|---|---|---|---|")
    dof = ["1", "2", "3", "4", "5", "6"]
    for var in ("added_mass", "damping", "excitation", "drift"):
        new, old = ds[var].values, ref[var].values
        if var in ("added_mass", "damping"):
            d = np.max(np.abs(np.diagonal(old[band], axis1=1, axis2=2)), axis=0)
            scale = np.sqrt(np.outer(d, d))[None]
            terms = [(i, j) for i in range(6) for j in range(6)]
        else:
            scale = np.max(np.abs(old[band]), axis=(0, 1))[None, None]
            terms = [(j,) for j in (range(6) if var == "excitation" else (0, 1, 5))]
        rel = np.abs(new - old) / np.where(scale > 0, scale, np.inf)
        worst = max(terms, key=lambda t: np.max(rel[(Ellipsis, *t)]))
        iw = int(np.unravel_index(np.argmax(rel[(Ellipsis, *worst)]), rel[(Ellipsis, *worst)].shape)[0])
        print(f"| {var} | {''.join(dof[t] for t in worst)} | {np.max(rel[(Ellipsis, *worst)]):.1e} | {w[iw]:.2f} |")
    dinf = np.abs(ds["added_mass_inf"].values - ref["added_mass_inf"].values)
    d = np.abs(np.diag(ref["added_mass_inf"].values))
    print(f"| added_mass_inf | all | {np.max(dinf / np.sqrt(np.outer(d, d))):.1e} | inf |")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--mesh", default="fine", help="hydro.mesh.resolution (fine | coarse)")
    ap.add_argument("--omega", type=float, nargs="+", default=[0.6, 1.2], help="frequencies of the lever runs, rad/s")
    ap.add_argument("--variants", nargs="+", default=list(VARIANTS), choices=VARIANTS, help="the first is the baseline")
    ap.add_argument("--no-lu-reuse-problems", type=int, default=None, help="problems solved by no_lu_reuse")
    ap.add_argument("--full", action="store_true", help="the whole BEM of the hydro rule")
    ap.add_argument("--jobs", type=int, default=2, help="--full: BEM worker processes")
    ap.add_argument("--deep-water-kh", default="default", help="--full: override hydro.deep_water_kh (or null)")
    ap.add_argument("--no-mirror", action="store_true", help="--full: hydro.mesh.mirror_symmetry false (before)")
    ap.add_argument("--reference", default=None, help="--full: a platform.nc to compare with")
    ap.add_argument("--save", default=None, help="--full: write the result here")
    ap.add_argument("--grid", default=None, help="--full: MIN:MAX:N instead of the study's hydro.omega")
    a = ap.parse_args()
    full(a) if a.full else levers(a)


if __name__ == "__main__":
    main()
