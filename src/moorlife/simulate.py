"""Coupled time-domain simulation of the floating platform, one sea state or a batch.

The rigid platform obeys Cummins' equation about the SWL origin (``moorlife.conventions``)::

    (M + A_inf) a = F_exc(t) + F_drift(t) - K q - int_0^T K_r(tau) v(t - tau) dtau
                    + F_drag + F_thrust + F_moor + F_trim

with ``q = (surge, sway, heave, roll, pitch, yaw)`` (m, rad), ``K`` the hydrostatic stiffness
with gravity, the radiation memory as a convolution with the retardation kernel ``K_r`` of the
BEM damping (default; or the fitted state space ``dx/dt = A x + B v``, force ``-C x``), first-
order excitation ``F_exc`` and Newman's slow drift ``F_drift`` synthesised for the whole record
by FFT (:mod:`moorlife.environment`), Morison drag on the relative velocity of every strip, the
rotor thrust ``T = 0.5 rho_a A Ct(v) v^2`` of the relative wind ``v`` passed through a notch at
the pitch frequency and applied at the hub along the wind (nacelle aligned with the wind), and a
constant trim load (the ballast adjustment that keeps each mooring system's platform at its
design draft and even keel). ``A_inf`` is made consistent with the memory (Ogilvie), so that
the model reproduces the BEM ``A(omega)`` and ``B(omega)``.

The mooring is a separate model (quasi-static surface or dynamic lumped-mass lines,
:mod:`moorlife.mooring`), advanced once per step to the fairlead positions extrapolated to the
end of the step; the platform is driven by the mean of the start and end fairlead forces
(explicit partitioned coupling, second order). The platform's own states use classical RK4
with forcing interpolated linearly inside the step; the convolution is held over the step.
The whole batch is advanced by one Numba kernel per step.

Design notes
------------
* Loads use linearised kinematics (small rotations): strip and hub velocities are
  ``v + omega x p`` with the body-frame position ``p``; the fairleads use the exact rotation.
* Wave kinematics for drag are evaluated at the strips' mean positions (first order).
* The kept record starts after ``transient``; statistics use only the kept part.
* A batch is bit-identical to its cases run alone: every random stream comes from
  ``case_rng(seed, mooring_system, case_id)`` and the kernel treats cases independently.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field, replace
from typing import Any

import numba
import numpy as np
import scipy.fft
import scipy.linalg

from moorlife import environment as env
from moorlife import names
from moorlife.mooring.dynamic import _step_batch as _dyn_step_batch
from moorlife.mooring.quasistatic import _fairlead_forces as _qs_fairlead_forces

__all__ = [
    "ModelInputs",
    "Forcing",
    "Record",
    "EXTRA_SCALAR_VARS",
    "EXTRA_LINE_VARS",
    "EXTRA_ATTRS",
    "TIMESERIES_VARS",
    "output_attrs",
    "prepare_model",
    "build_model",
    "attach_mooring",
    "platform_from",
    "build_forcing",
    "integrate",
    "summarise",
    "simulate_batch",
    "rotation_matrix",
    "frequency_response",
    "linear_natural_periods",
    "without_radiation_memory",
    "radiation_impedance",
    "effective_added_mass_inf",
    "static_equilibrium",
]

#: Extra scalar outputs per case (beyond ``names.SIM_SCALAR_VARS``).
EXTRA_SCALAR_VARS: tuple[str, ...] = (
    "surge_mean",
    "sway_mean",
    "heave_mean",
    "pitch_mean",
    "surge_std",
    "pitch_mpm",
    "offset_max",
    "gev_corr_pitch_mpm",
)
#: Extra per-line outputs per case.
EXTRA_LINE_VARS: tuple[str, ...] = ("tension_mean", "tension_std", "tension_max")
EXTRA_ATTRS: dict[str, dict[str, str]] = {
    "surge_mean": {"units": "m", "long_name": "mean surge offset"},
    "sway_mean": {"units": "m", "long_name": "mean sway offset"},
    "heave_mean": {"units": "m", "long_name": "mean heave offset"},
    "pitch_mean": {"units": "deg", "long_name": "mean pitch angle"},
    "surge_std": {"units": "m", "long_name": "standard deviation of surge"},
    "pitch_mpm": {"units": "deg", "long_name": "most probable maximum of |pitch|"},
    "offset_max": {"units": "m", "long_name": "largest horizontal offset in the record"},
    "tension_mean": {"units": "N", "long_name": "mean fairlead tension"},
    "tension_std": {"units": "N", "long_name": "standard deviation of fairlead tension"},
    "tension_max": {"units": "N", "long_name": "largest fairlead tension in the record"},
    "gev_corr_pitch_mpm": {"units": "1", "long_name": "GEV fit correlation (pitch_mpm)"},
}
#: Time series returned when ``simulation.keep_timeseries`` is true: (B, nt) or (B, 3, nt).
TIMESERIES_VARS: tuple[str, ...] = (
    "ts_surge", "ts_sway", "ts_heave", "ts_roll", "ts_pitch", "ts_yaw", "ts_accel", "ts_tension",
)


def output_attrs(name: str) -> dict[str, str]:
    """Attributes of any output of :func:`simulate_batch` (contract or extra)."""
    if name in names.SIM_ATTRS:
        return dict(names.SIM_ATTRS[name])
    if name in EXTRA_ATTRS:
        return dict(EXTRA_ATTRS[name])
    if name.startswith("ts_"):
        units = {"ts_tension": "N", "ts_accel": "m s-2"}.get(name, "rad" if name[3:] in ("roll", "pitch", "yaw") else "m")
        return {"units": units, "long_name": f"time series of {name[3:]} after the transient"}
    raise KeyError(f"{name!r} is not an output of simulate_batch")


# --------------------------------------------------------------------------------------
# model inputs
# --------------------------------------------------------------------------------------


@dataclass(frozen=True)
class ModelInputs:
    """Everything the integrator needs for one mooring system (picklable, arrays only).

    Attributes
    ----------
    mass : (6, 6)
        Rigid-body mass plus infinite-frequency added mass about the origin, kg / kg m / kg m2.
    stiffness : (6, 6)
        Hydrostatic restoring including gravity, N/m, N, N m/rad.
    damping : (6, 6)
        Extra linear damping (zero unless configured), N s/m ...
    rad_a, rad_b, rad_c : (nr, nr), (nr, 6), (6, nr)
        Radiation state space: ``dx/dt = rad_a x + rad_b v``, force ``-rad_c x``.
    omega : (nw,)
        BEM frequencies, rad/s.
    headings : (nh,)
        BEM propagation angles, rad, increasing.
    excitation : (nw, nh, 6) complex
        First-order excitation per metre of amplitude, ``exp(-i omega t)`` convention.
    drift : (nw, nh, 6)
        Mean drift force per squared metre of amplitude (Newman), N/m2.
    strip_pos, strip_axis : (ns, 3)
        Morison strip centres (m, body frame = global at rest) and unit axes.
    strip_cdn, strip_cda : (ns,)
        Normal drag factor ``0.5 rho Cd D L`` (kg/m) and axial (heave-plate) factor
        ``0.5 rho Cd_ax pi D^2 / 4`` (kg/m).
    hub : (3,)
        Hub position in the body frame, m.
    thrust_speed, thrust_force : (nv,)
        Tabulated thrust (N) against relative wind speed (m/s), ramps included.
    filt_a, filt_b, filt_c, filt_d : arrays
        Continuous state space of the pitch-band filter on v_rel (SISO).
    fairleads : (3, 3)
        Fairlead positions in the body frame (line, xyz), m.
    depth, rho, gravity : float
        Water depth (m), sea-water density, gravity.
    mooring_kind : str
        ``"quasistatic"``, ``"dynamic"`` (models of :mod:`moorlife.mooring`) or ``"linear"``
        (``mooring_stiffness`` about the origin; verification only, no line tensions).
    mooring_stiffness : (6, 6)
        Linear mooring stiffness used by ``"linear"`` and by :func:`linear_natural_periods`.
    mooring_args : tuple
        ``(props, layout, cfg, prototype)``: what ``moorlife.mooring.make_mooring`` needs, and
        a prototype model whose precomputed tables are reused for every batch.
    static_load : (6,)
        Constant load trimming the platform to its design draft and even keel with the
        mooring at rest (the ballast adjustment of each mooring system): minus the heave,
        roll and pitch components of the mooring load at rest, N and N m.
    kernel : (nlag, npairs)
        Radiation retardation kernel ``K_ij(k kernel_dt)`` of the coupled DOF pairs
        ``kernel_pairs (npairs, 2)``: when non-empty, the radiation force is the convolution
        ``-int K(tau) v(t - tau) dtau`` (trapezoid, velocity history at the integration step)
        instead of the state space (which must then be empty).
    kernel_dt : float
        Sampling of ``kernel``, s.
    line_info : dict
        ``link_diameter`` (m), ``mbs`` (N), ``chain`` of the lines (for fatigue).
    """

    mass: np.ndarray
    stiffness: np.ndarray
    damping: np.ndarray
    rad_a: np.ndarray
    rad_b: np.ndarray
    rad_c: np.ndarray
    omega: np.ndarray
    headings: np.ndarray
    excitation: np.ndarray
    drift: np.ndarray
    strip_pos: np.ndarray
    strip_axis: np.ndarray
    strip_cdn: np.ndarray
    strip_cda: np.ndarray
    hub: np.ndarray
    thrust_speed: np.ndarray
    thrust_force: np.ndarray
    filt_a: np.ndarray
    filt_b: np.ndarray
    filt_c: np.ndarray
    filt_d: np.ndarray
    fairleads: np.ndarray
    depth: float
    rho: float
    gravity: float
    mooring_kind: str = "linear"
    mooring_stiffness: np.ndarray = field(default_factory=lambda: np.zeros((6, 6)))
    mooring_args: tuple = ()
    static_load: np.ndarray = field(default_factory=lambda: np.zeros(6))
    kernel: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)))
    kernel_pairs: np.ndarray = field(default_factory=lambda: np.zeros((0, 2), dtype=np.int64))
    kernel_dt: float = 0.0
    line_info: Mapping[str, Any] = field(default_factory=dict)


def build_model(**kwargs: Any) -> ModelInputs:
    """Build :class:`ModelInputs` from arrays, with checks and defaults for optional parts.

    Missing optional parts: no radiation memory, no drift, no strips, no thrust, an identity
    filter (pass-through), zero damping, no fairleads.
    """
    kw = dict(kwargs)
    kw.setdefault("damping", np.zeros((6, 6)))
    kw.setdefault("rad_a", np.zeros((0, 0)))
    kw.setdefault("rad_b", np.zeros((0, 6)))
    kw.setdefault("rad_c", np.zeros((6, 0)))
    if "excitation" in kw:
        kw.setdefault("drift", np.zeros(np.shape(kw["excitation"])))
    kw.setdefault("strip_pos", np.zeros((0, 3)))
    kw.setdefault("strip_axis", np.zeros((0, 3)))
    kw.setdefault("strip_cdn", np.zeros(0))
    kw.setdefault("strip_cda", np.zeros(0))
    kw.setdefault("hub", np.array([0.0, 0.0, 90.0]))
    kw.setdefault("thrust_speed", np.array([-1.0, 1.0]))
    kw.setdefault("thrust_force", np.zeros(2))
    kw.setdefault("filt_a", np.zeros((0, 0)))
    kw.setdefault("filt_b", np.zeros((0, 1)))
    kw.setdefault("filt_c", np.zeros((1, 0)))
    kw.setdefault("filt_d", np.ones((1, 1)))
    kw.setdefault("fairleads", np.zeros((3, 3)))
    kw.setdefault("depth", 200.0)
    kw.setdefault("rho", 1025.0)
    kw.setdefault("gravity", env.G)
    scalars = ("mooring_kind", "mooring_args", "line_info", "depth", "rho", "gravity", "kernel_dt", "kernel_pairs")
    arrays = {k: (np.asarray(v, dtype=complex if k == "excitation" else float) if k not in scalars else v)
              for k, v in kw.items()}
    if "kernel_pairs" in arrays:
        arrays["kernel_pairs"] = np.asarray(arrays["kernel_pairs"], dtype=np.int64).reshape(-1, 2)
    m = ModelInputs(**arrays)
    for key, shape in (("mass", (6, 6)), ("stiffness", (6, 6)), ("damping", (6, 6))):
        if getattr(m, key).shape != shape:
            raise ValueError(f"ModelInputs.{key}: expected shape {shape}, got {getattr(m, key).shape}")
    nr = m.rad_a.shape[0]
    if m.rad_b.shape != (nr, 6) or m.rad_c.shape != (6, nr):
        raise ValueError(f"radiation state space: inconsistent shapes {m.rad_a.shape}, {m.rad_b.shape}, {m.rad_c.shape}")
    nw, nh = m.omega.size, m.headings.size
    if m.excitation.shape != (nw, nh, 6) or m.drift.shape != (nw, nh, 6):
        raise ValueError(f"excitation/drift: expected ({nw}, {nh}, 6), got {m.excitation.shape}, {m.drift.shape}")
    if m.kernel.size and (m.kernel.shape[1] != m.kernel_pairs.shape[0] or not m.kernel_dt > 0 or nr):
        raise ValueError("radiation: a kernel needs kernel_pairs, kernel_dt > 0 and no state space")
    if np.any(np.diff(m.headings) <= 0):
        raise ValueError("headings must increase strictly")
    if m.mooring_kind not in ("linear", "quasistatic", "dynamic"):
        raise ValueError(f"simulation.mooring_model = {m.mooring_kind!r}: expected 'quasistatic' or 'dynamic'")
    return m


# --------------------------------------------------------------------------------------
# forcing
# --------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Forcing:
    """External forcing of a batch, sampled on the integration grid.

    Attributes
    ----------
    grid : environment.RecordGrid
    force : (B, n + 1, 6)
        First-order plus slow-drift wave force at ``t_j = j dt``, N and N m.
    wind : (B, n + 1)
        Hub-height wind speed, m/s (zero: no wind).
    wind_dir : (B, 2)
        Unit vector of the wind's direction of travel (x, y).
    kin_every : int
        Kinematics are sampled every ``kin_every`` steps.
    kinematics : (B, nk, 3, ns) float32
        Undisturbed wave particle velocity at the strips' mean positions, m/s.
    """

    grid: env.RecordGrid
    force: np.ndarray
    wind: np.ndarray
    wind_dir: np.ndarray
    kin_every: int
    kinematics: np.ndarray


def _interp_heading(table: np.ndarray, headings: np.ndarray, theta: float) -> np.ndarray:
    """Linear interpolation of ``table (nw, nh, 6)`` at propagation angle ``theta`` on the circle."""
    from moorlife.hydro import interp_heading

    if headings.size == 1:
        return table[:, 0, :]
    return interp_heading(headings, table, float(theta))


def _interp_omega(values: np.ndarray, omega: np.ndarray, target: np.ndarray) -> np.ndarray:
    """Interpolate ``values (nw, 6)`` (complex or real) to ``target`` rad/s; zero outside."""
    out = np.zeros((target.size, values.shape[1]), dtype=values.dtype)
    for d in range(values.shape[1]):
        if np.iscomplexobj(values):
            out[:, d] = np.interp(target, omega, values[:, d].real, left=0, right=0) + 1j * np.interp(
                target, omega, values[:, d].imag, left=0, right=0)
        else:
            out[:, d] = np.interp(target, omega, values[:, d], left=0, right=0)
    return out


_KIN_CHUNK = 24  # kinematic series synthesised per FFT call


def _drag_kinematics_tf(model: ModelInputs, k: np.ndarray, omega: np.ndarray, theta: float) -> np.ndarray:
    """Velocity transfer functions at the strips, ``(nk, ns, 3)`` complex, per metre of amplitude."""
    p = model.strip_pos
    h = model.depth
    c, s = math.cos(theta), math.sin(theta)
    phase = np.exp(1j * k[:, None] * (p[None, :, 0] * c + p[None, :, 1] * s))
    z = np.minimum(p[None, :, 2], 0.0)
    kh = np.minimum(k[:, None] * h, 350.0)
    kz = np.minimum(k[:, None] * (z + h), 350.0)
    horiz = omega[:, None] * np.cosh(kz) / np.sinh(kh) * phase
    vert = -1j * omega[:, None] * np.sinh(kz) / np.sinh(kh) * phase
    wet = (p[None, :, 2] <= 0.0)
    horiz = horiz * wet
    vert = vert * wet
    return np.stack([horiz * c, horiz * s, vert], axis=-1)


def build_forcing(
    model: ModelInputs,
    grid: env.RecordGrid,
    waves: env.WaveComponents,
    wind: np.ndarray,
    wind_dir_deg: np.ndarray,
    *,
    kin_every: int,
    second_order: bool = True,
) -> Forcing:
    """Wave forces, wave kinematics and wind of a batch on the integration grid.

    Parameters
    ----------
    model : ModelInputs
    grid : environment.RecordGrid
    waves : environment.WaveComponents
        Complex amplitudes ``(B, nk)`` and propagation angles ``(B,)``.
    wind : (B, n + 1)
        Hub wind speed series, m/s.
    wind_dir_deg : (B,)
        Nautical direction the wind comes from, deg.
    kin_every : int
        Sampling of the drag kinematics, in steps.
    second_order : bool
        Add Newman's slow drift (difference-frequency part ``|a|^2`` of the drift envelope).

    Returns
    -------
    Forcing
    """
    from moorlife.conventions import flow_vector

    nb = waves.amplitude.shape[0]
    n1 = grid.n_steps + 1
    force = np.empty((nb, n1, 6))
    k = env.wave_number(waves.omega, model.depth)
    nkin = (grid.n_steps // kin_every) + 2
    ns = model.strip_pos.shape[0]
    kin = np.zeros((nb, nkin, 3, ns), dtype=np.float32)
    for b in range(nb):
        theta = float(waves.theta[b])
        x = _interp_omega(_interp_heading(model.excitation, model.headings, theta), model.omega, waves.omega)
        coeff = waves.amplitude[b][None, :] * x.T  # (6, nk)
        force[b] = env.synthesise(coeff, waves.index, grid).T
        if second_order:
            d = _interp_omega(_interp_heading(model.drift, model.headings, theta), model.omega, waves.omega)
            for dof in range(6):
                for sign in (1.0, -1.0):
                    part = np.maximum(sign * d[:, dof], 0.0)
                    if not part.any():
                        continue
                    a = env.synthesise_complex((np.sqrt(part) * waves.amplitude[b])[None, :], waves.index, grid)[0]
                    force[b, :, dof] += sign * (a.real**2 + a.imag**2)
        if ns:
            tf = _drag_kinematics_tf(model, k, waves.omega, theta)  # (nk, ns, 3)
            coeff = (waves.amplitude[b][:, None, None] * tf).transpose(0, 2, 1).reshape(waves.omega.size, 3 * ns).T
            flat = kin[b].reshape(nkin, ns * 3)
            # synthesise directly on the coarse kinematics grid (same frequency bins)
            coarse = grid.n_fft % kin_every == 0 and 2 * waves.index.max() < grid.n_fft // kin_every
            n_c = grid.n_fft // kin_every if coarse else grid.n_fft
            idx = (np.arange(nkin) * (1 if coarse else kin_every)) % n_c  # periodic synthesis
            for c0 in range(0, ns * 3, _KIN_CHUNK):  # bounded temporaries
                c1 = min(c0 + _KIN_CHUNK, ns * 3)
                spec = np.zeros((c1 - c0, n_c // 2 + 1), dtype=complex)
                spec[:, waves.index] = np.conj(coeff[c0:c1]) * (n_c / 2.0)
                series = scipy.fft.irfft(spec, n=n_c, axis=-1)
                flat[:, c0:c1] = series[:, idx].T
    wdir = flow_vector(np.asarray(wind_dir_deg, dtype=float)).reshape(nb, 2)
    return Forcing(grid=grid, force=force, wind=np.asarray(wind, dtype=float), wind_dir=wdir,
                   kin_every=int(kin_every), kinematics=kin)


# --------------------------------------------------------------------------------------
# the Numba kernel
# --------------------------------------------------------------------------------------


def rotation_matrix(rot: np.ndarray) -> np.ndarray:
    """Rotation matrix ``Rz(yaw) Ry(pitch) Rx(roll)`` of ``rot (..., 3)`` rad -> ``(..., 3, 3)``."""
    r = np.asarray(rot, dtype=float)
    out = np.empty(r.shape[:-1] + (3, 3))
    _rotation(r.reshape(-1, 3), out.reshape(-1, 3, 3))
    return out


@numba.njit(cache=True, inline="always")
def _rotation_entries(roll, pitch, yaw):  # pragma: no cover - numba
    """The nine entries of ``Rz(yaw) Ry(pitch) Rx(roll)``, row by row."""
    cr, sr = math.cos(roll), math.sin(roll)
    cp, sp = math.cos(pitch), math.sin(pitch)
    cy, sy = math.cos(yaw), math.sin(yaw)
    return (cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr,
            sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr,
            -sp, cp * sr, cp * cr)


@numba.njit(cache=True)
def _rotation(rot, out):  # pragma: no cover - numba
    for i in range(rot.shape[0]):
        e = _rotation_entries(rot[i, 0], rot[i, 1], rot[i, 2])
        out[i, 0, 0], out[i, 0, 1], out[i, 0, 2] = e[0], e[1], e[2]
        out[i, 1, 0], out[i, 1, 1], out[i, 1, 2] = e[3], e[4], e[5]
        out[i, 2, 0], out[i, 2, 1], out[i, 2, 2] = e[6], e[7], e[8]


@numba.njit(cache=True, inline="always")
def _rotated(q, b, f):  # pragma: no cover - numba
    """``R(q[b, 3:6]) f`` for a 3-vector ``f`` (the matrix of :func:`_rotation`)."""
    e = _rotation_entries(q[b, 3], q[b, 4], q[b, 5])
    px = e[0] * f[0] + e[1] * f[1] + e[2] * f[2]
    py = e[3] * f[0] + e[4] * f[1] + e[5] * f[2]
    pz = e[6] * f[0] + e[7] * f[1] + e[8] * f[2]
    return px, py, pz


@numba.njit(cache=True)
def _fairlead_motion(q, v, fair, r_out, v_out):  # pragma: no cover - numba
    """Fairlead positions and velocities ``(B, 3, 3)`` from the platform state."""
    for b in range(q.shape[0]):
        for i in range(fair.shape[0]):
            px, py, pz = _rotated(q, b, fair[i])
            r_out[b, i, 0] = q[b, 0] + px
            r_out[b, i, 1] = q[b, 1] + py
            r_out[b, i, 2] = q[b, 2] + pz
            wx, wy, wz = v[b, 3], v[b, 4], v[b, 5]
            v_out[b, i, 0] = v[b, 0] + wy * pz - wz * py
            v_out[b, i, 1] = v[b, 1] + wz * px - wx * pz
            v_out[b, i, 2] = v[b, 2] + wx * py - wy * px


@numba.njit(cache=True)
def _moor_generalised(q, fmoor, fair, out):  # pragma: no cover - numba
    """6-DOF mooring load about the (displaced) origin from fairlead forces ``(B, 3, 3)``."""
    for b in range(q.shape[0]):
        for d in range(6):
            out[b, d] = 0.0
        for i in range(fair.shape[0]):
            px, py, pz = _rotated(q, b, fair[i])
            fx, fy, fz = fmoor[b, i, 0], fmoor[b, i, 1], fmoor[b, i, 2]
            out[b, 0] += fx
            out[b, 1] += fy
            out[b, 2] += fz
            out[b, 3] += py * fz - pz * fy
            out[b, 4] += pz * fx - px * fz
            out[b, 5] += px * fy - py * fx


@numba.njit(cache=True)
def _rhs(b, t_frac, j, q, v, xr, zf, fmoor6, force, wind, wdir, kin, kin_every,
         minv, K, D, ra_ptr, ra_idx, ra_val, rb, rc,
         spos, saxis, scdn, scda, hub, tv, tf, fa, fb, fc, fd,
         dq, dv, dxr, dzf, F):  # pragma: no cover - numba
    """Time derivative of one case's state at ``t = (j + t_frac) dt`` (``F (6,)`` scratch)."""
    # external wave force, linear in time between samples j and j+1
    for d in range(6):
        F[d] = (1.0 - t_frac) * force[b, j, d] + t_frac * force[b, j + 1, d] + fmoor6[b, d]
    # hydrostatics + gravity, linear damping
    for d in range(6):
        acc = 0.0
        for e in range(6):
            acc += K[d, e] * q[e] + D[d, e] * v[e]
        F[d] -= acc
    # radiation memory
    nr = xr.shape[0]
    for d in range(6):
        acc = 0.0
        for r in range(nr):
            acc += rc[d, r] * xr[r]
        F[d] -= acc
    for r in range(nr):
        acc = 0.0
        for p in range(ra_ptr[r], ra_ptr[r + 1]):
            acc += ra_val[p] * xr[ra_idx[p]]
        for e in range(6):
            acc += rb[r, e] * v[e]
        dxr[r] = acc
    # Morison drag on the relative velocity; strips along the last axis (unit stride, SIMD)
    ns = spos.shape[1]
    if ns > 0:
        tk = (j + t_frac) / kin_every
        jk = int(tk)
        wk = tk - jk
        k0 = kin[b, jk]
        k1 = kin[b, jk + 1]
        vx, vy, vz = v[0], v[1], v[2]
        wx, wy, wz = v[3], v[4], v[5]
        f0 = f1 = f2 = m3 = m4 = m5 = 0.0
        for s in range(ns):
            px, py, pz = spos[0, s], spos[1, s], spos[2, s]
            ux = (1 - wk) * k0[0, s] + wk * k1[0, s] - (vx + wy * pz - wz * py)
            uy = (1 - wk) * k0[1, s] + wk * k1[1, s] - (vy + wz * px - wx * pz)
            uz = (1 - wk) * k0[2, s] + wk * k1[2, s] - (vz + wx * py - wy * px)
            ax, ay, az = saxis[0, s], saxis[1, s], saxis[2, s]
            ua = ux * ax + uy * ay + uz * az
            nx, ny, nz = ux - ua * ax, uy - ua * ay, uz - ua * az
            un = math.sqrt(nx * nx + ny * ny + nz * nz)
            ca = scda[s] * abs(ua) * ua
            fx = scdn[s] * un * nx + ca * ax
            fy = scdn[s] * un * ny + ca * ay
            fz = scdn[s] * un * nz + ca * az
            f0 += fx
            f1 += fy
            f2 += fz
            m3 += py * fz - pz * fy
            m4 += pz * fx - px * fz
            m5 += px * fy - py * fx
        F[0] += f0
        F[1] += f1
        F[2] += f2
        F[3] += m3
        F[4] += m4
        F[5] += m5
    # thrust at the hub, along the wind, from the filtered relative wind
    uw = (1.0 - t_frac) * wind[b, j] + t_frac * wind[b, j + 1]
    ex, ey = wdir[b, 0], wdir[b, 1]
    hx, hy, hz = hub[0], hub[1], hub[2]
    vhx = v[0] + v[4] * hz - v[5] * hy
    vhy = v[1] + v[5] * hx - v[3] * hz
    vrel = uw - (vhx * ex + vhy * ey)
    nf = zf.shape[0]
    vf = fd[0, 0] * vrel
    for r in range(nf):
        vf += fc[0, r] * zf[r]
    for r in range(nf):
        acc = fb[r, 0] * vrel
        for e in range(nf):
            acc += fa[r, e] * zf[e]
        dzf[r] = acc
    thrust = np.interp(vf, tv, tf)
    tx, ty = thrust * ex, thrust * ey
    F[0] += tx
    F[1] += ty
    F[3] += -hz * ty
    F[4] += hz * tx
    F[5] += hx * ty - hy * tx
    # accelerations
    for d in range(6):
        dq[d] = v[d]
        acc = 0.0
        for e in range(6):
            acc += minv[d, e] * F[e]
        dv[d] = acc


@numba.njit(cache=True)
def _rk4_step(j, dt, q, v, xr, zf, fmoor6, force, wind, wdir, kin, kin_every,
              minv, K, D, ra_ptr, ra_idx, ra_val, rb, rc,
              spos, saxis, scdn, scda, hub, tv, tf, fa, fb, fc, fd, acc_out):  # pragma: no cover
    """Advance every case of the batch from step ``j`` to ``j + 1`` (classical RK4, in place).

    ``acc_out (B, 6)`` receives the accelerations at the start of the step.
    """
    nb = q.shape[0]
    nr = xr.shape[1]
    nf = zf.shape[1]
    ny = 12 + nr + nf
    k = np.empty((4, ny))
    y0 = np.empty(ny)
    ys = np.empty(ny)
    F = np.empty(6)
    for b in range(nb):
        for d in range(6):
            y0[d] = q[b, d]
            y0[6 + d] = v[b, d]
        for r in range(nr):
            y0[12 + r] = xr[b, r]
        for r in range(nf):
            y0[12 + nr + r] = zf[b, r]
        for stage in range(4):
            if stage == 0:
                c, frac = 0.0, 0.0
            elif stage == 3:
                c, frac = 1.0, 1.0
            else:
                c, frac = 0.5, 0.5
            for i in range(ny):
                ys[i] = y0[i] + (c * dt * k[stage - 1, i] if stage > 0 else 0.0)
            _rhs(b, frac, j, ys[0:6], ys[6:12], ys[12:12 + nr], ys[12 + nr:ny], fmoor6, force, wind, wdir,
                 kin, kin_every, minv, K, D, ra_ptr, ra_idx, ra_val, rb, rc, spos, saxis, scdn, scda, hub,
                 tv, tf, fa, fb, fc, fd,
                 k[stage, 0:6], k[stage, 6:12], k[stage, 12:12 + nr], k[stage, 12 + nr:ny], F)
        for d in range(6):
            acc_out[b, d] = k[0, 6 + d]
        for i in range(ny):
            y0[i] += dt / 6.0 * (k[0, i] + 2.0 * k[1, i] + 2.0 * k[2, i] + k[3, i])
        for d in range(6):
            q[b, d] = y0[d]
            v[b, d] = y0[6 + d]
        for r in range(nr):
            xr[b, r] = y0[12 + r]
        for r in range(nf):
            zf[b, r] = y0[12 + nr + r]


@numba.njit(cache=True)
def _advance(j, i, dt, q, v, xr, zf, f_prev, f_new, coupled, static, fair, ten, motion, accel, tension, fmoor6, acc,
             hist, stride, ker, kpi, kpj,
             force, wind, wdir, kin, kin_every, minv, K, D, ra_ptr, ra_idx, ra_val, rb, rc,
             spos, saxis, scdn, scda, hub, tv, tf, fa, fb, fc, fd):  # pragma: no cover - numba
    """One coupled step ``j -> j + 1`` of the batch, with recording (kept sample ``i``).

    The load held constant over the step (``fmoor6``) is the mooring force, the trim load and,
    with a kernel, the radiation convolution. The platform is driven by the mean of the
    mooring forces at the start (``f_prev``) and at the predicted end (``f_new``); ``f_prev``
    then takes ``f_new``. ``ten`` is the line tension at ``t_{j+1}`` (kept as sample ``i + 1``).
    ``hist (B, stride, 6, 2 nlag)`` is the velocity history of the convolution (:func:`_convolve`).
    """
    nb = q.shape[0]
    nt = motion.shape[2]
    for b in range(nb):
        for d in range(6):
            fmoor6[b, d] = 0.0
    if coupled:
        for b in range(nb):
            for l in range(f_prev.shape[1]):
                for c in range(3):
                    f_prev[b, l, c] = 0.5 * (f_prev[b, l, c] + f_new[b, l, c])
        _moor_generalised(q, f_prev, fair, fmoor6)
        for b in range(nb):
            for l in range(f_prev.shape[1]):
                for c in range(3):
                    f_prev[b, l, c] = f_new[b, l, c]
        if 0 <= i + 1 < nt:
            for b in range(nb):
                for l in range(ten.shape[1]):
                    tension[b, l, i + 1] = ten[b, l]
    for b in range(nb):
        for d in range(6):
            fmoor6[b, d] += static[d]
    if ker.shape[1] > 0:
        _convolve(j, stride, v, hist, ker, kpi, kpj, fmoor6)
    if i >= 0:
        for b in range(nb):
            for d in range(6):
                motion[b, d, i] = q[b, d]
    _rk4_step(j, dt, q, v, xr, zf, fmoor6, force, wind, wdir, kin, kin_every, minv, K, D, ra_ptr, ra_idx,
              ra_val, rb, rc, spos, saxis, scdn, scda, hub, tv, tf, fa, fb, fc, fd, acc)
    if i >= 0:
        hx, hy, hz = hub[0], hub[1], hub[2]
        for b in range(nb):
            accel[b, 0, i] = acc[b, 0] + acc[b, 4] * hz - acc[b, 5] * hy
            accel[b, 1, i] = acc[b, 1] + acc[b, 5] * hx - acc[b, 3] * hz
            accel[b, 2, i] = acc[b, 2] + acc[b, 3] * hy - acc[b, 4] * hx


@numba.njit(cache=True)
def _convolve(j, stride, v, hist, ker, kpi, kpj, out):  # pragma: no cover - numba
    """Subtract the radiation convolution ``sum_k K[k] v(t_j - k stride dt)`` from ``out (B, 6)``.

    ``ker (npairs, nlag)`` holds the kernel with the trapezoid weights and its step ``stride dt``
    folded in, oldest lag first (``ker[p, nlag - 1 - k] = w_k K_p(k stride dt)``).
    ``hist (B, stride, 6, 2 nlag)`` is the velocity history of every step, split by the
    step's residue modulo ``stride`` and stored twice (slot and slot + nlag) so that the
    ``nlag`` samples of a convolution are one contiguous window: each pair is a unit-stride
    dot product, which the compiler vectorises. ``v`` is stored first.
    """
    npair, nlag = ker.shape
    c = j % stride
    slot = (j // stride) % nlag
    for b in range(v.shape[0]):
        for d in range(6):
            hist[b, c, d, slot] = v[b, d]
            hist[b, c, d, slot + nlag] = v[b, d]
    for p in range(npair):  # one kernel row at a time, for every case (it stays in cache)
        k = ker[p]
        for b in range(v.shape[0]):
            h = hist[b, c, kpj[p]]
            acc = 0.0
            for i in range(nlag):
                acc += k[i] * h[slot + 1 + i]
            out[b, kpi[p]] -= acc


@numba.njit(cache=True)
def _predict_fairleads(q, v, fair, dt, r_out, v_out):  # pragma: no cover - numba
    """Fairlead positions extrapolated to ``t + dt`` and velocities, ``(B, 3, 3)``."""
    _fairlead_motion(q, v, fair, r_out, v_out)
    for b in range(q.shape[0]):
        for l in range(fair.shape[0]):
            for c in range(3):
                r_out[b, l, c] += dt * v_out[b, l, c]


@numba.njit(cache=True)
def _run_dynamic(n, j0, dt, fair, r_f, v_f, mr, mv, mrp, mvp, mhist, nsub, scheme, mparams, mwork, forces, ten,
                 q, v, xr, zf, f_prev, static, motion, accel, tension, fmoor6, acc, hist, stride, ker, kpi, kpj,
                 *platform):  # pragma: no cover - numba
    """The whole record with dynamic lines, in one compiled loop (no per-step dispatch).

    Each step is exactly the Python loop of :func:`integrate`: predict the fairleads, advance
    the lines (``moorlife.mooring.dynamic._step_batch``, whose ``forces`` and ``ten`` are the
    state's arrays), then :func:`_advance` the platform.
    """
    for j in range(n):
        _predict_fairleads(q, v, fair, dt, r_f, v_f)
        _dyn_step_batch(mr, mv, mrp, mvp, mhist, r_f, v_f, dt, nsub, scheme, mparams, mwork, forces, ten)
        _advance(j, j - j0, dt, q, v, xr, zf, f_prev, forces, True, static, fair, ten, motion, accel, tension,
                 fmoor6, acc, hist, stride, ker, kpi, kpj, *platform)


@numba.njit(cache=True)
def _run_quasistatic(n, j0, dt, fair, r_f, v_f, anchors, table, forces, ten,
                     q, v, xr, zf, f_prev, static, motion, accel, tension, fmoor6, acc, hist, stride, ker, kpi, kpj,
                     *platform):  # pragma: no cover - numba
    """The whole record with quasi-static lines, in one compiled loop (see :func:`_run_dynamic`)."""
    for j in range(n):
        _predict_fairleads(q, v, fair, dt, r_f, v_f)
        _qs_fairlead_forces(r_f, anchors, *table, forces, ten)
        _advance(j, j - j0, dt, q, v, xr, zf, f_prev, forces, True, static, fair, ten, motion, accel, tension,
                 fmoor6, acc, hist, stride, ker, kpi, kpj, *platform)


def _run_compiled(moor: Any, mstate: Any, n: int, j0: int, dt: float, fair: np.ndarray, r_f: np.ndarray,
                  v_f: np.ndarray, loop: tuple, platform: tuple) -> bool:
    """Run the record in one compiled loop if ``moor`` is a known line model; ``False`` otherwise."""
    from moorlife import mooring as moor_pkg

    if type(moor) is moor_pkg.DynamicMooring:
        nsub = moor.substeps(dt)
        try:
            _run_dynamic(n, j0, float(dt), fair, r_f, v_f, mstate.r, mstate.v, mstate.r_prev, mstate.v_prev,
                         mstate.step_prev, nsub, moor._scheme, moor.model.params, moor._w, mstate.forces,
                         mstate.tension, *loop, *platform)
        except FloatingPointError:
            raise FloatingPointError(
                f"dynamic mooring ({moor.props.name}): non-finite fairlead tension; line state diverged "
                f"(dt = {dt} s)"
            ) from None
        return True
    if type(moor) is moor_pkg.QuasiStaticMooring:
        forces, ten = mstate
        _run_quasistatic(n, j0, float(dt), fair, r_f, v_f, moor.anchors, moor.table.args(), forces, ten,
                         *loop, *platform)
        return True
    return False


def _csr(a: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Compressed sparse rows of a dense matrix (exact zeros dropped)."""
    nr = a.shape[0]
    ptr = np.zeros(nr + 1, dtype=np.int64)
    idx, val = [], []
    for r in range(nr):
        nz = np.flatnonzero(a[r])
        idx.extend(nz.tolist())
        val.extend(a[r, nz].tolist())
        ptr[r + 1] = len(idx)
    return ptr, np.asarray(idx, dtype=np.int64), np.asarray(val, dtype=float)


# --------------------------------------------------------------------------------------
# mooring adapters
# --------------------------------------------------------------------------------------


class _LinearMooring:
    """Linear 6-DOF spring about the origin (verification only); same interface as moorlife.mooring."""

    def __init__(self, stiffness: np.ndarray, batch: int):
        self.k = np.asarray(stiffness, dtype=float)
        self.batch = batch

    def init(self, r_fair: np.ndarray) -> dict:
        return {"q": np.zeros((self.batch, 6))}

    def tension(self, state: dict) -> np.ndarray:
        return np.full((self.batch, 3), np.nan)


def _make_mooring(model: ModelInputs, batch: int):
    """A mooring model for ``batch`` cases, reusing the prototype built by :func:`prepare_model`."""
    if model.mooring_kind == "linear":
        return _LinearMooring(model.mooring_stiffness, batch)
    from moorlife import mooring as moor

    props, layout, cfg, proto = model.mooring_args
    if isinstance(proto, moor.QuasiStaticMooring):
        return moor.QuasiStaticMooring(proto.table, layout, batch)
    if isinstance(proto, moor.DynamicMooring):
        return moor.DynamicMooring(proto.model, props, layout, proto.settings, batch)
    return moor.make_mooring(model.mooring_kind, props, layout, cfg, batch=batch)


# --------------------------------------------------------------------------------------
# integration
# --------------------------------------------------------------------------------------


def _kernel_at(model: ModelInputs, dt: float) -> tuple[np.ndarray, int, np.ndarray, np.ndarray]:
    """The retardation kernel with trapezoid weights, its stride in steps, and its DOF pairs.

    The kernel is returned as ``(npairs, nlag)``, oldest lag first (the layout of
    :func:`_convolve`). It keeps its own sampling when it is a whole number ``stride`` of steps (the
    history is then summed every ``stride`` steps: the kernel and the velocity are smooth on
    that scale), else it is resampled at ``dt``.
    """
    if model.kernel.size == 0:
        return np.zeros((0, 0)), 1, np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64)
    ratio = model.kernel_dt / dt
    stride = int(round(ratio)) if abs(ratio - round(ratio)) < 1e-9 and round(ratio) >= 1 else 1
    h = stride * dt
    t_src = np.arange(model.kernel.shape[0]) * model.kernel_dt
    t = np.arange(0.0, t_src[-1] + 1e-9, h)
    ker = np.stack([np.interp(t, t_src, model.kernel[:, p]) for p in range(model.kernel.shape[1])], axis=1)
    w = np.full(t.size, h)  # trapezoid weights folded in
    w[[0, -1]] *= 0.5
    return (np.ascontiguousarray((ker * w[:, None])[::-1].T), stride, model.kernel_pairs[:, 0].copy(),
            model.kernel_pairs[:, 1].copy())


@dataclass(frozen=True)
class Record:
    """Kept part of a simulated record (after the transient).

    Attributes
    ----------
    dt : float
        Sample step, s.
    motion : (B, 6, nt)
        Platform displacement about the origin, m and rad.
    accel : (B, 3, nt)
        Nacelle (hub) acceleration, m/s2 (linearised rigid-body kinematics).
    tension : (B, 3, nt)
        Fairlead tension of M1, M2, M3, N (NaN for the linear verification mooring).
    """

    dt: float
    motion: np.ndarray
    accel: np.ndarray
    tension: np.ndarray


def integrate(
    model: ModelInputs,
    forcing: Forcing,
    *,
    transient: float,
    q0: np.ndarray | None = None,
    v0: np.ndarray | None = None,
    mooring_override: Any | None = None,
    locked: Sequence[int] = (),
) -> Record:
    """Integrate the coupled system over the forcing grid.

    Parameters
    ----------
    model : ModelInputs
    forcing : Forcing
    transient : float
        Seconds discarded at the start.
    q0, v0 : (B, 6), optional
        Initial displacement and velocity (default: at rest at the origin).
    mooring_override : object, optional
        A mooring object with ``init/step/tension`` (tests).
    locked : sequence of int, optional
        Platform DOFs (0-5, surge..yaw) held at their initial displacement, like the DOF
        switches of a decay-test set-up: their rows and columns of the inverse mass matrix are
        zero and the free DOFs use the inverse of their own block. Default: all six free.

    Returns
    -------
    Record
    """
    grid = forcing.grid
    dt = grid.dt
    nb = forcing.force.shape[0]
    n = grid.n_steps
    j0 = int(round(transient / dt))
    if j0 >= n:
        raise ValueError(f"transient {transient} s leaves nothing of a {n * dt} s record")
    nt = n - j0
    q = np.zeros((nb, 6)) if q0 is None else np.array(q0, dtype=float).reshape(nb, 6)
    v = np.zeros((nb, 6)) if v0 is None else np.array(v0, dtype=float).reshape(nb, 6)
    nr = model.rad_a.shape[0]
    xr = np.zeros((nb, nr))
    nf = model.filt_a.shape[0]
    zf = np.zeros((nb, nf))
    if nf:  # start the filter at its steady state for the initial wind (no start-up kick)
        zf[:] = -np.linalg.solve(model.filt_a, model.filt_b[:, 0])[None, :] * forcing.wind[:, :1]
    ra = _csr(model.rad_a)
    free = _free_dofs(locked)
    held = np.setdiff1d(np.arange(6), free)
    minv = _inverse_mass(model.mass, free)
    if np.any(v[:, held] != 0.0):
        raise ValueError(f"integrate: v0 must be 0 in the locked DOFs {held.tolist()}")
    kin = forcing.kinematics
    if kin.shape[2:] != (3, model.strip_pos.shape[0]):
        raise ValueError("forcing kinematics do not match the model strips")
    moor = mooring_override if mooring_override is not None else _make_mooring(model, nb)
    linear = isinstance(moor, _LinearMooring)
    fair = np.ascontiguousarray(model.fairleads)
    r_f = np.empty((nb, 3, 3))
    v_f = np.empty((nb, 3, 3))
    _fairlead_motion(q, v, fair, r_f, v_f)
    mstate = moor.init(r_f.copy())
    f_prev = np.zeros((nb, 3, 3)) if linear else np.array(moor.forces(mstate), dtype=float)
    fmoor6 = np.zeros((nb, 6))
    acc = np.zeros((nb, 6))
    motion = np.empty((nb, 6, nt))
    accel = np.empty((nb, 3, nt))
    tension = np.empty((nb, 3, nt))
    hub = model.hub
    # the verification-only linear mooring is exact: folded into the stiffness
    stiff = model.stiffness + (model.mooring_stiffness if linear else 0.0)
    args = (forcing.force, forcing.wind, forcing.wind_dir, kin, forcing.kin_every, minv, stiff,
            model.damping, ra[0], ra[1], ra[2], model.rad_b, model.rad_c, np.ascontiguousarray(model.strip_pos.T),
            np.ascontiguousarray(model.strip_axis.T), model.strip_cdn, model.strip_cda, hub, model.thrust_speed, model.thrust_force,
            model.filt_a, model.filt_b, model.filt_c, model.filt_d)
    coupled = not linear
    ker, stride, kpi, kpj = _kernel_at(model, dt)
    hist = np.zeros((nb, stride, 6, 2 * ker.shape[1]))
    f_new = np.zeros((nb, 3, 3))
    ten = np.zeros((nb, 3))
    static = np.asarray(model.static_load, dtype=float)
    if coupled and j0 == 0:
        tension[:, :, 0] = moor.tension(mstate)
    loop = (q, v, xr, zf, f_prev, static, motion, accel, tension, fmoor6, acc, hist, stride, ker, kpi, kpj)
    if coupled and _run_compiled(moor, mstate, n, j0, dt, fair, r_f, v_f, loop, args):
        return Record(dt=dt, motion=motion, accel=accel, tension=tension)
    for j in range(n):
        if coupled:
            # predictor: advance the lines to the fairlead positions extrapolated to t + dt
            _predict_fairleads(q, v, fair, dt, r_f, v_f)
            f_new, mstate = moor.step(mstate, r_f, v_f, dt)  # views, used before the next step
            ten = moor.tension(mstate)
        _advance(j, j - j0, dt, q, v, xr, zf, f_prev, f_new, coupled, static, fair, ten, motion, accel, tension,
                 fmoor6, acc, hist, stride, ker, kpi, kpj, *args)
    if linear:
        tension[:] = np.nan
    return Record(dt=dt, motion=motion, accel=accel, tension=tension)


# --------------------------------------------------------------------------------------
# linear analysis (verification)
# --------------------------------------------------------------------------------------


def _free_dofs(locked: Sequence[int]) -> np.ndarray:
    """The DOFs not in ``locked``, ``(nfree,)`` sorted; ``locked`` is validated and read once."""
    lk = sorted({int(d) for d in locked})
    if any(d < 0 or d > 5 for d in lk):
        raise ValueError(f"locked DOFs {lk}: each must be 0-5 (surge..yaw)")
    free = np.setdiff1d(np.arange(6), lk)
    if free.size == 0:
        raise ValueError("locked DOFs: at least one DOF must stay free")
    return free


def _inverse_mass(mass: np.ndarray, free: np.ndarray) -> np.ndarray:
    """``(6, 6)`` inverse of the ``free`` block of ``mass``, zero in the other rows and columns."""
    minv = np.zeros((6, 6))
    minv[np.ix_(free, free)] = np.linalg.inv(np.asarray(mass, dtype=float)[np.ix_(free, free)])
    return minv


def without_radiation_memory(model: ModelInputs) -> ModelInputs:
    """The model with its radiation memory removed: constant added mass ``A_inf``, no wave damping.

    This is the convention of published natural periods such as the OC4 definition's
    (``T = 2 pi sqrt((M + A_inf) / C)``, the added mass of FAST's linearisation), used to check a
    decay test against them like for like; the simulation itself always keeps the memory. The
    linear and viscous damping, the mooring and everything else are unchanged.
    """
    return replace(model, rad_a=np.zeros((0, 0)), rad_b=np.zeros((0, 6)), rad_c=np.zeros((6, 0)),
                   kernel=np.zeros((0, 0)), kernel_pairs=np.zeros((0, 2), dtype=np.int64), kernel_dt=0.0)


def radiation_impedance(model: ModelInputs, omega: np.ndarray) -> np.ndarray:
    """Frequency response of the model's radiation memory, ``Z(omega)``, ``(nw, 6, 6)`` complex.

    The radiation force on a harmonic velocity ``v exp(-i omega t)`` is ``-Z(omega) v``, so
    ``Re(Z) = B(omega)`` and ``-Im(Z) / omega = A(omega) - A_inf``. State space:
    ``Z = C (-i omega I - A)^-1 B``; kernel: ``Z = int_0^T K(t) exp(i omega t) dt`` (trapezoid).
    """
    w = np.atleast_1d(np.asarray(omega, dtype=float))
    out = np.zeros((w.size, 6, 6), dtype=complex)
    nr = model.rad_a.shape[0]
    if nr:
        eye = np.eye(nr)
        for i, wi in enumerate(w):
            out[i] = model.rad_c @ np.linalg.solve(-1j * wi * eye - model.rad_a, model.rad_b)
    if model.kernel.size:
        t = np.arange(model.kernel.shape[0]) * model.kernel_dt
        e = np.exp(1j * np.outer(w, t))  # (nw, nt)
        z = np.trapezoid(e[:, :, None] * model.kernel[None, :, :], t, axis=1)  # (nw, npairs)
        for p, (i, j) in enumerate(model.kernel_pairs):
            out[:, i, j] += z[:, p]
    return out


def frequency_response(
    model: ModelInputs,
    omega: np.ndarray,
    theta: float,
    *,
    mooring_stiffness: np.ndarray | None = None,
    added_mass: np.ndarray | None = None,
    radiation_damping: np.ndarray | None = None,
) -> np.ndarray:
    """Linear response amplitude operator (RAO) per metre of wave amplitude.

    Solves ``[-omega^2 (M + A_inf + a(omega)) - i omega B(omega) + K + K_m] xi = X(omega, theta)``
    in the ``exp(-i omega t)`` convention. By default the radiation terms come from the model's
    own state space (the exact frequency-domain counterpart of the time integrator).

    Parameters
    ----------
    model : ModelInputs
    omega : (nw,)
        Frequencies, rad/s.
    theta : float
        Propagation angle, rad.
    mooring_stiffness : (6, 6), optional
        Default ``model.mooring_stiffness``.
    added_mass, radiation_damping : (nw, 6, 6), optional
        BEM ``A(omega) - A_inf`` and ``B(omega)`` instead of the state space.

    Returns
    -------
    numpy.ndarray, shape (nw, 6), complex
        Motion per metre of amplitude (m/m, rad/m).
    """
    w = np.atleast_1d(np.asarray(omega, dtype=float))
    km = model.mooring_stiffness if mooring_stiffness is None else np.asarray(mooring_stiffness)
    x = _interp_omega(_interp_heading(model.excitation, model.headings, theta), model.omega, w)
    if added_mass is None:
        z = radiation_impedance(model, w)
    else:
        z = np.asarray(radiation_damping) - 1j * w[:, None, None] * np.asarray(added_mass)
    out = np.empty((w.size, 6), dtype=complex)
    for i, wi in enumerate(w):
        h = -wi**2 * model.mass + model.stiffness + km - 1j * wi * (model.damping + z[i])
        out[i] = np.linalg.solve(h, x[i])
    return out


def linear_natural_periods(
    model: ModelInputs, mooring_stiffness: np.ndarray | None = None, locked: Sequence[int] = ()
) -> np.ndarray:
    """Natural periods (s) of the coupled linear system, one per DOF.

    For each DOF the search starts at its uncoupled estimate ``2 pi sqrt((M + a)_dd / K_dd)``
    and iterates the generalised eigenproblem ``(K + K_m) x = w^2 (M + A_inf + a(w)) x`` with
    the frequency-dependent added mass of the model's own radiation memory, following the
    eigenvalue nearest the current frequency (so surge-pitch and sway-roll coupling through the
    mass matrix is included, as in a decay test). ``locked`` DOFs are held (see
    :func:`integrate`): the eigenproblem is that of the free block. Returns ``(6,)``, ``inf``
    without restoring or for a locked DOF.
    """
    km = model.mooring_stiffness if mooring_stiffness is None else np.asarray(mooring_stiffness)
    free = _free_dofs(locked)
    ix = np.ix_(free, free)
    kk = model.stiffness + km
    out = np.full(6, np.inf)
    for d in free:
        if kk[d, d] <= 0:
            continue
        w = math.sqrt(kk[d, d] / model.mass[d, d])
        for _ in range(40):
            a = model.mass - radiation_impedance(model, np.array([w]))[0].imag / w
            ev = scipy.linalg.eigvals(kk[ix], a[ix])
            ws = np.sqrt(np.abs(ev.real))
            w_new = float(ws[np.argmin(np.abs(ws - w))])
            if abs(w_new - w) < 1e-10 * w:
                break
            w = w_new
        out[d] = 2 * math.pi / w
    return out


# --------------------------------------------------------------------------------------
# statistics of a record
# --------------------------------------------------------------------------------------


def summarise(
    record: Record,
    *,
    line_info: Mapping[str, Any],
    fatigue_cfg: Mapping[str, Any] | None,
    stats_cfg: Mapping[str, Any] | None,
    keep_timeseries: bool = False,
) -> dict[str, np.ndarray]:
    """The per-case outputs of a batch of records.

    Parameters
    ----------
    record : Record
        Kept records, ``(B, ..., nt)``.
    line_info : mapping
        ``link_diameter`` (m), ``mbs`` (N), ``chain`` of the lines.
    fatigue_cfg : mapping or None
        The ``fatigue:`` config section (curves, mean stress, residue); None skips damage.
    stats_cfg : mapping or None
        The ``statistics:`` section (``block``: GEV block length in s, ``method``) plus
        ``mpm_duration`` (s, the duration the MPM refers to; default 3600, one hour of sea
        state; taken from ``simulation.mpm_duration`` by :func:`simulate_batch`).
    keep_timeseries : bool
        Also return the records (``ts_*``).

    Returns
    -------
    dict of numpy.ndarray
        ``names.SIM_SCALAR_VARS`` ``(B,)``, ``names.SIM_LINE_VARS`` ``(B, 3)``,
        ``gev_corr_<v>`` for ``v`` in ``names.GEV_VARS``, and :data:`EXTRA_SCALAR_VARS`,
        :data:`EXTRA_LINE_VARS`. Magnitudes: surge, sway and heave MPMs are of ``|x|``; the
        acceleration is the horizontal magnitude at the hub.
    """
    from moorlife import stats

    st = dict(stats_cfg or {})
    block = float(st.get("block", 60.0))
    mpm_duration = float(st.get("mpm_duration", 3600.0))
    method = str(st.get("method", "lmoments"))
    dt = record.dt
    mo = record.motion
    nt = mo.shape[-1]
    out: dict[str, np.ndarray] = {}

    def gev(x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return stats.gev_mpm(x, dt, block=block, duration=mpm_duration, method=method)

    mpm, corr = gev(np.abs(mo[:, :3, :]))
    for i, name in enumerate(("surge_mpm", "sway_mpm", "heave_mpm")):
        out[name] = mpm[:, i]
        out[f"gev_corr_{name}"] = corr[:, i]
    acc = np.hypot(record.accel[:, 0, :], record.accel[:, 1, :])
    out["accel_mpm"], out["gev_corr_accel_mpm"] = gev(acc)
    pct = stats.percentiles(acc, [90.0, 95.0, 99.0])
    out["accel_p90"], out["accel_p95"], out["accel_p99"] = pct[:, 0], pct[:, 1], pct[:, 2]
    ten = record.tension
    if np.all(np.isfinite(ten)):
        out["tension_mpm"], out["gev_corr_tension_mpm"] = gev(ten)
        out["tension_mean"] = ten.mean(axis=-1)
        out["tension_std"] = ten.std(axis=-1)
        out["tension_max"] = ten.max(axis=-1)
        if fatigue_cfg is not None:
            from moorlife import fatigue

            settings = fatigue.fatigue_settings(fatigue_cfg, source="config.yaml")
            d_sn, d_tn = fatigue.hourly_damage(
                ten, nt * dt, link_diameter=line_info["link_diameter"], mbs=line_info["mbs"],
                chain=line_info["chain"], **settings.damage_kwargs(),
            )
            out["damage_sn"], out["damage_tn"] = np.asarray(d_sn), np.asarray(d_tn)
    else:
        nan3 = np.full(ten.shape[:2], np.nan)
        for name in ("tension_mpm", "gev_corr_tension_mpm", "tension_mean", "tension_std", "tension_max",
                     "damage_sn", "damage_tn"):
            out[name] = nan3.copy()
    out["surge_mean"] = mo[:, 0].mean(axis=-1)
    out["sway_mean"] = mo[:, 1].mean(axis=-1)
    out["heave_mean"] = mo[:, 2].mean(axis=-1)
    out["pitch_mean"] = np.rad2deg(mo[:, 4].mean(axis=-1))
    out["surge_std"] = mo[:, 0].std(axis=-1)
    out["pitch_mpm"], out["gev_corr_pitch_mpm"] = gev(np.rad2deg(np.abs(mo[:, 4])))
    out["offset_max"] = np.hypot(mo[:, 0], mo[:, 1]).max(axis=-1)
    if keep_timeseries:
        for i, name in enumerate(("ts_surge", "ts_sway", "ts_heave", "ts_roll", "ts_pitch", "ts_yaw")):
            out[name] = mo[:, i].astype(np.float32)
        out["ts_accel"] = acc.astype(np.float32)
        out["ts_tension"] = ten.astype(np.float32)
    return out


# --------------------------------------------------------------------------------------
# one batch of sea states
# --------------------------------------------------------------------------------------


def _sim_settings(sim_cfg: Mapping[str, Any]) -> dict[str, Any]:
    s = dict(sim_cfg)
    out = {
        "duration": float(s.get("duration", 3600.0)),
        "transient": float(s.get("transient", 600.0)),
        "dt": float(s.get("dt", 0.1)),
        "gamma": s.get("gamma", "dnv"),
        "kinematics_dt": float(s.get("kinematics_dt", 0.25)),
        "second_order": bool(s.get("second_order", True)),
        "keep_timeseries": bool(s.get("keep_timeseries", False)),
        "wind": dict(s.get("wind", {})),
        "omega_range": s.get("omega_range", None),
        "mpm_duration": float(s.get("mpm_duration", 3600.0)),
    }
    for key in ("duration", "dt", "kinematics_dt"):
        if not out[key] > 0:
            raise ValueError(f"config key 'simulation.{key}' = {s.get(key)!r} must be positive")
    if out["transient"] < 0:
        raise ValueError(f"config key 'simulation.transient' = {s.get('transient')!r} must be >= 0")
    return out


def _check_cases(cases: Mapping[str, np.ndarray], case_ids: np.ndarray) -> dict[str, np.ndarray]:
    missing = [k for k in names.METOCEAN_VARS if k not in cases]
    if missing:
        raise ValueError(f"simulate_batch: sea-state variable(s) {missing} missing (got {sorted(cases)})")
    arr = {k: np.atleast_1d(np.asarray(cases[k], dtype=float)) for k in names.METOCEAN_VARS}
    nb = np.size(case_ids)
    for k, v in arr.items():
        if v.shape != (nb,):
            raise ValueError(f"simulate_batch: {k!r} has shape {v.shape}, expected ({nb},) like case_ids")
        bad = ~np.isfinite(v)
        if k in ("hs", "tp", "wind_speed"):
            bad |= v < 0
        if k == "tp":
            bad |= v == 0
        if bad.any():
            i = int(np.flatnonzero(bad)[0])
            raise ValueError(f"simulate_batch: case {case_ids[i]}: {k} = {float(v[i])!r} is invalid")
    return arr


def simulate_batch(
    cases: Mapping[str, np.ndarray],
    *,
    case_ids: np.ndarray,
    mooring_system: str,
    seed: int,
    model_inputs: ModelInputs,
    sim_cfg: Mapping[str, Any],
    fatigue_cfg: Mapping[str, Any] | None,
    stats_cfg: Mapping[str, Any] | None,
    stream: str = "case",
) -> dict[str, np.ndarray]:
    """Simulate a batch of sea states and return their statistics (pure; Dask-friendly).

    Parameters
    ----------
    cases : mapping of str to (B,) arrays
        ``wind_speed`` (m/s, hub height), ``wind_dir`` (deg, from), ``hs`` (m), ``tp`` (s),
        ``wave_dir`` (deg, from); other keys (e.g. ``hindcast_index``) are ignored.
    case_ids : (B,) int
        The case (or bin) ids: with ``seed`` and ``mooring_system`` they fix the random phases.
    mooring_system : str
        E.g. ``"MS3"``.
    seed : int
        The study seed.
    model_inputs : ModelInputs
        From :func:`prepare_model`.
    sim_cfg, fatigue_cfg, stats_cfg : mapping
        The ``simulation``, ``fatigue`` and ``statistics`` config sections.
    stream : str
        The dimension of ``case_ids`` (``"case"`` or ``"bin"``), so that bins and cases with
        the same id draw independent phases.

    Returns
    -------
    dict of numpy.ndarray
        See :func:`summarise`; leading axis the case.
    """
    ids = np.atleast_1d(np.asarray(case_ids))
    sea = _check_cases(cases, ids)
    s = _sim_settings(sim_cfg)
    model = model_inputs
    grid = env.record_grid(s["duration"], s["transient"], s["dt"])
    n_bins = grid.n_fft // 2 + 1
    wave_ph, wind_ph = env.case_streams(seed, mooring_system, ids, n_bins, stream)
    gamma = env.resolve_gamma(s["gamma"], sea["hs"], sea["tp"])
    w_lo, w_hi = (float(model.omega.min()), float(model.omega.max())) if s["omega_range"] is None else map(
        float, s["omega_range"])
    waves = env.wave_components(grid, sea["hs"], sea["tp"], sea["wave_dir"], gamma, wave_ph,
                                omega_min=w_lo, omega_max=w_hi)
    wind_cfg = {**s["wind"], "height": float(model.hub[2])}
    wind = env.wind_series(grid, sea["wind_speed"], wind_ph, wind_cfg)
    kin_every = max(1, int(round(s["kinematics_dt"] / s["dt"])))
    forcing = build_forcing(model, grid, waves, wind, sea["wind_dir"], kin_every=kin_every,
                            second_order=s["second_order"])
    record = integrate(model, forcing, transient=s["transient"])
    bad = ~np.isfinite(record.motion).all(axis=(1, 2))
    if model.mooring_kind != "linear":
        bad |= ~np.isfinite(record.tension).all(axis=(1, 2))
    if bad.any():
        b = int(np.flatnonzero(bad)[0])
        raise FloatingPointError(
            f"simulate_batch ({mooring_system}): case {ids[b]} diverged (non-finite motion or tension) with "
            f"hs={sea['hs'][b]}, tp={sea['tp'][b]}, wave_dir={sea['wave_dir'][b]}, wind_speed={sea['wind_speed'][b]}, "
            f"wind_dir={sea['wind_dir'][b]}; reduce simulation.dt"
        )
    st = {**dict(stats_cfg or {}), "mpm_duration": s["mpm_duration"]}
    return summarise(record, line_info=model.line_info, fatigue_cfg=fatigue_cfg, stats_cfg=st,
                     keep_timeseries=s["keep_timeseries"])


# --------------------------------------------------------------------------------------
# model preparation (once per mooring system)
# --------------------------------------------------------------------------------------


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
    return (np.asarray(pos, dtype=float).reshape(-1, 3), np.asarray(axis, dtype=float).reshape(-1, 3),
            np.asarray(cdn, dtype=float), np.asarray(cda, dtype=float))


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
    ss_order = 30 if str(sim_cfg.get("radiation", "convolution")) == "statespace" else None
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

    rho = float(pm.rho)
    members = platform_cfg.get("members")
    if not members:
        raise ValueError("platform config: no 'members' (needed for the Morison drag strips)")
    strip_len = max(float(sim_cfg.get("drag_strip_length", 4.0)), float(platform_cfg.get("morison_strip_length", 1.0)))
    strips = _strips_from_members(members, strip_len, rho)
    v = np.arange(-40.0, 80.0 + 1e-9, 0.02)
    thrust = turbine.thrust(v, pm.ct_wind_speed, pm.ct, rho_air=pm.rho_air, rotor_area=pm.rotor_area,
                            cut_in=pm.cut_in, cut_out=pm.cut_out, shutdown_ramp=pm.shutdown_ramp,
                            startup_ramp=pm.startup_ramp)
    filt = turbine.notch_filter(pm.pitch_filter_centre, pm.pitch_filter_quality)
    damp = np.diag(np.asarray(sim_cfg.get("extra_damping", [0.0] * 6), dtype=float))
    depth = float(pm.water_depth)
    if not np.isfinite(depth):  # e.g. a WAMIT import without the depth
        depth = float(platform_cfg["environment"]["water_depth"])
    radiation = str(sim_cfg.get("radiation", "convolution"))
    if radiation == "convolution":
        memory = float(sim_cfg.get("radiation_memory", 60.0))
        nk = int(np.searchsorted(np.asarray(pm.kernel_t), memory + 1e-9))
        kern6 = np.asarray(pm.kernel, float)[:nk]
        pairs = _kernel_pairs(kern6)
        rad = dict(kernel=np.stack([kern6[:, i, j] for i, j in pairs], axis=1), kernel_pairs=pairs,
                   kernel_dt=float(pm.kernel_dt))
    elif radiation == "statespace":
        rad = dict(rad_a=pm.ss_A, rad_b=pm.ss_B, rad_c=pm.ss_C)
    else:
        raise ValueError(f"config key 'simulation.radiation' = {radiation!r}: expected 'convolution' or 'statespace'")
    model = build_model(
        mass=np.asarray(pm.mass, float) + np.asarray(pm.added_mass_inf, float),
        stiffness=np.asarray(pm.stiffness, float),
        damping=damp,
        **rad,
        omega=pm.omega, headings=pm.headings,
        excitation=np.conj(np.asarray(pm.excitation)), drift=pm.drift,
        strip_pos=strips[0], strip_axis=strips[1], strip_cdn=strips[2], strip_cda=strips[3],
        hub=np.asarray(pm.hub_point, float), thrust_speed=v, thrust_force=thrust,
        filt_a=filt.A, filt_b=np.asarray(filt.B, float).reshape(-1, 1), filt_c=np.asarray(filt.C, float).reshape(1, -1),
        filt_d=np.array([[float(filt.D)]]),
        depth=depth, rho=rho, gravity=float(pm.g),
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


def attach_mooring(model: ModelInputs, mooring_row: Mapping[str, Any], mooring_cfg: Mapping[str, Any] | None) -> ModelInputs:
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
        lines at rest (the ballast adjustment of each mooring system).
    """
    from moorlife import mooring as moor

    props = moor.line_properties(mooring_row, water_density=model.rho, gravity=model.gravity)
    layout = moor.oc4_layout(mooring_cfg)
    if abs(layout.depth - model.depth) > 1e-6:
        raise ValueError(f"mooring.water_depth = {layout.depth} m differs from the platform's water depth {model.depth} m")
    kind = moor.mooring_settings(mooring_cfg).model
    proto = moor.make_mooring(kind, props, layout, mooring_cfg, batch=1)
    fair = np.ascontiguousarray(layout.fairleads_body, dtype=float)
    rest = _rest_mooring_load(proto, fair)
    static = np.zeros(6)
    static[[2, 3, 4]] = -rest[[2, 3, 4]]
    return replace(
        model, mooring_kind=kind, mooring_args=(props, layout, mooring_cfg, proto), fairleads=fair,
        static_load=static,
        line_info={"link_diameter": props.link_diameter, "mbs": props.MBS, "chain": props.chain},
    )


def static_equilibrium(model: ModelInputs, load: np.ndarray, *, tol: float = 1e-6, max_iter: int = 50) -> tuple[np.ndarray, np.ndarray]:
    """Static position of the moored platform under a constant external load.

    Solves ``load + static_load + F_moor(q) - K q = 0`` by Newton iterations with a
    finite-difference Jacobian, the mooring force from the quasi-static catenary of the model's
    lines (``"linear"`` models use ``mooring_stiffness``).

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
    load = np.asarray(load, dtype=float)
    if model.mooring_kind == "linear":
        q = np.linalg.solve(model.stiffness + model.mooring_stiffness, load + model.static_load)
        return q, np.full(3, np.nan)
    from moorlife import mooring as moor

    props, layout, cfg, _ = model.mooring_args
    qs = moor.make_mooring("quasistatic", props, layout, cfg, batch=7)
    fair = np.ascontiguousarray(model.fairleads)

    def residual(qb: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        r = np.empty((qb.shape[0], 3, 3))
        vz = np.zeros_like(r)
        _fairlead_motion(qb, np.zeros_like(qb), fair, r, vz)
        st = qs.init(r)
        f6 = np.zeros((qb.shape[0], 6))
        _moor_generalised(qb, np.array(qs.forces(st), dtype=float), fair, f6)
        return load + model.static_load + f6 - qb @ model.stiffness.T, np.array(qs.tension(st))

    q = np.zeros(6)
    h = np.array([1e-3, 1e-3, 1e-3, 1e-5, 1e-5, 1e-5])
    for _ in range(max_iter):
        qb = np.vstack([q, q + np.diag(h)])
        res, ten = residual(qb)
        jac = ((res[1:] - res[0]) / h[:, None]).T
        dq = np.linalg.lstsq(jac, -res[0], rcond=None)[0]
        q = q + dq
        if np.all(np.abs(dq) < tol * np.maximum(1.0, np.abs(q))):
            break
    res, ten = residual(np.vstack([q] * 7))
    return q, ten[0]
