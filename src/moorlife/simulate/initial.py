"""The start of a record: the platform, the lines and the filters at the record's mean equilibrium.

A record that starts with the platform at rest at its trimmed position is pushed off by the
mean thrust and the mean wave drift, and swings about its new mean at the surge period (about
100 s, lightly damped) for several minutes: that is what ``simulation.transient`` used to
discard (600 s). :func:`equilibrium_start` starts every sea state where its record will
oscillate instead:

* the platform at the static offset under the record's mean load (:func:`mean_load`: the
  mean rotor thrust of its wind series and the mean of its wave force, i.e. the mean drift;
  the model has no current), found by Newton iterations on the mooring restoring plus the
  hydrostatics (:func:`static_offsets`), at rest;
* the lines in their static shape at that offset: the integrator initialises the mooring model
  at the start's fairlead positions (the dynamic lines' static node solve); with dynamic lines
  the offset is corrected once against their own static forces, which differ from the
  catenary's by the seabed springs and the discretisation (a few kN);
* the radiation memory at its steady state for a body at rest (zero state-space states; the
  convolution's velocity history is zero in the integrator) and the rotor's pitch-band filter
  at its steady state for the first wind sample (:func:`at_rest`).

Pure numpy around the compiled fairlead kinematics of :mod:`moorlife.simulate.kernel`.
"""

from __future__ import annotations

from typing import Any, NamedTuple

import numpy as np

from moorlife.simulate.forcing import Forcing
from moorlife.simulate.kernel import _fairlead_motion, _moor_generalised
from moorlife.simulate.model import ModelInputs

__all__ = [
    "InitialState",
    "Equilibrium",
    "at_rest",
    "mean_load",
    "static_offsets",
    "mean_equilibrium",
    "equilibrium_start",
]

#: Finite-difference steps of the Newton Jacobian (m, m, m, rad, rad, rad).
_FD_STEP = np.array([1e-3, 1e-3, 1e-3, 1e-5, 1e-5, 1e-5])


class InitialState(NamedTuple):
    """The state a batch of records starts from (what :func:`moorlife.simulate.integrate` takes).

    Attributes
    ----------
    displacement : (B, 6)
        Platform displacement about the origin, m and rad.
    velocity : (B, 6)
        Platform velocity, m/s and rad/s.
    radiation : (B, nr)
        Radiation state-space states (empty with a retardation kernel, whose velocity history
        starts at zero: the body at rest before ``t = 0``).
    filter : (B, nf)
        States of the rotor's pitch-band filter.
    history : (B, 6, m), optional
        Platform velocity of the ``m`` steps before ``t = 0``, oldest first, for the radiation
        convolution (None: at rest before ``t = 0``; :func:`moorlife.simulate.steady_start`).
    """

    displacement: np.ndarray
    velocity: np.ndarray
    radiation: np.ndarray
    filter: np.ndarray
    history: np.ndarray | None = None


class Equilibrium(NamedTuple):
    """Static equilibria of a batch under constant loads (:func:`static_offsets`).

    Attributes
    ----------
    displacement : (B, 6)
        Platform displacement, m and rad.
    load : (B, 6)
        The external load balanced there (without the trim load), N and N m.
    tension : (B, 3)
        Fairlead tensions of the quasi-static catenary at its equilibrium, N (NaN for a linear
        mooring).
    residual : (B, 6)
        Remaining force imbalance at ``displacement`` with the model's own lines, N and N m.
    """

    displacement: np.ndarray
    load: np.ndarray
    tension: np.ndarray
    residual: np.ndarray


def at_rest(
    model: ModelInputs, forcing: Forcing, q0: np.ndarray | None = None, v0: np.ndarray | None = None
) -> InitialState:
    """The platform at ``q0`` with velocity ``v0`` (default: at rest at the origin).

    The radiation states are zero (their steady state for a body at rest) and the pitch-band
    filter is at its steady state for the first wind sample, ``z = -A^-1 B u(0)``, so the
    rotor starts without a kick. This is the start of every record before issue 23 (with
    ``q0 = 0``).

    Parameters
    ----------
    model : ModelInputs
    forcing : Forcing
        The batch's forcing (its batch size and first wind sample).
    q0, v0 : (B, 6) or (6,), optional

    Returns
    -------
    InitialState
    """
    nb = forcing.force.shape[0]
    q = np.zeros((nb, 6)) if q0 is None else np.array(q0, dtype=float).reshape(nb, 6)
    v = np.zeros((nb, 6)) if v0 is None else np.array(v0, dtype=float).reshape(nb, 6)
    xr = np.zeros((nb, model.rad_a.shape[0]))
    nf = model.filt_a.shape[0]
    zf = np.zeros((nb, nf))
    if nf:
        zf[:] = -np.linalg.solve(model.filt_a, model.filt_b[:, 0])[None, :] * np.asarray(forcing.wind)[:, :1]
    return InitialState(displacement=q, velocity=v, radiation=xr, filter=zf)


def mean_load(model: ModelInputs, forcing: Forcing) -> np.ndarray:
    """Mean external load of each record of a batch on the platform at rest, ``(B, 6)``.

    The time mean over the simulated series of the wave force (first order, which averages
    out, plus Newman's slow drift, whose mean is the mean drift force) and of the rotor thrust
    ``T(u(t))`` of the hub wind series applied at the hub along the wind, as in the integrator.
    The thrust of the unfiltered wind is used: the pitch-band filter passes the mean unchanged.
    Morison drag has no mean without current.

    Returns
    -------
    numpy.ndarray, shape (B, 6)
        N and N m, about the origin.
    """
    load = np.asarray(forcing.force, dtype=float).mean(axis=1)
    thrust = np.interp(np.asarray(forcing.wind, dtype=float), model.thrust_speed, model.thrust_force).mean(axis=1)
    tx = thrust * forcing.wind_dir[:, 0]
    ty = thrust * forcing.wind_dir[:, 1]
    hx, hy, hz = (float(c) for c in model.hub)
    load[:, 0] += tx
    load[:, 1] += ty
    load[:, 3] += -hz * ty
    load[:, 4] += hz * tx
    load[:, 5] += hx * ty - hy * tx
    return load


def _static_lines(model: ModelInputs) -> Any:
    """The quasi-static line model of the static solve (the model's own, or built from its lines)."""
    from moorlife import mooring as moor

    if model.static_mooring is not None:
        return model.static_mooring
    props, layout, cfg, _ = model.mooring_args
    return moor.make_mooring("quasistatic", props, layout, cfg, batch=1)


def _line_loads(model: ModelInputs, lines: Any, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Mooring load about the displaced origin ``(n, 6)`` and fairlead tensions ``(n, 3)`` at rest at ``q (n, 6)``."""
    fair = np.ascontiguousarray(model.fairleads, dtype=float)
    q = np.ascontiguousarray(q, dtype=float)
    r = np.empty((q.shape[0], fair.shape[0], 3))
    vel = np.empty_like(r)
    _fairlead_motion(q, np.zeros_like(q), fair, r, vel)
    state = lines.init(r)
    f6 = np.zeros((q.shape[0], 6))
    _moor_generalised(q, np.ascontiguousarray(lines.forces(state), dtype=float), fair, f6)
    return f6, np.array(lines.tension(state), dtype=float)


def static_offsets(model: ModelInputs, loads: np.ndarray, *, tol: float = 1e-6, max_iter: int = 50) -> Equilibrium:
    """Static positions of the moored platform under constant external loads, a batch at once.

    Solves ``load + static_load + F_moor(q) - K q = 0`` for every row of ``loads`` by Newton
    iterations with a finite-difference Jacobian; ``F_moor`` is the quasi-static catenary of
    the model's lines (``"linear"`` models: ``mooring_stiffness``, one linear solve).

    Parameters
    ----------
    model : ModelInputs
    loads : (B, 6) or (6,)
        External loads about the origin, N and N m.
    tol : float
        Convergence: every step below ``tol * max(1, |q|)``.
    max_iter : int

    Returns
    -------
    Equilibrium
        ``residual`` is the imbalance with the quasi-static lines (zero to the tolerance).
    """
    loads = np.atleast_2d(np.asarray(loads, dtype=float))
    nb = loads.shape[0]
    trim = np.asarray(model.static_load, dtype=float)
    if model.mooring_kind == "linear":
        kk = model.stiffness + model.mooring_stiffness
        q = np.linalg.solve(np.broadcast_to(kk, (nb, 6, 6)), (loads + trim)[..., None])[..., 0]
        return Equilibrium(q, loads.copy(), np.full((nb, 3), np.nan), loads + trim - _times(kk, q))
    lines = _static_lines(model)
    q = np.zeros((nb, 6))
    todo = np.arange(nb)  # each case iterates on its own: a batch gives its cases' bits alone
    for _ in range(max_iter):
        res, jac = _residual_and_jacobian(model, lines, q[todo], loads[todo] + trim)
        dq = np.linalg.solve(jac, -res[..., None])[..., 0]
        q[todo] += dq
        todo = todo[~np.all(np.abs(dq) < tol * np.maximum(1.0, np.abs(q[todo])), axis=1)]
        if todo.size == 0:
            break
    f6, ten = _line_loads(model, lines, q)
    return Equilibrium(q, loads.copy(), ten, loads + trim + f6 - _times(model.stiffness, q))


def _times(matrix: np.ndarray, q: np.ndarray) -> np.ndarray:
    """``matrix @ q`` for every row of ``q (..., 6)``, row by row (the bits do not depend on the batch)."""
    return (np.asarray(matrix, dtype=float) * q[..., None, :]).sum(axis=-1)


def _residual_and_jacobian(
    model: ModelInputs, lines: Any, q: np.ndarray, load: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Residual ``load + F_moor(q) - K q`` ``(n, 6)`` and its finite-difference Jacobian ``(n, 6, 6)``."""
    n = q.shape[0]
    pts = q[:, None, :] + np.concatenate([np.zeros((1, 6)), np.diag(_FD_STEP)])[None]
    f6, _ = _line_loads(model, lines, pts.reshape(-1, 6))
    res = load[:, None, :] + f6.reshape(n, 7, 6) - _times(model.stiffness, pts)
    return res[:, 0], ((res[:, 1:] - res[:, :1]) / _FD_STEP[None, :, None]).transpose(0, 2, 1)


def _dynamic_lines(model: ModelInputs, batch: int) -> Any:
    """The model's dynamic lines for ``batch`` cases (from the prototype), or None."""
    from moorlife import mooring as moor

    props, layout, _, proto = model.mooring_args
    if not isinstance(proto, moor.DynamicMooring):
        return None
    return moor.DynamicMooring(proto.model, props, layout, proto.settings, batch)


def mean_equilibrium(model: ModelInputs, forcing: Forcing, *, check: bool = False) -> Equilibrium:
    """The static equilibrium of each record of a batch under its mean load (:func:`mean_load`).

    With dynamic lines, the quasi-static offset is corrected by one Newton step on the dynamic
    lines' own static forces (their static shape at the offset, relaxed as the integrator
    relaxes them), with the quasi-static Jacobian.

    Parameters
    ----------
    model : ModelInputs
    forcing : Forcing
    check : bool
        With dynamic lines, also evaluate their imbalance at the corrected offset (one more
        static solve and relaxation of the lines); otherwise ``residual`` is NaN for them.

    Returns
    -------
    Equilibrium
    """
    loads = mean_load(model, forcing)
    eq = static_offsets(model, loads)
    dyn = _dynamic_lines(model, loads.shape[0]) if model.mooring_kind == "dynamic" else None
    if dyn is None:
        return eq
    trim = np.asarray(model.static_load, dtype=float)

    def dyn_residual(q: np.ndarray) -> np.ndarray:
        f6, _ = _line_loads(model, dyn, q)
        return loads + trim + f6 - _times(model.stiffness, q)

    _, jac = _residual_and_jacobian(model, _static_lines(model), eq.displacement, loads + trim)
    q = eq.displacement - np.linalg.solve(jac, dyn_residual(eq.displacement)[..., None])[..., 0]
    res = dyn_residual(q) if check else np.full_like(q, np.nan)
    return Equilibrium(q, loads, eq.tension, res)


def equilibrium_start(model: ModelInputs, forcing: Forcing) -> InitialState:
    """Every record of a batch at rest at its mean equilibrium (the default start).

    :func:`mean_equilibrium` places the platform; :func:`at_rest` sets the radiation memory and
    the rotor filter to their steady states; the integrator puts the lines in their static shape
    at the start's fairleads.

    Parameters
    ----------
    model : ModelInputs
    forcing : Forcing

    Returns
    -------
    InitialState
    """
    return at_rest(model, forcing, q0=mean_equilibrium(model, forcing).displacement)
