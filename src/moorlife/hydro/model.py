"""The simulator's linear model of the platform, :class:`PlatformModel`, built from
``platform.nc`` and ``platform.yaml`` by :func:`load_platform_model`."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np
import xarray as xr

from moorlife.hydro.bem import RADIATING_DOF
from moorlife.hydro.body import gravity_stiffness, natural_periods, system_mass_properties
from moorlife.hydro.loads import morison_elements
from moorlife.hydro.mesh import members_from_config
from moorlife.hydro.radiation import fit_state_space, retardation_kernel


@dataclass(frozen=True)
class PlatformModel:
    """Everything the time-domain integrator needs, as arrays (SI units, origin at SWL).

    Equation of motion (Cummins), ``x`` the 6 dofs about the origin::

        (mass + added_mass_inf) xddot + C_ss x_r + stiffness x
            = F_exc(t) + F_drift(t) + F_morison + F_mooring + F_thrust
        dx_r/dt = ss_A x_r + ss_B xdot          (radiation force = -ss_C @ x_r)

    or, with the kernel, radiation force ``= -sum K(t_k) xdot(t - t_k) kernel_dt``.

    Attributes
    ----------
    mass : ``(6, 6)`` platform + ballast + tower + RNA about the origin, kg / kg m / kg m^2.
    total_mass : float, kg; cg : ``(3,)`` m.
    added_mass_inf : ``(6, 6)``.
    hydrostatic_stiffness : ``(6, 6)`` buoyancy + waterplane (as WAMIT .hst).
    stiffness : ``(6, 6)`` hydrostatic + gravity (``-m g z_G``); no mooring.
    ss_A ``(n, n)``, ss_B ``(n, 6)``, ss_C ``(6, n)``: radiation state space;
    ss_kernel_error, ss_damping_error : float, relative fit errors (see :class:`StateSpace`).
    kernel_t ``(nt,)`` s, kernel ``(nt, 6, 6)``, kernel_dt : float: the retardation kernel.
    omega ``(nw,)`` rad/s, headings ``(nh,)`` rad (propagation angle),
    excitation ``(nw, nh, 6)`` complex per unit amplitude, exp(+i w t),
    drift ``(nw, nh, 6)`` N/m^2, added_mass / damping ``(nw, 6, 6)``.
    morison_points ``(ne, 3)``, morison_axis ``(ne, 3)``, morison_length, morison_diameter,
    morison_cd ``(ne,)``; axial_points ``(np, 3)``, axial_axis ``(np, 3)``, axial_area,
    axial_cd ``(np,)`` (heave plates).
    rho, g, water_depth : environment; rho_air : kg/m^3.
    hub_point ``(3,)`` m, hub_height m, rotor_radius m, rotor_area m^2,
    ct_wind_speed, ct ``(nct,)``, cut_in, cut_out, shutdown_ramp, startup_ramp m/s,
    pitch_natural_frequency rad/s (with the linear OC4 mooring), pitch_filter_centre rad/s,
    pitch_filter_quality.
    """

    mass: np.ndarray
    total_mass: float
    cg: np.ndarray
    added_mass_inf: np.ndarray
    hydrostatic_stiffness: np.ndarray
    stiffness: np.ndarray
    ss_A: np.ndarray
    ss_B: np.ndarray
    ss_C: np.ndarray
    ss_kernel_error: float
    ss_damping_error: float
    kernel_t: np.ndarray
    kernel: np.ndarray
    kernel_dt: float
    omega: np.ndarray
    headings: np.ndarray
    excitation: np.ndarray
    drift: np.ndarray
    added_mass: np.ndarray
    damping: np.ndarray
    morison_points: np.ndarray
    morison_axis: np.ndarray
    morison_length: np.ndarray
    morison_diameter: np.ndarray
    morison_cd: np.ndarray
    axial_points: np.ndarray
    axial_axis: np.ndarray
    axial_area: np.ndarray
    axial_cd: np.ndarray
    rho: float
    g: float
    water_depth: float
    rho_air: float
    hub_point: np.ndarray
    hub_height: float
    rotor_radius: float
    rotor_area: float
    ct_wind_speed: np.ndarray
    ct: np.ndarray
    cut_in: float
    cut_out: float
    shutdown_ramp: float
    startup_ramp: float
    pitch_natural_frequency: float
    pitch_filter_centre: float
    pitch_filter_quality: float
    mooring_stiffness: np.ndarray = field(default_factory=lambda: np.zeros((6, 6)))


def load_platform_model(
    platform: xr.Dataset,
    platform_cfg: Mapping,
    *,
    kernel_duration: float = 80.0,
    kernel_dt: float = 0.2,
    ss_order: int | None = 30,
    source: str = "platform.yaml",
) -> PlatformModel:
    """Build the simulator's :class:`PlatformModel` from ``platform.nc`` and ``platform.yaml``.

    Parameters
    ----------
    platform : xarray.Dataset
        As read by :func:`moorlife.io.platform.open_platform_nc` (complex ``excitation``).
    platform_cfg : mapping
        ``platform.yaml`` content.
    kernel_duration, kernel_dt : float
        Length and step of the retardation kernel, s.
    ss_order : int or None
        Order of the radiation state space; None skips the fit (5-16 s) when the simulator
        uses the convolution, and leaves empty ``ss_*`` arrays with NaN fit errors.
    """
    from moorlife.turbine import ct_table

    for v in ("added_mass", "added_mass_inf", "damping", "excitation", "hydrostatic_stiffness"):
        if v not in platform:
            raise ValueError(f"platform dataset: variable '{v}' is missing")
    env = platform_cfg["environment"]
    rho, g = float(platform.attrs.get("rho", env["rho_water"])), float(platform.attrs.get("g", env["gravity"]))
    M, mtot, cg = system_mass_properties(platform_cfg, source)
    omega = platform["omega"].values
    A = platform["added_mass"].transpose("omega", "dof", RADIATING_DOF).values
    B = platform["damping"].transpose("omega", "dof", RADIATING_DOF).values
    Ainf = platform["added_mass_inf"].transpose("dof", RADIATING_DOF).values
    Ch = platform["hydrostatic_stiffness"].transpose("dof", RADIATING_DOF).values
    X = platform["excitation"].transpose("omega", "heading", "dof").values
    D = platform["drift"].transpose("omega", "heading", "dof").values if "drift" in platform else np.zeros(X.shape)
    C = Ch + gravity_stiffness(mtot, cg, g)
    t = np.arange(0.0, kernel_duration + 0.5 * kernel_dt, kernel_dt)
    K = retardation_kernel(omega, B, t)
    if ss_order is None:
        ss_a, ss_b, ss_c, ss_errs = np.zeros((0, 0)), np.zeros((0, 6)), np.zeros((6, 0)), (np.nan, np.nan)
    else:
        step = max(1, int(round(0.5 / kernel_dt)))  # fit on a 0.5 s sampling: small Hankel matrix
        ss = fit_state_space(t[::step], K[::step], ss_order, omega=omega, damping=B)
        ss_a, ss_b, ss_c, ss_errs = ss.A, ss.B, ss.C, (ss.kernel_error, ss.damping_error)
    mem = members_from_config(platform_cfg, source)
    el = morison_elements(mem, float(platform_cfg.get("morison_strip_length", 1.0)))
    tcfg = platform_cfg["turbine"]
    ws, ct = ct_table(tcfg, source)
    Km = np.diag(np.asarray(platform_cfg.get("mooring_stiffness_diag", [0.0] * 6), dtype=float))
    (Tp,) = natural_periods(M, omega, A, C + Km, dofs=(4,))
    wp = 2.0 * np.pi / Tp
    fc = tcfg.get("pitch_filter", {}) or {}
    centre = float(fc["centre"]) if fc.get("centre") is not None else wp
    R = float(tcfg["rotor_radius"])
    return PlatformModel(
        mass=M,
        total_mass=mtot,
        cg=cg,
        added_mass_inf=Ainf,
        hydrostatic_stiffness=Ch,
        stiffness=C,
        ss_A=ss_a,
        ss_B=ss_b,
        ss_C=ss_c,
        ss_kernel_error=ss_errs[0],
        ss_damping_error=ss_errs[1],
        kernel_t=t,
        kernel=K,
        kernel_dt=float(kernel_dt),
        omega=omega,
        headings=platform["heading"].values,
        excitation=X,
        drift=D,
        added_mass=A,
        damping=B,
        morison_points=el["points"],
        morison_axis=el["axis"],
        morison_length=el["length"],
        morison_diameter=el["diameter"],
        morison_cd=el["cd"],
        axial_points=el["axial_points"],
        axial_axis=el["axial_axis"],
        axial_area=el["axial_area"],
        axial_cd=el["axial_cd"],
        rho=rho,
        g=g,
        water_depth=float(platform.attrs.get("water_depth", env["water_depth"])),
        rho_air=float(env.get("rho_air", 1.225)),
        hub_point=np.array([0.0, 0.0, float(tcfg["hub_height"])]),
        hub_height=float(tcfg["hub_height"]),
        rotor_radius=R,
        rotor_area=np.pi * R**2,
        ct_wind_speed=ws,
        ct=ct,
        cut_in=float(tcfg["cut_in"]),
        cut_out=float(tcfg["cut_out"]),
        shutdown_ramp=float(tcfg.get("shutdown_ramp", 1.0)),
        startup_ramp=float(tcfg.get("startup_ramp", 1.0)),
        pitch_natural_frequency=float(wp),
        pitch_filter_centre=centre,
        pitch_filter_quality=float(fc.get("quality", 1.0)),
        mooring_stiffness=Km,
    )
