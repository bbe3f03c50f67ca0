"""Time integration of a batch: the coupled step loop over the forcing grid (:func:`integrate`)."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from moorlife.simulate.forcing import Forcing
from moorlife.simulate.initial import InitialState, at_rest
from moorlife.simulate.kernel import (
    Body,
    DynamicLines,
    Excitation,
    MooringLink,
    Radiation,
    Recorder,
    Rotor,
    State,
    Strips,
    _advance,
    _fairlead_motion,
    _predict_fairleads,
    _run_dynamic,
    _run_quasistatic,
)
from moorlife.simulate.linear import _free_dofs, _inverse_mass
from moorlife.simulate.model import ModelInputs

__all__ = ["Record", "integrate"]

#: Step the dynamic lines of a batch together (``moorlife.mooring.lanes``, the same bits); False
#: keeps the one-line reference step throughout (for the tests that compare the two).
LANES = True


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


def _run_compiled(moor: Any, mstate: Any, n: int, dt: float, records: tuple) -> bool:
    """Run the record in one compiled loop if ``moor`` is a known line model; ``False`` otherwise.

    ``records`` is ``(state, body, rad, strips, rotor, wave, rec)`` (:mod:`moorlife.simulate.kernel`);
    the lines are advanced by their model's compiled step (the interface of :mod:`moorlife.mooring`).
    """
    from moorlife import mooring as moor_pkg

    if type(moor) is moor_pkg.DynamicMooring:
        from moorlife.mooring import lanes

        nl = mstate.r.shape[0] * mstate.r.shape[1] if LANES else 0
        N = moor.model.n_segments
        try:
            lines = DynamicLines(mstate, moor.kernel, lanes.lane_state(nl, N), lanes.lane_work(nl, N))
            _run_dynamic(n, float(dt), moor.substeps(dt), *records, lines)
        except FloatingPointError:
            raise FloatingPointError(
                f"dynamic mooring ({moor.props.name}): non-finite fairlead tension; line state diverged (dt = {dt} s)"
            ) from None
        return True
    if type(moor) is moor_pkg.QuasiStaticMooring:
        _run_quasistatic(n, float(dt), *records, mstate, moor.anchors, moor.table)
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
    return (
        np.ascontiguousarray((ker * w[:, None])[::-1].T),
        stride,
        model.kernel_pairs[:, 0].copy(),
        model.kernel_pairs[:, 1].copy(),
    )


def _fill_history(hist: np.ndarray, past: np.ndarray, nb: int) -> None:
    """Put the velocities of the steps before ``t = 0`` (``past (B, 6, m)``, oldest first) into the
    convolution's ring buffer ``hist (stride, 6, 2 nlag, B)`` where :func:`_convolve` reads them."""
    stride, _, two_nlag, _ = hist.shape
    nlag = two_nlag // 2
    m = past.shape[2]
    if past.shape[:2] != (nb, 6) or m < stride * (nlag - 1):
        raise ValueError(f"integrate: the start's history must be ({nb}, 6, >= {stride * (nlag - 1)})")
    for k in range(m):
        j = k - m  # the step, before t = 0
        c, slot = j % stride, (j // stride) % nlag
        hist[c, :, slot, :] = past[:, :, k].T
        hist[c, :, slot + nlag, :] = past[:, :, k].T


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
    start: InitialState | None = None,
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
        Initial displacement and velocity (default: at rest at the origin), with the radiation
        memory at rest and the rotor filter at its steady state (:func:`~moorlife.simulate.initial.at_rest`).
    start : InitialState, optional
        The whole initial state instead of ``q0, v0`` (e.g.
        :func:`~moorlife.simulate.initial.equilibrium_start`). The lines always start in their
        static shape at the start's fairlead positions.
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
    if start is None:
        start = at_rest(model, forcing, q0, v0)
    elif q0 is not None or v0 is not None:
        raise ValueError("integrate: give either start or q0/v0, not both")
    nr = model.rad_a.shape[0]
    nf = model.filt_a.shape[0]
    if start.displacement.shape != (nb, 6) or start.velocity.shape != (nb, 6):
        raise ValueError(f"integrate: the start's displacement and velocity must be ({nb}, 6)")
    if start.radiation.shape != (nb, nr) or start.filter.shape != (nb, nf):
        raise ValueError(f"integrate: the start's radiation and filter states must be ({nb}, {nr}) and ({nb}, {nf})")
    # the kernels update the state in place: copies, so that the caller's start stays as given
    q, v, xr, zf = (np.array(a, dtype=float) for a in start[:4])
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
    # the verification-only linear mooring is exact: folded into the stiffness
    stiff = model.stiffness + (model.mooring_stiffness if linear else 0.0)
    coupled = not linear
    ker, stride, kpi, kpj = _kernel_at(model, dt)
    hist = np.zeros((stride, 6, 2 * ker.shape[1], nb))
    if start.history is not None and ker.shape[1]:
        _fill_history(hist, np.asarray(start.history, dtype=float), nb)
    static = np.asarray(model.static_load, dtype=float)
    state = State(
        displacement=q,
        velocity=v,
        radiation=xr,
        filter=zf,
        mooring_force=f_prev,
        held_load=fmoor6,
        acceleration=acc,
        history=hist,
        convolution=np.zeros((ker.shape[0], nb)),
        fairlead_position=r_f,
        fairlead_velocity=v_f,
    )
    body = Body(
        inverse_mass=minv, stiffness=stiff, damping=model.damping, trim_load=static, hub=model.hub, fairleads=fair
    )
    rad = Radiation(
        ss_row_start=ra[0],
        ss_column=ra[1],
        ss_value=ra[2],
        ss_input=model.rad_b,
        ss_output=model.rad_c,
        kernel=ker,
        kernel_stride=stride,
        kernel_force_dof=kpi,
        kernel_velocity_dof=kpj,
    )
    strips = Strips(
        position=np.ascontiguousarray(model.strip_pos.T),
        axis=np.ascontiguousarray(model.strip_axis.T),
        drag_normal=model.strip_cdn,
        drag_axial=model.strip_cda,
        loads=np.zeros((6, model.strip_pos.shape[0])),
    )
    rotor = Rotor(
        wind_speed=model.thrust_speed,
        thrust=model.thrust_force,
        filter_a=model.filt_a,
        filter_b=model.filt_b,
        filter_c=model.filt_c,
        filter_d=model.filt_d,
    )
    wave = Excitation(
        force=forcing.force, wind=forcing.wind, wind_dir=forcing.wind_dir, kinematics=kin, kin_every=forcing.kin_every
    )
    rec = Recorder(start=j0, motion=motion, accel=accel, tension=tension)
    records = (state, body, rad, strips, rotor, wave, rec)
    if coupled and j0 == 0:
        tension[:, :, 0] = moor.tension(mstate)
    if coupled and _run_compiled(moor, mstate, n, dt, records):
        return Record(dt=dt, motion=motion, accel=accel, tension=tension)
    link = MooringLink(coupled=coupled, forces=np.zeros((nb, 3, 3)), tension=np.zeros((nb, 3)))
    for j in range(n):
        if coupled:
            # predictor: advance the lines to the fairlead positions extrapolated to t + dt
            _predict_fairleads(q, v, fair, dt, r_f, v_f)
            f_new, mstate = moor.step(mstate, r_f, v_f, dt)  # views, used before the next step
            link = MooringLink(coupled=True, forces=f_new, tension=moor.tension(mstate))
        _advance(j, dt, state, body, rad, strips, rotor, wave, link, rec)
    if linear:
        tension[:] = np.nan
    return Record(dt=dt, motion=motion, accel=accel, tension=tension)
