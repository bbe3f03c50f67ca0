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

Shapes: ``B`` sea states (batch), 3 lines (M1, M2, M3, see :data:`moorlife.names.LINES`),
3 components ``(x east, y north, z up)``. ``step`` advances the lines by ``dt`` to the instant
at which the fairleads are at ``r_fair`` with velocity ``v_fair`` and returns the forces at
that instant; the dynamic model subcycles internally (``mooring.max_time_step``). Returned
arrays are views into the state, overwritten by the next call: copy them to keep them.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any, Protocol

import numpy as np

from moorlife.mooring.dynamic import DynamicMooring, DynamicState, line_model
from moorlife.mooring.lines import (
    Layout,
    LineProperties,
    MooringSettings,
    check_r4s,
    line_properties,
    mooring_settings,
    oc4_layout,
)
from moorlife.mooring.quasistatic import ForceTable, QuasiStaticMooring, catenary, catenary_solve, force_table

__all__ = [
    "MooringModel",
    "make_mooring",
    "fairlead_positions",
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
    "QuasiStaticMooring",
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
