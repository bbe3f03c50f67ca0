"""Mooring lines: properties, quasi-static catenary and dynamic lumped-mass models.

One interface for both models, "fairlead positions and velocities in, forces out"::

    from moorlife.mooring import make_mooring, line_properties, oc4_layout
    props = line_properties(row)                 # one row of config/mooring_systems.tsv
    layout = oc4_layout(config)                  # anchors (3, 3), fairleads_body (3, 3)
    model = make_mooring("dynamic", props, layout, config, batch=B)
    state = model.init(r_fair)                   # r_fair (B, 3, 3): fairlead positions, m
    for each platform step:
        forces, state = model.step(state, r_fair, v_fair, dt)
        # forces (B, 3, 3): force of each line ON THE PLATFORM at its fairlead, N, global frame
        tension = model.tension(state)           # (B, 3) fairlead tension magnitude, N

Both models also have ``model.forces(state)`` (the last forces, ``(B, 3, 3)``); the simulator
may rebuild a model for another batch size from a prototype without recomputing the force
table or the line parameters: ``QuasiStaticMooring(proto.table, layout, batch)`` and
``DynamicMooring(proto.model, props, layout, proto.settings, batch)``. Helpers:
:func:`fairlead_kinematics` (fairlead positions and velocities of a rigid 6-DOF platform) and
:func:`mooring_loads` (force and moment about a point).

Shapes: ``B`` sea states (batch), 3 lines (M1, M2, M3, see :data:`moorlife.names.LINES`),
3 components ``(x east, y north, z up)``. ``step`` advances the lines by ``dt`` to the instant
at which the fairleads are at ``r_fair`` with velocity ``v_fair`` and returns the forces at
that instant; the dynamic model subcycles internally (``mooring.max_time_step``). Returned
arrays are views into the state, overwritten by the next call: copy them to keep them.

Compiled steps. Each model also has a public Numba-compiled step, which a compiled caller
(the simulator's record loop, :mod:`moorlife.simulate.kernel`) calls once per platform step
instead of ``model.step``; the states are records (``typing.NamedTuple``) that compiled code
takes as they are, and the step updates them in place (``state.forces (B, L, 3)``,
``state.tension (B, L)``)::

    dynamic.step_lines(state, r_fair, v_fair, dt, model.substeps(dt), model.kernel)
        # state: DynamicState from DynamicMooring.init; model.kernel: LineKernel
    quasistatic.step_lines(state, r_fair, model.anchors, model.table)
        # state: QuasiStaticState from QuasiStaticMooring.init; model.table: ForceTable

They are the same computation as ``model.step`` (which calls them), bit for bit; the
dynamic step raises ``FloatingPointError`` on a non-finite tension.

The fast path of the dynamic step steps every line of a batch at once, the lines as the lanes of
vectors in blocks of ``lanes.W`` (:mod:`moorlife.mooring.lanes`, BDF2 once its history is started)::

    lanes.pack(state, ls)                        # ls = lanes.lane_state(B * L, N)
    lanes.step_lanes(ls, r_fair, v_fair, dt, nsub, model.model.params, work, forces, tension)
    lanes.unpack(ls, state)

It gives the bits of ``dynamic.step_lines``, which stays as its strict reference.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any, Protocol

import numpy as np

from moorlife.mooring import dynamic, lanes, quasistatic
from moorlife.mooring.dynamic import DynamicMooring, DynamicState, LineKernel, line_model
from moorlife.mooring.lines import (
    Layout,
    LineProperties,
    MooringSettings,
    check_r4s,
    line_properties,
    mooring_settings,
    oc4_layout,
)
from moorlife.mooring.quasistatic import (
    ForceTable,
    QuasiStaticMooring,
    QuasiStaticState,
    catenary,
    catenary_solve,
    force_table,
)

__all__ = [
    "MooringModel",
    "make_mooring",
    "fairlead_positions",
    "fairlead_kinematics",
    "mooring_loads",
    "rotation_matrix",
    "line_properties",
    "check_r4s",
    "oc4_layout",
    "mooring_settings",
    "catenary",
    "catenary_solve",
    "force_table",
    "Layout",
    "LineProperties",
    "MooringSettings",
    "ForceTable",
    "DynamicMooring",
    "DynamicState",
    "LineKernel",
    "QuasiStaticMooring",
    "QuasiStaticState",
    "dynamic",
    "lanes",
    "quasistatic",
]


class MooringModel(Protocol):
    """What the simulator needs from a mooring model."""

    kind: str

    def init(self, r_fair: np.ndarray) -> Any:
        """State for fairlead positions ``(B, L, 3)``."""

    def step(self, state: Any, r_fair: np.ndarray, v_fair: np.ndarray, dt: float) -> tuple[np.ndarray, Any]:
        """Forces ``(B, L, 3)`` on the platform after advancing by ``dt``, and the state."""

    def tension(self, state: Any) -> np.ndarray:
        """Fairlead tension magnitude ``(B, L)``."""


def make_mooring(
    kind: str | None, props: LineProperties, layout: Layout, cfg: Mapping[str, Any] | None = None, batch: int = 1
) -> MooringModel:
    """Build the quasi-static or dynamic mooring model of one line type.

    Parameters
    ----------
    kind : {"quasistatic", "dynamic"} or None
        None takes ``mooring.model`` from the configuration.
    props : LineProperties
        The chain (all lines of a system share it).
    layout : Layout
        Anchors and fairleads.
    cfg : mapping, optional
        The study configuration (or its ``mooring`` section); defaults if None.
    batch : int
        Number of sea states integrated together.

    Raises
    ------
    ValueError
        For an unknown ``kind``.
    """
    settings = mooring_settings(cfg)
    kind = settings.model if kind is None else kind
    if kind == "quasistatic":
        return QuasiStaticMooring(force_table(props, layout, settings), layout, batch)
    if kind == "dynamic":
        return DynamicMooring(line_model(props, layout, settings), props, layout, settings, batch)
    raise ValueError(f"mooring model kind {kind!r} must be 'quasistatic' or 'dynamic'")


def fairlead_positions(layout: Layout, offset: np.ndarray) -> np.ndarray:
    """Fairlead positions ``(B, L, 3)`` for rigid translations ``offset (B, 3)`` of the platform (m)."""
    offset = np.atleast_2d(np.asarray(offset, dtype=float))
    return layout.fairleads_body[None, :, :] + offset[:, None, :]


def rotation_matrix(angles: np.ndarray) -> np.ndarray:
    """Rotation matrices ``(B, 3, 3)`` of roll, pitch, yaw ``(B, 3)`` (rad), ``R = Rz Ry Rx``."""
    a = np.atleast_2d(np.asarray(angles, dtype=float))
    cr, sr = np.cos(a[:, 0]), np.sin(a[:, 0])
    cp, sp = np.cos(a[:, 1]), np.sin(a[:, 1])
    cy, sy = np.cos(a[:, 2]), np.sin(a[:, 2])
    R = np.empty((a.shape[0], 3, 3))
    R[:, 0, 0] = cy * cp
    R[:, 0, 1] = cy * sp * sr - sy * cr
    R[:, 0, 2] = cy * sp * cr + sy * sr
    R[:, 1, 0] = sy * cp
    R[:, 1, 1] = sy * sp * sr + cy * cr
    R[:, 1, 2] = sy * sp * cr - cy * sr
    R[:, 2, 0] = -sp
    R[:, 2, 1] = cp * sr
    R[:, 2, 2] = cp * cr
    return R


def fairlead_kinematics(layout: Layout, pose: np.ndarray, velocity: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Fairlead positions and velocities of a rigid platform.

    Parameters
    ----------
    layout : Layout
    pose : numpy.ndarray, shape (B, 6)
        Surge, sway, heave (m) of the body origin (still water line on the centreline) and
        roll, pitch, yaw (rad), ``R = Rz(yaw) Ry(pitch) Rx(roll)``.
    velocity : numpy.ndarray, shape (B, 6)
        Translational (m/s) and angular (rad/s, global frame) velocity.

    Returns
    -------
    r_fair, v_fair : numpy.ndarray, shape (B, L, 3)
        ``x + R p`` and ``v + omega x (R p)`` for the body-frame fairleads ``p``.
    """
    pose = np.atleast_2d(np.asarray(pose, dtype=float))
    velocity = np.atleast_2d(np.asarray(velocity, dtype=float))
    arm = np.einsum("bij,lj->bli", rotation_matrix(pose[:, 3:]), layout.fairleads_body)
    r = pose[:, None, :3] + arm
    v = velocity[:, None, :3] + np.cross(velocity[:, None, 3:], arm)
    return r, v


def mooring_loads(forces: np.ndarray, r_fair: np.ndarray, reference: np.ndarray) -> np.ndarray:
    """Total mooring force and moment on the platform about a reference point.

    Parameters
    ----------
    forces : numpy.ndarray, shape (B, L, 3)
        Line forces on the platform at the fairleads, N.
    r_fair : numpy.ndarray, shape (B, L, 3)
        Fairlead positions, m.
    reference : numpy.ndarray, shape (B, 3)
        Point about which moments are taken (e.g. the body origin), m.

    Returns
    -------
    numpy.ndarray, shape (B, 6)
        ``Fx, Fy, Fz`` (N) and ``Mx, My, Mz`` (N m), global frame.
    """
    arm = r_fair - np.asarray(reference, dtype=float)[:, None, :]
    return np.concatenate([forces.sum(axis=1), np.cross(arm, forces).sum(axis=1)], axis=1)
