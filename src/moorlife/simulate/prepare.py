"""Model preparation, once per mooring system: platform, drag strips, mooring, trim, equilibrium."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import replace
from typing import Any

import numpy as np

from moorlife.settings import SimulationSettings
from moorlife.simulate.initial import static_offsets
from moorlife.simulate.kernel import _moor_generalised
from moorlife.simulate.linear import radiation_impedance
from moorlife.simulate.model import ModelInputs, build_model

__all__ = ["prepare_model", "platform_from", "effective_added_mass_inf", "attach_mooring", "static_equilibrium"]


def _strips_from_members(members: list[Mapping[str, Any]], strip_length: float, rho: float) -> tuple[np.ndarray, ...]:
    """Morison drag strips ``(pos, axis, cdn, cda)`` from the ``members`` of platform.yaml.

    Each member ``a -> b`` is cut into strips of at most ``strip_length``; only the wetted
    part (``z <= 0``) is kept. The axial (heave-plate) drag ``axial_cd`` acts on the full
    disk ``pi D^2 / 4`` at end ``a``.
    """
    pos, axis, cdn, cda = [], [], [], []
    for mem in members:
        a = np.asarray(mem["a"], dtype=float)
        b = np.asarray(mem["b"], dtype=float)
        d = float(mem["diameter"])
        seg = b - a
        length = float(np.linalg.norm(seg))
        if length <= 0:
            raise ValueError(f"platform member {mem.get('name', '?')!r}: ends a and b coincide")
        t = seg / length
        n = max(1, int(math.ceil(length / strip_length)))
        for k in range(n):
            s0, s1 = k / n, (k + 1) / n
            p0, p1 = a + s0 * seg, a + s1 * seg
            if p0[2] > 0 and p1[2] > 0:
                continue
            # clip the wetted part at the still-water line
            if p0[2] > 0 or p1[2] > 0:
                lo, hi = (p0, p1) if p0[2] <= 0 else (p1, p0)
                f = (0.0 - lo[2]) / (hi[2] - lo[2])
                hi = lo + f * (hi - lo)
                p0, p1 = lo, hi
            wet = float(np.linalg.norm(p1 - p0))
            pos.append(0.5 * (p0 + p1))
            axis.append(t)
            cdn.append(0.5 * rho * float(mem.get("cd", 0.0)) * d * wet)
            cda.append(0.0)
        if float(mem.get("axial_cd", 0.0)) > 0 and a[2] <= 0:
            pos.append(a.copy())
            axis.append(t)
            cdn.append(0.0)
            cda.append(0.5 * rho * float(mem["axial_cd"]) * math.pi * d**2 / 4.0)
    return (
        np.asarray(pos, dtype=float).reshape(-1, 3),
        np.asarray(axis, dtype=float).reshape(-1, 3),
        np.asarray(cdn, dtype=float),
        np.asarray(cda, dtype=float),
    )


def _rest_mooring_load(proto: Any, fairleads: np.ndarray) -> np.ndarray:
    """6-DOF mooring load about the origin with the platform at rest (batch of one)."""
    state = proto.init(np.ascontiguousarray(fairleads[None, :, :], dtype=float))
    f = np.array(proto.forces(state), dtype=float)
    out = np.zeros((1, 6))
    _moor_generalised(np.zeros((1, 6)), f, np.ascontiguousarray(fairleads), out)
    return out[0]


def prepare_model(
    platform_ds: Any,
    platform_cfg: Mapping[str, Any],
    mooring_row: Mapping[str, Any],
    mooring_cfg: Mapping[str, Any] | None,
    sim_cfg: Mapping[str, Any],
) -> ModelInputs:
    """Assemble the integrator inputs of one mooring system (call once, reuse for every batch).

    Parameters
    ----------
    platform_ds : xarray.Dataset
        ``results/hydro/platform.nc`` (BEM coefficients).
    platform_cfg : mapping
        ``config/platform.yaml`` (masses, members, turbine).
    mooring_row : mapping
        The system's row of ``config/mooring_systems.tsv``.
    mooring_cfg : mapping or None
        The ``mooring:`` config section; ``mooring.model`` selects quasi-static or dynamic lines.
    sim_cfg : mapping
        The ``simulation:`` section (``extra_damping``, ``drag_strip_length``).

    Returns
    -------
    ModelInputs
    """
    from moorlife import hydro

    # the state-space fit (5-16 s) is only needed when it is the radiation model
    ss_order = 30 if SimulationSettings.from_config(sim_cfg, source="simulation").radiation == "statespace" else None
    pm = hydro.load_platform_model(platform_ds, platform_cfg, ss_order=ss_order)
    return attach_mooring(platform_from(pm, platform_cfg, sim_cfg), mooring_row, mooring_cfg)


def platform_from(pm: Any, platform_cfg: Mapping[str, Any], sim_cfg: Mapping[str, Any]) -> ModelInputs:
    """Integrator inputs of the platform alone (no mooring lines) from a ``hydro.PlatformModel``.

    * The excitation is conjugated: ``hydro`` stores WAMIT's ``exp(+i omega t)`` convention,
      the simulator uses ``exp(-i omega t)`` (:mod:`moorlife.environment`).
    * Morison strips are cut from ``platform_cfg["members"]`` at ``simulation.drag_strip_length``
      (the wave kinematics hardly vary over a few metres; fewer strips, less memory).
    * Thrust is ``turbine.thrust`` (cut-in/out ramps included) tabulated every 0.02 m/s.
    * The pitch-band filter is ``turbine.notch_filter`` at the platform's pitch frequency.
    * ``mooring_stiffness`` is the linearised OC4 mooring of ``platform.yaml``, used only by
      the linear verification runs.
    """
    from moorlife import turbine

    sim = SimulationSettings.from_config(sim_cfg, source="simulation")
    rho = float(pm.rho)
    members = platform_cfg.get("members")
    if not members:
        raise ValueError("platform config: no 'members' (needed for the Morison drag strips)")
    strip_len = max(sim.drag_strip_length, float(platform_cfg.get("morison_strip_length", 1.0)))
    strips = _strips_from_members(members, strip_len, rho)
    v = np.arange(-40.0, 80.0 + 1e-9, 0.02)
    thrust = turbine.thrust(
        v,
        pm.ct_wind_speed,
        pm.ct,
        rho_air=pm.rho_air,
        rotor_area=pm.rotor_area,
        cut_in=pm.cut_in,
        cut_out=pm.cut_out,
        shutdown_ramp=pm.shutdown_ramp,
        startup_ramp=pm.startup_ramp,
    )
    filt = turbine.notch_filter(pm.pitch_filter_centre, pm.pitch_filter_quality)
    damp = np.diag(np.asarray(sim.extra_damping, dtype=float))
    depth = float(pm.water_depth)
    if not np.isfinite(depth):  # e.g. a WAMIT import without the depth
        depth = float(platform_cfg["environment"]["water_depth"])
    radiation = sim.radiation
    if radiation == "convolution":
        memory = sim.radiation_memory
        nk = int(np.searchsorted(np.asarray(pm.kernel_t), memory + 1e-9))
        kern6 = np.asarray(pm.kernel, float)[:nk]
        pairs = _kernel_pairs(kern6)
        rad = dict(
            kernel=np.stack([kern6[:, i, j] for i, j in pairs], axis=1),
            kernel_pairs=pairs,
            kernel_dt=float(pm.kernel_dt),
        )
    elif radiation == "statespace":
        rad = dict(rad_a=pm.ss_A, rad_b=pm.ss_B, rad_c=pm.ss_C)
    else:
        raise ValueError(f"config key 'simulation.radiation' = {radiation!r}: expected 'convolution' or 'statespace'")
    model = build_model(
        mass=np.asarray(pm.mass, float) + np.asarray(pm.added_mass_inf, float),
        stiffness=np.asarray(pm.stiffness, float),
        damping=damp,
        **rad,
        omega=pm.omega,
        headings=pm.headings,
        excitation=np.conj(np.asarray(pm.excitation)),
        drift=pm.drift,
        strip_pos=strips[0],
        strip_axis=strips[1],
        strip_cdn=strips[2],
        strip_cda=strips[3],
        hub=np.asarray(pm.hub_point, float),
        thrust_speed=v,
        thrust_force=thrust,
        filt_a=filt.A,
        filt_b=np.asarray(filt.B, float).reshape(-1, 1),
        filt_c=np.asarray(filt.C, float).reshape(1, -1),
        filt_d=np.array([[float(filt.D)]]),
        depth=depth,
        rho=rho,
        gravity=float(pm.g),
        mooring_stiffness=np.asarray(pm.mooring_stiffness, float),
    )
    a_inf = effective_added_mass_inf(model, np.asarray(pm.omega, float), np.asarray(pm.added_mass, float))
    return replace(model, mass=np.asarray(pm.mass, float) + a_inf)


def _kernel_pairs(kern: np.ndarray, rel: float = 1e-3) -> np.ndarray:
    """DOF pairs ``(i, j)`` whose kernel matters: ``max|K_ij| > rel sqrt(max|K_ii| max|K_jj|)``."""
    peak = np.abs(kern).max(axis=0)
    diag = np.sqrt(np.outer(np.diag(peak), np.diag(peak)))
    i, j = np.nonzero((peak > rel * diag) & (peak > 0))
    return np.stack([i, j], axis=1).astype(np.int64)


def effective_added_mass_inf(
    model: ModelInputs, omega: np.ndarray, added_mass: np.ndarray, band: tuple[float, float] = (0.2, 2.5)
) -> np.ndarray:
    """Infinite-frequency added mass consistent with the model's radiation memory (Ogilvie).

    ``A_inf = mean_omega [A_BEM(omega) - (A(omega) - A_inf)_memory]`` over the BEM frequencies
    in ``band`` (rad/s), so that ``A_inf`` plus the memory's frequency-dependent part
    reproduces the BEM added mass where the platform responds. A BEM's own ``A_inf`` can be
    inconsistent with the kernel built from a damping curve truncated at ``omega_max`` (or
    missing); this choice keeps natural periods and RAOs on the BEM ``A(omega)``. On the OC4
    WAMIT coefficients it agrees with WAMIT's tabulated ``A_inf`` within 0.1 % (surge).

    Returns
    -------
    numpy.ndarray, shape (6, 6)
    """
    w = np.asarray(omega, dtype=float)
    sel = (w >= band[0]) & (w <= band[1])
    if not sel.any():
        raise ValueError(f"no BEM frequency in the band {band} rad/s")
    z = radiation_impedance(model, w[sel])
    a_mem = -z.imag / w[sel][:, None, None]
    return (np.asarray(added_mass, dtype=float)[sel] - a_mem).mean(axis=0)


def attach_mooring(
    model: ModelInputs, mooring_row: Mapping[str, Any], mooring_cfg: Mapping[str, Any] | None
) -> ModelInputs:
    """Give a platform model its mooring system (lines, layout, model kind, trim load).

    Parameters
    ----------
    model : ModelInputs
        The platform (any mooring fields are replaced).
    mooring_row : mapping
        The system's row of ``config/mooring_systems.tsv`` (with ``mooring_system``).
    mooring_cfg : mapping or None
        The ``mooring:`` config section; ``mooring.model`` picks quasi-static or dynamic lines.

    Returns
    -------
    ModelInputs
        With ``mooring_kind``, ``mooring_args``, ``fairleads``, ``line_info`` and the
        ``static_load`` that trims the platform to even keel at its design draft with the
        lines at rest (the ballast adjustment of each mooring system), and the quasi-static
        model of the same lines as ``static_mooring`` (the static solves of the start).
    """
    from moorlife import mooring as moor

    props = moor.line_properties(mooring_row, water_density=model.rho, gravity=model.gravity)
    layout = moor.oc4_layout(mooring_cfg)
    if abs(layout.depth - model.depth) > 1e-6:
        raise ValueError(
            f"mooring.water_depth = {layout.depth} m differs from the platform's water depth {model.depth} m"
        )
    kind = moor.mooring_settings(mooring_cfg).model
    proto = moor.make_mooring(kind, props, layout, mooring_cfg, batch=1)
    fair = np.ascontiguousarray(layout.fairleads_body, dtype=float)
    rest = _rest_mooring_load(proto, fair)
    static = np.zeros(6)
    static[[2, 3, 4]] = -rest[[2, 3, 4]]
    statics = proto if kind == "quasistatic" else moor.make_mooring("quasistatic", props, layout, mooring_cfg, batch=1)
    return replace(
        model,
        mooring_kind=kind,
        mooring_args=(props, layout, mooring_cfg, proto),
        fairleads=fair,
        static_load=static,
        static_mooring=statics,
        line_info={"link_diameter": props.link_diameter, "mbs": props.MBS, "chain": props.chain},
    )


def static_equilibrium(
    model: ModelInputs, load: np.ndarray, *, tol: float = 1e-6, max_iter: int = 50
) -> tuple[np.ndarray, np.ndarray]:
    """Static position of the moored platform under a constant external load.

    Solves ``load + static_load + F_moor(q) - K q = 0`` by Newton iterations with a
    finite-difference Jacobian, the mooring force from the quasi-static catenary of the model's
    lines (``"linear"`` models use ``mooring_stiffness``); one case of
    :func:`moorlife.simulate.initial.static_offsets`.

    Parameters
    ----------
    model : ModelInputs
    load : (6,)
        External load about the origin (e.g. steady thrust at the hub), N and N m.

    Returns
    -------
    q : (6,)
        Displacement, m and rad.
    tension : (3,)
        Fairlead tensions there, N (NaN for a linear model).
    """
    eq = static_offsets(model, np.asarray(load, dtype=float).reshape(1, 6), tol=tol, max_iter=max_iter)
    return eq.displacement[0], eq.tension[0]
