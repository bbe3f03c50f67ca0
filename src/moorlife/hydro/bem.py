"""The Capytaine BEM: frequency and heading grids, radiation and diffraction solves, far-field
mean drift, the ``platform.nc`` dataset, and the ``hydro`` rule's driver (:func:`bem_from_settings`,
with Richardson extrapolation in panel size).

The Capytaine part (:func:`run_bem`) is the only non-pure function of :mod:`moorlife.hydro`.
"""

from __future__ import annotations

import logging
from collections.abc import Mapping
from typing import Any

import numpy as np
import numpy.typing as npt
import xarray as xr

from moorlife.hydro.body import gravity_stiffness, motion_rao, system_mass_properties
from moorlife.hydro.mesh import capytaine_body, members_from_config
from moorlife.names import DOFS
from moorlife.settings import HydroSettings, fill_section, section_defaults

log = logging.getLogger(__name__)

DOF_NAMES: tuple[str, ...] = DOFS
RADIATING_DOF = "radiating_dof"


def frequency_grid(omega_min: float, omega_max: float, n: int) -> np.ndarray:
    """Equally spaced angular frequencies ``(n,)`` in rad/s.

    Raises
    ------
    ValueError
        Unless ``0 < omega_min < omega_max`` and ``n >= 2``.
    """
    if not (0.0 < omega_min < omega_max) or int(n) < 2:
        raise ValueError(f"hydro.omega: need 0 < min < max and n >= 2, got min={omega_min}, max={omega_max}, n={n}")
    return np.linspace(float(omega_min), float(omega_max), int(n))


def heading_grid(step_deg: float) -> np.ndarray:
    """Propagation headings ``[0, 360)`` deg every ``step_deg``, returned in radians."""
    step = float(step_deg)
    if not (0.0 < step <= 180.0) or abs(360.0 / step - round(360.0 / step)) > 1e-9:
        raise ValueError(f"hydro.heading_step: {step_deg!r} must divide 360 and lie in (0, 180]")
    return np.deg2rad(np.arange(0.0, 360.0 - 1e-9, step))


def wavenumber(omega: npt.ArrayLike, depth: npt.ArrayLike, g: float) -> np.ndarray:
    """Wavenumber from ``omega^2 = g k tanh(k h)`` (Newton, rad/m).

    ``depth`` is a scalar or one depth per frequency; where it is infinite, ``k = omega^2 / g``.
    """
    w = np.asarray(omega, dtype=float)
    h_all = np.broadcast_to(np.asarray(depth, dtype=float), w.shape)
    deep = np.isinf(h_all)
    h = np.where(deep, 1.0, h_all)  # placeholder depth where infinite (overwritten below)
    k0 = w**2 / g
    k = np.where(k0 * h > 20, k0, np.maximum(k0, w / np.sqrt(g * h)))
    for _ in range(60):
        th = np.tanh(k * h)
        f = g * k * th - w**2
        df = g * th + g * k * h * (1.0 - th**2)
        k = k - f / df
    return np.where(deep, k0, k)


def solver_depths(omega: npt.ArrayLike, water_depth: float, g: float, deep_water_kh: float | None) -> np.ndarray:
    """The water depth each frequency is solved with: infinite where ``k h > deep_water_kh``.

    Above the threshold the finite-depth Green function differs from the infinite-depth one
    by terms of order ``exp(-2 k h)`` (the bottom's image), far below the discretisation
    error, and costs 2-3 times as much on the OC4 fine mesh (validation/hydro.md, section 4,
    which also shows a difference of up to 1e-3 of the peak in the heave terms that does not
    decay with ``k h``). ``k`` is the finite-depth wavenumber; an infinite frequency counts as
    ``k h`` infinite.

    Parameters
    ----------
    omega : array-like
        ``(nw,)`` rad/s (``inf`` allowed).
    water_depth : float
        The site's depth in m.
    g : float
        m/s^2.
    deep_water_kh : float or None
        The threshold; ``None`` solves every frequency with the finite depth.

    Returns
    -------
    numpy.ndarray
        ``(nw,)`` depths in m, ``water_depth`` or ``inf``.
    """
    w = np.asarray(omega, dtype=float)
    h = float(water_depth)
    out = np.full(w.shape, h)
    if deep_water_kh is None or np.isinf(h):
        return np.full(w.shape, np.inf) if np.isinf(h) else out
    finite = np.isfinite(w)
    kh = np.full(w.shape, np.inf)
    kh[finite] = wavenumber(w[finite], h, g) * h
    out[kh > float(deep_water_kh)] = np.inf
    return out


def bem_settings(hydro_cfg: Mapping, platform_cfg: Mapping) -> dict:
    """Everything that changes the BEM result, as plain data (the ``hydro`` rule's params).

    Geometry and environment come from ``platform.yaml``; grid, headings and mesh from the
    ``hydro`` section of the study config. Mass properties and the linear mooring stiffness
    are included because the mean drift coefficients depend on the body motions, the installed
    Capytaine version because the solver's numbers change with it (these params are also the
    key of the rule's between-workflow cache). For ``source: wamit`` only the file prefix and
    the environment matter.
    """
    h = HydroSettings.from_config(hydro_cfg, source="config.yaml")
    raw = fill_section("hydro", hydro_cfg, source="config.yaml")  # the omega grid as written
    if h.source == "wamit":  # only the files (rule inputs) and the redimensionalisation
        return {"source": "wamit", "wamit_prefix": h.wamit_prefix, "environment": dict(platform_cfg["environment"])}
    res = h.mesh_resolution
    sizes = h.panel_size
    if res not in sizes:
        raise ValueError(f"hydro.mesh.resolution = {res!r} is not one of hydro.mesh.panel_size {sorted(sizes)}")
    around = h.around_refinement
    # omitted at its default 1.0: the mesh is then the one from before the option existed, and
    # the settings (the rule's params) of existing runs stay valid, so no BEM reruns for nothing
    extra = {"around_refinement": around} if around != 1.0 else {}
    # the same for the deep-water threshold at null (every frequency in finite depth, as before)
    deep = {"deep_water_kh": h.deep_water_kh} if h.deep_water_kh is not None else {}
    # and for the mirror symmetry at false (the rotation alone and the mesh of before)
    mirror = {"mirror_symmetry": True} if h.mirror_symmetry else {}
    return {
        "source": h.source,
        "capytaine": _capytaine_version(),
        "wamit_prefix": h.wamit_prefix,
        "environment": dict(platform_cfg["environment"]),
        "members": [dict(m) for m in platform_cfg["members"]],
        "omega": dict(raw["omega"]),
        "heading_step": h.heading_step,
        "panel_size": sizes[res],
        "richardson": h.richardson,
        "rotational_symmetry": h.rotational_symmetry,
        **mirror,
        "irregular_frequency_removal": h.irregular_frequency_removal,
        "kochin_directions": h.kochin_directions,
        **deep,
        "bodies": {k: dict(platform_cfg[k]) for k in ("platform", "tower", "rna")},
        "mooring_stiffness_diag": list(platform_cfg.get("mooring_stiffness_diag", [0.0] * 6)),
        **extra,
    }


def _capytaine_version() -> str:
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("capytaine")
    except PackageNotFoundError:  # no BEM possible; the rule's script says so when it runs
        return "not installed"


def run_bem(
    body,
    omega: np.ndarray,
    headings: np.ndarray,
    *,
    water_depth: float,
    rho: float,
    g: float,
    mass_matrix: np.ndarray,
    stiffness: np.ndarray,
    n_kochin: int = 72,
    n_jobs: int = 1,
    deep_water_kh: float | None = None,
) -> xr.Dataset:
    """Solve radiation and diffraction with Capytaine and build the ``platform.nc`` dataset.

    Parameters
    ----------
    body : capytaine.FloatingBody
        From :func:`capytaine_body`.
    omega : numpy.ndarray
        ``(nw,)`` rad/s.
    headings : numpy.ndarray
        ``(nh,)`` propagation angles, rad.
    water_depth, rho, g : float
        m, kg/m^3, m/s^2.
    mass_matrix : numpy.ndarray
        ``(6, 6)`` system mass about the origin, used only for the motions behind the drift.
    stiffness : numpy.ndarray
        ``(6, 6)`` total restoring (hydrostatic + gravity + linear mooring) for the same.
    n_kochin : int
        Number of directions of the Kochin functions (far-field mean drift).
    deep_water_kh : float or None
        Frequencies with ``k h`` above it (and the infinite frequency) are solved with the
        infinite-depth Green function (:func:`solver_depths`); ``None``: all in ``water_depth``.
    n_jobs : int
        Worker processes; every frequency is solved single-threaded, in a fixed order, by a
        fresh solver in a freshly spawned process, so the result does not depend on ``n_jobs``
        nor on what the calling process did before
        (Capytaine's own ``n_jobs`` splits a frequency's problems into groups, which changed
        the results by up to 2e-4 relative between 2 and 3 jobs). The random sampling of
        Capytaine's Prony decomposition (finite depth) is seeded (:func:`_seed_prony`), so
        the same settings give the same bits from run to run.

    Returns
    -------
    xarray.Dataset
        See :func:`moorlife.io.platform.write_platform_nc` for the layout.
    """
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor

    import capytaine as cpt

    omega = np.asarray(omega, dtype=float)
    headings = np.asarray(headings, dtype=float)
    dofs = list(body.dofs)
    depths = solver_depths([*omega, np.inf], water_depth, g, deep_water_kh)  # the last: A_inf
    kws = [dict(water_depth=float(d), rho=float(rho), g=float(g)) for d in depths]
    log.info("capytaine: %d faces (+lid), %d frequencies, %d headings", body.mesh.nb_faces, omega.size, headings.size)
    deep = np.isinf(depths[:-1]) & np.isfinite(float(water_depth))
    if deep.any():
        log.info(
            "capytaine: %d of %d frequencies (omega >= %.3f rad/s, k h > %g) in infinite depth",
            int(deep.sum()),
            omega.size,
            float(omega[deep].min()),
            deep_water_kh,
        )
    theta = np.linspace(0.0, 2.0 * np.pi, int(n_kochin) + 1)
    nw, nh, nt = omega.size, headings.size, theta.size
    A = np.zeros((nw, 6, 6))
    B = np.zeros((nw, 6, 6))
    F = np.zeros((nw, nh, 6), dtype=complex)  # Capytaine convention exp(-i w t)
    H_rad = np.zeros((nw, 6, nt), dtype=complex)
    H_dif = np.zeros((nw, nh, nt), dtype=complex)

    # one frequency = one unit of work, whichever process runs it (see n_jobs above)
    # each frequency in a fresh spawned process: Capytaine keeps process-level state (Green
    # function tabulation, cached decompositions, matrix caches) that made an in-process solve
    # depend on what the process had solved before (2.5e-4 relative, seen inside pytest)
    ctx = multiprocessing.get_context("spawn")
    with ProcessPoolExecutor(max_workers=max(1, int(n_jobs)), mp_context=ctx, max_tasks_per_child=1) as pool:
        jobs = [
            pool.submit(_solve_frequency, body, float(w), headings, theta, kw) for w, kw in zip([*omega, np.inf], kws)
        ]
        parts = [j.result() for j in jobs]
    for iw, (a_w, b_w, f_w, hr_w, hd_w) in enumerate(parts[:-1]):
        A[iw], B[iw], F[iw], H_rad[iw], H_dif[iw] = a_w, b_w, f_w, hr_w, hd_w
    log.info("capytaine: %d frequencies solved", nw)
    A_inf = parts[-1][0]
    hs = body.compute_hydrostatic_stiffness(rho=rho, g=g).sel(influenced_dof=dofs, radiating_dof=dofs).values
    C_hydro = np.asarray(hs, dtype=float)
    # motions (Capytaine convention) and far-field mean drift, each frequency with the depth
    # (and so the wavenumber) its Kochin functions were computed with
    k = wavenumber(omega, depths[:-1], g)
    xi = motion_rao(omega, mass_matrix, A, B, stiffness, np.conj(F))  # our convention
    drift = far_field_drift(omega, k, headings, theta, H_dif, H_rad, np.conj(xi), water_depth=depths[:-1], rho=rho, g=g)
    attrs = {
        "source": f"capytaine {cpt.__version__}",
        "panels": int(body.mesh.nb_faces),
        "lid_panels": int(body.lid_mesh.nb_faces) if body.lid_mesh is not None else 0,
        "displaced_volume": float(body.volume),
        "center_of_buoyancy": [float(v) for v in body.center_of_buoyancy],
        "waterplane_area": float(body.waterplane_area),
        "drift_method": "far-field (Kochin functions, Maruo/Newman), surge sway yaw; heave roll pitch 0",
    }
    if deep_water_kh is not None:
        attrs["deep_water_kh"] = float(deep_water_kh)
        attrs["infinite_depth_frequencies"] = int(deep.sum())
        attrs["infinite_depth_omega_min"] = float(omega[deep].min()) if deep.any() else float("inf")
        attrs["added_mass_inf_depth"] = float(depths[-1])
    return platform_dataset(
        omega,
        headings,
        A,
        A_inf,
        B,
        np.conj(F),
        C_hydro,
        drift,
        water_depth=water_depth,
        rho=rho,
        g=g,
        attrs=attrs,
    )


def _solve_frequency(
    body: Any, omega: float, headings: np.ndarray, theta: np.ndarray, kw: Mapping[str, float]
) -> tuple[np.ndarray, ...]:
    """Radiation (6 dofs) and diffraction (every heading) at one frequency, single-threaded.

    On a dihedral mesh (:func:`moorlife.hydro.dihedral.dihedral_order`) the influence matrix is
    factorised by its irreducible blocks and only the headings in ``[0, pi / n]`` are solved,
    the others following by symmetry (:mod:`moorlife.hydro.dihedral`; exact).

    Returns ``A (6,6)``, ``B (6,6)``, ``F (nh,6)`` (Capytaine convention), and the Kochin
    functions ``H_rad (6,nt)`` and ``H_dif (nh,nt)`` (empty when ``omega`` is infinite).
    """
    import capytaine as cpt
    from capytaine.bem.airy_waves import froude_krylov_force
    from capytaine.post_pro.kochin import compute_kochin
    from threadpoolctl import threadpool_limits

    from moorlife.hydro import dihedral

    dofs = list(body.dofs)
    finite = bool(np.isfinite(omega))
    n = dihedral.dihedral_order(body)
    if n and (theta.size - 1) % n == 0:
        solved, how = dihedral.heading_orbits(headings, n)
    else:
        solved, how = headings, []
    problems = [cpt.RadiationProblem(body=body, omega=omega, radiating_dof=d, **kw) for d in dofs]
    if finite:
        problems += [cpt.DiffractionProblem(body=body, omega=omega, wave_direction=b, **kw) for b in solved]
    A, B = np.zeros((6, 6)), np.zeros((6, 6))
    F0 = np.zeros((solved.size, 6), dtype=complex)
    H_rad = np.zeros((6, theta.size), dtype=complex)
    H0 = np.zeros((solved.size, theta.size), dtype=complex)
    _seed_prony()
    solver = cpt.BEMSolver(engine=dihedral.dihedral_engine()) if n else cpt.BEMSolver()
    with threadpool_limits(limits=1):
        results = solver.solve_all(problems, keep_details=finite, n_jobs=1, n_threads=1, progress_bar=False)
        for r in results:
            if isinstance(r.problem, cpt.RadiationProblem):
                j = dofs.index(r.radiating_dof)
                A[:, j] = [r.added_masses[d] for d in dofs]
                B[:, j] = [r.radiation_dampings[d] for d in dofs] if finite else 0.0
                if finite:
                    H_rad[j] = compute_kochin(r, theta)
            else:
                ih = int(np.argmin(np.abs(solved - r.problem.wave_direction)))
                fk = froude_krylov_force(r.problem)
                F0[ih] = [r.forces[d] + fk[d] for d in dofs]
                H0[ih] = compute_kochin(r, theta)
    if solved is headings:
        return A, B, F0, H_rad, H0
    F = np.stack([dihedral.transform_excitation(F0[i], a, s) for i, a, s in how])
    H_dif = np.stack([dihedral.transform_kochin(H0[i], a, s) for i, a, s in how])
    return A, B, F, H_rad, H_dif


PRONY_SEED = 20190601
"""Seed of the random generator of Capytaine's Prony decomposition (any fixed value)."""


def _seed_prony() -> None:
    """Give Capytaine's Prony decomposition a freshly seeded generator.

    The finite-depth Green function approximates part of its kernel by a sum of exponentials
    (``capytaine.tools.prony_decomposition``), fitted on a domain whose end is moved at random
    by up to 1 % (to step over a singular point) with an unseeded module-level generator. The
    fit, and so every finite-depth coefficient, then changed from run to run: up to 1.5e-5 of
    the added mass between two ``make run`` (2026-12-03), and 2.4e-4 once on the coarse mesh.
    Capytaine offers no argument for it, so the module's generator is replaced before each
    frequency (each solve draws the same sequence, whatever ran before in the process).

    Raises
    ------
    RuntimeError
        If the installed Capytaine has no such generator (its Prony code changed: check it).
    """
    from capytaine.tools import prony_decomposition

    if not isinstance(getattr(prony_decomposition, "RNG", None), np.random.Generator):
        raise RuntimeError(
            "capytaine.tools.prony_decomposition.RNG is gone: check how this Capytaine version "
            "randomises its Prony decomposition before trusting the BEM to be reproducible"
        )
    prony_decomposition.RNG = np.random.default_rng(PRONY_SEED)


def far_field_drift(
    omega: np.ndarray,
    k: np.ndarray,
    headings: np.ndarray,
    theta: np.ndarray,
    H_dif: np.ndarray,
    H_rad: np.ndarray,
    rao_capytaine: np.ndarray,
    *,
    water_depth: npt.ArrayLike,
    rho: float,
    g: float,
) -> np.ndarray:
    """Mean drift force per amplitude^2 from Kochin functions (far-field, Maruo/Newman).

    Capytaine's ``far_field_mean_drift_force`` restricted to unidirectional waves and vectorised.

    Parameters
    ----------
    omega, k : numpy.ndarray
        ``(nw,)`` rad/s and rad/m.
    headings : numpy.ndarray
        ``(nh,)`` rad.
    theta : numpy.ndarray
        ``(nt,)`` Kochin directions covering ``[0, 2 pi]`` inclusive, equally spaced.
    H_dif : numpy.ndarray
        ``(nw, nh, nt)`` diffraction Kochin functions (Capytaine convention).
    H_rad : numpy.ndarray
        ``(nw, 6, nt)`` radiation Kochin functions per unit motion amplitude (Capytaine's
        radiation problems prescribe a unit displacement, velocity ``-i w``).
    rao_capytaine : numpy.ndarray
        ``(nw, nh, 6)`` motion per unit amplitude in Capytaine's convention.
    water_depth : float or numpy.ndarray
        m, one value or ``(nw,)``: the depth each frequency was solved with (``inf`` allowed).

    Returns
    -------
    numpy.ndarray
        ``(nw, nh, 6)``, only surge, sway and yaw non-zero.
    """
    H = 1j * (H_dif + np.einsum("whd,wdt->wht", rao_capytaine, H_rad))  # (nw, nh, nt)
    dth = theta[1] - theta[0]
    dH = np.gradient(H, dth, axis=-1, edge_order=2)
    # periodic derivative at the ends
    dH[..., 0] = dH[..., -1] = (H[..., 1] - H[..., -2]) / (2 * dth)
    Hb = np.stack(
        [
            [
                np.interp(headings[j] % (2 * np.pi), theta, H[i, j].real)
                + 1j * np.interp(headings[j] % (2 * np.pi), theta, H[i, j].imag)
                for j in range(H.shape[1])
            ]
            for i in range(H.shape[0])
        ]
    )
    dHb = np.stack(
        [
            [
                np.interp(headings[j] % (2 * np.pi), theta, dH[i, j].real)
                + 1j * np.interp(headings[j] % (2 * np.pi), theta, dH[i, j].imag)
                for j in range(H.shape[1])
            ]
            for i in range(H.shape[0])
        ]
    )
    h_all = np.broadcast_to(np.asarray(water_depth, dtype=float), np.shape(omega))
    deep = np.isinf(h_all)
    h = np.where(deep, 1.0, h_all)  # placeholder where infinite (the deep formula is used there)
    coef1 = 2 * np.pi * rho * omega
    k0 = omega**2 / g
    coef2 = np.where(
        deep,
        2 * np.pi * rho * k**2,
        2 * np.pi * rho * k * (k0 * h) ** 2 / (h * ((k * h) ** 2 - (k0 * h) ** 2 + k0 * h)),
    )
    c1, c2 = coef1[:, None], coef2[:, None]
    absH2 = np.abs(H) ** 2
    integ = lambda f: np.trapezoid(f, theta, axis=-1)  # noqa: E731
    fx = -c1 * np.cos(headings) * Hb.imag - c2 * integ(absH2 * np.cos(theta))
    fy = -c1 * np.sin(headings) * Hb.imag - c2 * integ(absH2 * np.sin(theta))
    mz = c1 / k[:, None] * dHb.real - c2 / k[:, None] * integ(np.imag(np.conj(H) * dH))
    out = np.zeros(H.shape[:2] + (6,))
    out[..., 0], out[..., 1], out[..., 5] = fx, fy, mz
    return out


def platform_dataset(
    omega,
    headings,
    added_mass,
    added_mass_inf,
    damping,
    excitation,
    hydrostatic_stiffness,
    drift,
    *,
    water_depth: float,
    rho: float,
    g: float,
    attrs: Mapping | None = None,
) -> xr.Dataset:
    """Assemble the ``platform.nc`` dataset from arrays (package conventions, SI units).

    Parameters
    ----------
    omega : ``(nw,)`` rad/s; headings : ``(nh,)`` rad (propagation angle);
    added_mass, damping : ``(nw, 6, 6)``; added_mass_inf : ``(6, 6)``;
    excitation : ``(nw, nh, 6)`` complex, per unit amplitude, exp(+i w t);
    hydrostatic_stiffness : ``(6, 6)`` buoyancy + waterplane; drift : ``(nw, nh, 6)`` or None.
    """
    dof = list(DOF_NAMES)
    coords = {
        "omega": ("omega", np.asarray(omega, float), {"units": "rad s-1", "long_name": "wave angular frequency"}),
        "heading": (
            "heading",
            np.asarray(headings, float),
            {
                "units": "rad",
                "long_name": "wave propagation angle, counter-clockwise from +x (east), direction of travel",
            },
        ),
        "dof": ("dof", dof),
        RADIATING_DOF: (RADIATING_DOF, dof),
    }
    mat = ("omega", "dof", RADIATING_DOF)
    units_m = "kg, kg m, kg m2 (by dof pair)"
    data = {
        "added_mass": (
            mat,
            np.asarray(added_mass, float),
            {"units": units_m, "long_name": "radiation added mass A(omega) about the origin"},
        ),
        "added_mass_inf": (
            ("dof", RADIATING_DOF),
            np.asarray(added_mass_inf, float),
            {"units": units_m, "long_name": "infinite-frequency added mass"},
        ),
        "damping": (
            mat,
            np.asarray(damping, float),
            {"units": "N s m-1, N s, N m s (by dof pair)", "long_name": "radiation damping B(omega)"},
        ),
        "excitation": (
            ("omega", "heading", "dof"),
            np.asarray(excitation, complex),
            {
                "units": "N m-1, N (moments: N m m-1)",
                "long_name": "first-order wave excitation per unit amplitude",
                "phase_convention": "exp(+i omega t) (WAMIT); eta = Re[a exp(i omega t)] at the origin",
            },
        ),
        "hydrostatic_stiffness": (
            ("dof", RADIATING_DOF),
            np.asarray(hydrostatic_stiffness, float),
            {
                "units": "N m-1, N, N m (by dof pair)",
                "long_name": "hydrostatic restoring, buoyancy and waterplane only (no -m g zG)",
            },
        ),
    }
    if drift is not None:
        data["drift"] = (
            ("omega", "heading", "dof"),
            np.asarray(drift, float),
            {"units": "N m-2, N m m-2 (moments)", "long_name": "mean drift force per wave amplitude squared"},
        )
    ds = xr.Dataset(
        {k: xr.Variable(*v) for k, v in data.items()},
        coords={k: xr.Variable(*v) if len(v) == 3 else xr.Variable(*v) for k, v in coords.items()},
    )
    ds.attrs.update(
        {
            "rho": float(rho),
            "g": float(g),
            "water_depth": float(water_depth),
            "reference_point": [0.0, 0.0, 0.0],
            "phase_convention": "exp(+i omega t) (WAMIT); Capytaine output conjugated",
        }
    )
    if attrs:
        ds.attrs.update(dict(attrs))
    return ds


def richardson(fine: xr.Dataset, coarse: xr.Dataset, ratio: float = 2.0) -> xr.Dataset:
    """First-order Richardson extrapolation in panel size of the hydrodynamic coefficients.

    A constant-panel BEM converges linearly in the panel size ``h`` near sharp edges (the
    heave-plate rims): ``F(h) = F0 + c h``. With ``F(h)`` and ``F(ratio h)``:
    ``F0 = F(h) + (F(h) - F(ratio h)) / (ratio - 1)``. Applied to ``added_mass``,
    ``added_mass_inf``, ``damping``, ``excitation`` and ``drift``; hydrostatics are kept from
    the fine mesh (exact to its polygons).
    """
    out = fine.copy()
    f = 1.0 / (float(ratio) - 1.0)
    for v in ("added_mass", "added_mass_inf", "damping", "excitation", "drift"):
        if v in fine and v in coarse:
            out[v] = (fine[v] + f * (fine[v] - coarse[v])).assign_attrs(fine[v].attrs)
    out.attrs["richardson"] = f"F(h) + (F(h) - F({ratio:g} h)) / {ratio - 1:g}, h = {fine.attrs.get('panel_size')} m"
    return out


def bem_from_settings(settings: Mapping, n_jobs: int = 1) -> xr.Dataset:
    """Run the BEM described by :func:`bem_settings` (the ``hydro`` rule's params).

    With ``settings["richardson"]`` the BEM is also run at twice the panel size and the
    coefficients are extrapolated to zero panel size (:func:`richardson`).

    Returns
    -------
    xarray.Dataset
        The ``platform.nc`` dataset, with the settings' mesh information in its attributes.
    """
    ds = _bem_one_mesh(settings, float(settings["panel_size"]), n_jobs)
    if settings.get("richardson"):
        coarse = _bem_one_mesh(settings, 2.0 * float(settings["panel_size"]), n_jobs)
        ds = richardson(ds, coarse, 2.0)
    return ds


def _bem_one_mesh(settings: Mapping, panel_size: float, n_jobs: int) -> xr.Dataset:
    env = settings["environment"]
    members = members_from_config({"members": settings["members"]}, "hydro params")
    om = settings["omega"]
    omega = frequency_grid(om["min"], om["max"], om["n"])
    headings = heading_grid(settings["heading_step"])
    M, mtot, cg = system_mass_properties(settings["bodies"], "hydro params")
    # omitted at its schema default (bem_settings)
    around = float(settings.get("around_refinement", section_defaults("hydro.mesh")["around_refinement"]))
    mirror = bool(settings.get("mirror_symmetry"))  # omitted at false (bem_settings)
    body = capytaine_body(
        members,
        panel_size,
        rotational_symmetry=settings.get("rotational_symmetry"),
        mirror_symmetry=mirror,
        lid=settings["irregular_frequency_removal"],
        around=around,
    )
    rho, g, h = float(env["rho_water"]), float(env["gravity"]), float(env["water_depth"])
    Ch = np.asarray(body.compute_hydrostatic_stiffness(rho=rho, g=g).values, dtype=float)
    C = Ch + gravity_stiffness(mtot, cg, g) + np.diag(np.asarray(settings["mooring_stiffness_diag"], dtype=float))
    ds = run_bem(
        body,
        omega,
        headings,
        water_depth=h,
        rho=rho,
        g=g,
        mass_matrix=M,
        stiffness=C,
        n_kochin=settings["kochin_directions"],
        n_jobs=n_jobs,
        deep_water_kh=settings.get("deep_water_kh"),  # omitted at null (bem_settings)
    )
    ds.attrs.update(
        {
            "panel_size": float(panel_size),
            "around_refinement": around,
            "rotational_symmetry": int(settings.get("rotational_symmetry") or 0),
            "mirror_symmetry": int(mirror),
            "irregular_frequency_removal": int(bool(settings["irregular_frequency_removal"])),
        }
    )
    return ds
