"""The start of a record at its linear periodic steady state (``simulation.start: steady``).

The mean-equilibrium start (:mod:`moorlife.simulate.initial`) puts the platform where its record
oscillates about, but at rest: the lightly damped slow-drift surge and sway then need several
hundred seconds to build up to their stationary amplitude (``validation/transient.md``). The
synthesised forcing is periodic with its FFT period, so the steady state of a *linearised* model
under that same forcing is known at every instant, by FFT. :func:`steady_start` starts each record
there: platform displacement and velocity, the radiation convolution's velocity history (or the
state-space states), and the rotor filter, all at the linear periodic response at ``t = 0``.

The linear model about the mean equilibrium (:func:`~moorlife.simulate.initial.mean_equilibrium`):

* restoring: hydrostatics plus the quasi-static catenary's stiffness at the mean offset
  (finite differences, as the static solve);
* inertia and radiation: ``M + A_inf`` and the model's own radiation memory (its impedance);
* Morison drag: stochastic linearisation about the record's own wave kinematics,
  ``B = sum_s J_s^T E[df/du] J_s`` with the time mean over the record, and the drag force of the
  undisturbed kinematics as a load (its difference-frequency part drives the slow drift too);
* rotor: the thrust of the filtered undisturbed wind as a load, and the aerodynamic damping
  ``max(E[T'], 0) G(omega) e e^T`` of the pitch-band filter ``G`` on the relative wind (none
  above rated, where the thrust curve falls);
* the dynamic lines' slow-drift damping (drag and seabed friction), measured once per model by a
  forced slow oscillation (:func:`line_damping`);
* the model's extra linear damping. The lines start in their static shape, as before.

Only the start changes; the integration that follows is the full nonlinear model.
"""

from __future__ import annotations

import math
import weakref
from typing import Any

import numba
import numpy as np

from moorlife.simulate.forcing import Forcing
from moorlife.simulate.initial import (
    InitialState,
    _dynamic_lines,
    _residual_and_jacobian,
    _static_lines,
    mean_equilibrium,
)
from moorlife.simulate.integration import _kernel_at
from moorlife.simulate.kernel import _fairlead_motion, _moor_generalised
from moorlife.simulate.linear import radiation_impedance
from moorlife.simulate.model import ModelInputs

__all__ = ["drag_linearisation", "linear_stiffness", "periodic_response", "steady_start"]

#: Frequencies above this (rad/s) carry no response worth solving for (the platform's RAOs are
#: negligible there and the forcing spectra have no energy).
OMEGA_MAX = 4.0
#: Samples (at least) of the time means of the drag linearisation: a mean of a stationary record.
MEAN_SAMPLES = 4096
#: Step of the frequency grid the radiation impedance is evaluated on and interpolated from,
#: rad/s (it is smooth on the scale of 2 pi / its memory: 0.1 rad/s for 60 s).
IMPEDANCE_STEP = 0.02


def _strip_jacobians(model: ModelInputs) -> np.ndarray:
    """``(ns, 3, 6)``: strip velocity ``v + omega x p`` from the platform velocity (small angles)."""
    p = np.asarray(model.strip_pos, dtype=float)
    ns = p.shape[0]
    j = np.zeros((ns, 3, 6))
    j[:, 0, 0] = j[:, 1, 1] = j[:, 2, 2] = 1.0
    # omega x p = -p x omega = -[p]_x omega
    j[:, 0, 4], j[:, 0, 5] = p[:, 2], -p[:, 1]
    j[:, 1, 3], j[:, 1, 5] = -p[:, 2], p[:, 0]
    j[:, 2, 3], j[:, 2, 4] = p[:, 1], -p[:, 0]
    return j


@numba.njit(cache=True, error_model="numpy")
def _drag_pass(u, pos, axis, cn, ca, thin, load, mean_abs_n, mean_outer, mean_abs_a):  # pragma: no cover - numba
    """The drag load ``(nk, 6)`` of each sample of the kinematics ``u (nk, 3, ns)``, and over every
    ``thin``-th sample the sums of ``|u_n|`` ``(ns,)``, ``u_n u_n^T / |u_n|`` (upper triangle of
    ``(ns, 3, 3)``) and ``|u_a|``."""
    nk, _, ns = u.shape
    for k in range(nk):
        f0 = f1 = f2 = m3 = m4 = m5 = 0.0
        uk = u[k]
        for s in range(ns):  # the strips of one sample (contiguous), the sums in registers
            ax, ay, az = axis[0, s], axis[1, s], axis[2, s]
            ux, uy, uz = float(uk[0, s]), float(uk[1, s]), float(uk[2, s])
            ua = ux * ax + uy * ay + uz * az
            nx, ny, nz = ux - ua * ax, uy - ua * ay, uz - ua * az
            un = math.sqrt(nx * nx + ny * ny + nz * nz)
            c = ca[s] * abs(ua) * ua
            fx = cn[s] * un * nx + c * ax
            fy = cn[s] * un * ny + c * ay
            fz = cn[s] * un * nz + c * az
            px, py, pz = pos[0, s], pos[1, s], pos[2, s]
            f0 += fx
            f1 += fy
            f2 += fz
            m3 += py * fz - pz * fy
            m4 += pz * fx - px * fz
            m5 += px * fy - py * fx
        load[k, 0], load[k, 1], load[k, 2], load[k, 3], load[k, 4], load[k, 5] = f0, f1, f2, m3, m4, m5
    for k in range(0, nk, thin):
        uk = u[k]
        for s in range(ns):
            ax, ay, az = axis[0, s], axis[1, s], axis[2, s]
            ux, uy, uz = float(uk[0, s]), float(uk[1, s]), float(uk[2, s])
            ua = ux * ax + uy * ay + uz * az
            nx, ny, nz = ux - ua * ax, uy - ua * ay, uz - ua * az
            un = math.sqrt(nx * nx + ny * ny + nz * nz)
            mean_abs_n[s] += un
            mean_abs_a[s] += abs(ua)
            if un > 0.0:
                r = 1.0 / un
                mean_outer[s, 0, 0] += nx * nx * r
                mean_outer[s, 0, 1] += nx * ny * r
                mean_outer[s, 0, 2] += nx * nz * r
                mean_outer[s, 1, 1] += ny * ny * r
                mean_outer[s, 1, 2] += ny * nz * r
                mean_outer[s, 2, 2] += nz * nz * r


def _strip_forces(model: ModelInputs, u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Morison drag of the undisturbed kinematics ``u (nk, 3, ns)``: load ``(nk, 6)`` and ``E[df/du] (ns, 3, 3)``."""
    a = np.ascontiguousarray(model.strip_axis, dtype=float)  # (ns, 3)
    cn = np.ascontiguousarray(model.strip_cdn, dtype=float)
    ca = np.ascontiguousarray(model.strip_cda, dtype=float)
    nk, _, ns = u.shape
    thin = max(1, nk // MEAN_SAMPLES)
    load = np.empty((nk, 6))
    abs_n, abs_a, outer = np.zeros(ns), np.zeros(ns), np.zeros((ns, 3, 3))
    pos = np.ascontiguousarray(np.asarray(model.strip_pos, dtype=float).T)
    _drag_pass(np.ascontiguousarray(u), pos, np.ascontiguousarray(a.T), cn, ca, thin, load, abs_n, outer, abs_a)
    nk = len(range(0, nk, thin))  # the samples of the means
    for i, e in ((1, 0), (2, 0), (2, 1)):  # the kernel sums the upper triangle
        outer[:, i, e] = outer[:, e, i]
    proj = np.eye(3)[None] - a[:, :, None] * a[:, None, :]  # (ns, 3, 3)
    dfdu = cn[:, None, None] * ((abs_n / nk)[:, None, None] * proj + outer / nk)
    dfdu += (2.0 * ca * abs_a / nk)[:, None, None] * (a[:, :, None] * a[:, None, :])
    return load, dfdu


def drag_linearisation(model: ModelInputs, kinematics: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Stochastic linearisation of the strips' Morison drag about one record's wave kinematics.

    Parameters
    ----------
    model : ModelInputs
    kinematics : (nk, 3, ns)
        Undisturbed wave particle velocity at the strips over one period, m/s.

    Returns
    -------
    load : (nk, 6)
        Drag load of the undisturbed kinematics on the platform at rest, N and N m.
    damping : (6, 6)
        ``sum_s J_s^T E[df/du] J_s``, the equivalent linear damping of the platform's velocity.
    """
    if np.asarray(model.strip_pos).shape[0] == 0:
        return np.zeros((kinematics.shape[0], 6)), np.zeros((6, 6))
    load, dfdu = _strip_forces(model, np.asarray(kinematics))
    jac = _strip_jacobians(model)
    return load, np.einsum("scd,sce,sef->df", jac, dfdu, jac)


def linear_stiffness(model: ModelInputs, q: np.ndarray, loads: np.ndarray) -> np.ndarray:
    """``(B, 6, 6)`` restoring stiffness (hydrostatics plus quasi-static lines) at ``q (B, 6)``."""
    if model.mooring_kind == "linear":
        return np.broadcast_to(model.stiffness + model.mooring_stiffness, (q.shape[0], 6, 6)).copy()
    trim = np.asarray(model.static_load, dtype=float)
    _, jac = _residual_and_jacobian(model, _static_lines(model), q, loads + trim)
    return -jac


def _filter_response(model: ModelInputs, omega: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Pitch-band filter: ``G(omega)`` (nw,) of the output and ``(i omega - A)^-1 B`` (nw, nf) of its states."""
    nf = model.filt_a.shape[0]
    d = float(np.asarray(model.filt_d)[0, 0])
    if nf == 0:
        return np.full(omega.size, d, dtype=complex), np.zeros((omega.size, 0), dtype=complex)
    lhs = 1j * omega[:, None, None] * np.eye(nf)[None] - model.filt_a[None]
    rhs = np.broadcast_to(model.filt_b.astype(complex), (omega.size, nf, 1))
    states = np.linalg.solve(lhs, rhs)[..., 0]
    return states @ model.filt_c[0] + d, states


#: Forced slow oscillation that measures the dynamic lines' damping: amplitude (m) and period (s).
LINE_DAMPING_TEST = (1.0, 100.0)
_LINE_DAMPING: dict[int, tuple[Any, np.ndarray]] = {}


def line_damping(model: ModelInputs) -> np.ndarray:
    """``(6, 6)`` slow-drift damping of the model's dynamic lines (zero for other moorings).

    Measured once per model, as a decay or forced-oscillation test would: the lines are driven in
    surge, and in sway, by a harmonic platform motion of :data:`LINE_DAMPING_TEST` about the
    origin, and the energy their forces take out over the second cycle gives the equivalent linear
    damping ``B = -int F v dt / (pi a^2 omega)`` (drag and seabed friction of the lines). Cached
    for the life of the model object.
    """
    hit = _LINE_DAMPING.get(id(model))
    if hit is not None and hit[0]() is model:
        return hit[1]
    out = np.zeros((6, 6))
    lines = _dynamic_lines(model, 2) if model.mooring_kind == "dynamic" else None
    if lines is not None:
        amp, period = LINE_DAMPING_TEST
        om = 2.0 * np.pi / period
        dt = 0.1
        n = int(round(2 * period / dt))
        fair = np.ascontiguousarray(model.fairleads, dtype=float)
        q, v = np.zeros((2, 6)), np.zeros((2, 6))
        r, rv = np.empty((2, fair.shape[0], 3)), np.empty((2, fair.shape[0], 3))
        _fairlead_motion(q, v, fair, r, rv)
        state = lines.init(r.copy())
        f6 = np.zeros((2, 6))
        work = np.zeros(2)
        for j in range(1, n + 1):
            t = j * dt
            q[0, 0] = q[1, 1] = amp * np.sin(om * t)
            v[0, 0] = v[1, 1] = amp * om * np.cos(om * t)
            _fairlead_motion(q, v, fair, r, rv)
            forces, state = lines.step(state, r, rv, dt)
            f6[:] = 0.0
            _moor_generalised(q, np.ascontiguousarray(forces, dtype=float), fair, f6)
            if j > n // 2:  # the second cycle, trapezoid-free (a sum over whole cycles)
                work += np.array([f6[0, 0] * v[0, 0], f6[1, 1] * v[1, 1]]) * dt
        out[0, 0], out[1, 1] = np.clip(-work / (np.pi * amp**2 * om), 0.0, None)
    _LINE_DAMPING[id(model)] = (weakref.ref(model), out)
    return out


def _impedance(model: ModelInputs, omega: np.ndarray) -> np.ndarray:
    """The model's radiation impedance at ``omega``, interpolated from a grid of :data:`IMPEDANCE_STEP`."""
    grid = np.arange(0.0, omega.max() + 2 * IMPEDANCE_STEP, IMPEDANCE_STEP)
    z = radiation_impedance(model, grid).reshape(grid.size, 36)
    out = np.empty((omega.size, 36), dtype=complex)
    for k in range(36):
        out[:, k] = np.interp(omega, grid, z[:, k].real) + 1j * np.interp(omega, grid, z[:, k].imag)
    return out.reshape(omega.size, 6, 6)


def periodic_response(
    model: ModelInputs, forcing: Forcing, period: int, *, q_mean: np.ndarray, stiffness: np.ndarray
) -> dict[str, np.ndarray]:
    """Linear periodic steady-state response of every record of a batch, one period long.

    Parameters
    ----------
    model : ModelInputs
    forcing : Forcing
        Holds at least ``period`` samples (``period / kin_every`` of the kinematics): one whole
        period of the synthesis, which is periodic with it.
    period : int
        The period in steps (the FFT length of the synthesis).
    q_mean : (B, 6)
        The mean equilibrium the response is about.
    stiffness : (B, 6, 6)
        Restoring stiffness there (:func:`linear_stiffness`).

    Returns
    -------
    dict
        ``displacement``, ``velocity`` ``(B, period, 6)`` (the mean included in the displacement),
        ``filter`` ``(B, period, nf)``, ``radiation`` ``(B, period, nr)``.
    """
    dt = forcing.grid.dt
    n = int(period)
    ke = forcing.kin_every
    if forcing.force.shape[1] < n or forcing.kinematics.shape[1] < n // ke:
        raise ValueError(f"periodic_response: the forcing holds less than one period of {n} steps")
    # the kinematics are periodic on their own grid only when it divides the period: else their
    # drag is linearised (a time mean) but not applied as a load
    drag_load = n % ke == 0
    nb = forcing.force.shape[0]
    omega = 2.0 * np.pi * np.fft.rfftfreq(n, dt)
    keep = np.flatnonzero((omega > 0.0) & (omega <= OMEGA_MAX))
    w = omega[keep]
    shared = {
        "omega": omega,
        "keep": keep,
        "filter": _filter_response(model, omega),
        "impedance": np.conj(_impedance(model, w)),  # exp(+i omega t) convention
        "radiation": _radiation_states(model, omega),
        "kin_bins": (n // ke) // 2 + 1 if drag_load else 0,
        "line_damping": line_damping(model),
    }
    out: dict[str, list[np.ndarray]] = {"displacement": [], "velocity": [], "filter": [], "radiation": []}
    for b in range(nb):  # case by case: a case's bits do not depend on the batch
        one = _case_response(
            model,
            shared,
            force=np.asarray(forcing.force[b, :n], dtype=float),
            wind=np.asarray(forcing.wind[b, :n], dtype=float),
            wind_dir=np.asarray(forcing.wind_dir[b], dtype=float),
            kinematics=forcing.kinematics[b, : n // ke],
            kin_every=ke,
            stiffness=np.asarray(stiffness[b], dtype=float),
        )
        one["displacement"] += q_mean[b][None, :]
        for key, val in one.items():
            out[key].append(val)
    return {key: np.stack(val) for key, val in out.items()}


def _radiation_states(model: ModelInputs, omega: np.ndarray) -> np.ndarray:
    """``(nw, nr, 6)``: the state-space radiation states per unit velocity, ``(i omega - A)^-1 B``."""
    nr = model.rad_a.shape[0]
    if nr == 0:
        return np.zeros((omega.size, 0, 6), dtype=complex)
    lhs = 1j * omega[:, None, None] * np.eye(nr)[None] - model.rad_a[None]
    return np.linalg.solve(lhs, np.broadcast_to(model.rad_b.astype(complex), (omega.size, nr, 6)))


def _case_response(
    model: ModelInputs,
    shared: dict,
    *,
    force: np.ndarray,
    wind: np.ndarray,
    wind_dir: np.ndarray,
    kinematics: np.ndarray,
    kin_every: int,
    stiffness: np.ndarray,
) -> dict[str, np.ndarray]:
    """One record's periodic response about zero (see :func:`periodic_response`)."""
    n = force.shape[0]
    omega, keep = shared["omega"], shared["keep"]
    w = omega[keep]
    g, g_states = shared["filter"]
    # rotor: the thrust of the filtered undisturbed wind, and the mean slope of the thrust curve
    uhat = np.fft.rfft(wind)
    uf = np.fft.irfft(uhat * g, n=n)  # G(0) passes the mean as the filter does
    tv, tf = np.asarray(model.thrust_speed, dtype=float), np.asarray(model.thrust_force, dtype=float)
    slope_tab = np.diff(tf) / np.diff(tv)
    seg = np.clip(np.searchsorted(tv, uf, side="right") - 1, 0, slope_tab.size - 1)
    slope = float(np.where((uf >= tv[0]) & (uf <= tv[-1]), slope_tab[seg], 0.0).mean())
    # above rated the thrust falls with the wind: a negative aerodynamic damping, which the linear
    # model would turn into a near-unstable slow-drift resonance that the nonlinear record (drag,
    # the lines) never reaches. The start takes none rather than a negative one.
    slope = max(slope, 0.0)
    hx, hy, hz = (float(c) for c in model.hub)
    ex, ey = float(wind_dir[0]), float(wind_dir[1])
    e = np.array([ex, ey, 0.0, -hz * ey, hz * ex, hx * ey - hy * ex])
    # the loads: waves (first order and slow drift), thrust, drag of the undisturbed kinematics
    load = force + np.interp(uf, tv, tf)[:, None] * e[None, :]
    fhat = np.fft.rfft(load, axis=0)[keep]  # (nw, 6)
    dload, bdrag = drag_linearisation(model, kinematics)
    if shared["kin_bins"]:
        dhat = np.fft.rfft(dload, axis=0) * kin_every  # on the step grid's normalisation
        inside = keep[keep < shared["kin_bins"] - 1]  # the kinematics' own Nyquist bin excluded
        fhat[: inside.size] += dhat[inside]
    damping = np.asarray(model.damping, dtype=float) + bdrag + shared["line_damping"]
    aero = slope * g[keep][:, None, None] * np.outer(e, e)[None]
    h = (
        -(w**2)[:, None, None] * np.asarray(model.mass, dtype=float)[None]
        + stiffness[None]
        + 1j * w[:, None, None] * (damping[None] + aero + shared["impedance"])
    )
    xhat = np.zeros((omega.size, 6), dtype=complex)
    xhat[keep] = np.linalg.solve(h, fhat[..., None])[..., 0]
    vhat = 1j * omega[:, None] * xhat
    # the rotor filter on the relative wind u - e.v, and the radiation states on v
    zhat = (uhat - vhat @ e)[:, None] * g_states  # at omega = 0: -A^-1 B times the mean
    rhat = np.einsum("wrd,wd->wr", shared["radiation"], vhat)
    return {
        "displacement": np.fft.irfft(xhat, n=n, axis=0),
        "velocity": np.fft.irfft(vhat, n=n, axis=0),
        "filter": np.fft.irfft(zhat, n=n, axis=0),
        "radiation": np.fft.irfft(rhat, n=n, axis=0),
    }


def steady_start(model: ModelInputs, forcing: Forcing, period: int, *, first: int = 0) -> InitialState:
    """Every record of a batch at its linear periodic steady state at step ``first``.

    Parameters
    ----------
    model : ModelInputs
    forcing : Forcing
        One whole period of the synthesis (at least ``period`` samples), as the record's own
        forcing when its grid holds the period.
    period : int
        The synthesis period in steps (``grid.n_fft``).
    first : int
        The step of the period the record starts at.

    Returns
    -------
    InitialState
        With ``history``, the velocity of the ``stride * nlag`` steps before the start (oldest
        first) for the radiation convolution.
    """
    eq = mean_equilibrium(model, forcing)
    k = linear_stiffness(model, eq.displacement, eq.load)
    resp = periodic_response(model, forcing, period, q_mean=eq.displacement, stiffness=k)
    j = int(first) % period
    ker, stride, _, _ = _kernel_at(model, forcing.grid.dt)
    m = stride * ker.shape[1]
    past = (j - m + np.arange(m)) % period
    return InitialState(
        displacement=resp["displacement"][:, j].copy(),
        velocity=resp["velocity"][:, j].copy(),
        radiation=resp["radiation"][:, j].copy(),
        filter=resp["filter"][:, j].copy(),
        history=np.ascontiguousarray(resp["velocity"][:, past].transpose(0, 2, 1)),
    )
