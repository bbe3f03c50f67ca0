"""The ``lifecycle.rbf`` configuration section as a typed record (:class:`RBFSettings`)."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from moorlife.lifecycle.outputs import DEFAULT_OUTPUTS

__all__ = ["RBFSettings", "rbf_settings"]


@dataclass(frozen=True)
class RBFSettings:
    """The ``lifecycle.rbf`` config section.

    Attributes
    ----------
    shape_mode : {"rippa", "fixed"}
    fixed_damage, fixed_tension, fixed_other : float
        Fixed ``q0`` (paper: 0.1 damage, 0.175 tension).
    grid_min, grid_max : float
    grid_n : int
        Rippa's search grid (geometric).
    share_tol : float
        See :func:`moorlife.rbf.choose_shapes`.
    log_damage : bool
        Interpolate ``log10`` of the damage outputs.
    smoothing : tuple of float
        Ridge candidates on the kernel diagonal; with several, each output takes the one with
        the smallest leave-one-out error, jointly with its shape (``(0.0,)``: exact
        interpolation, the paper's choice).
    chunk_rows : int
    outputs : tuple of str
        Variables of ``simulations.zarr`` to rebuild.
    """

    shape_mode: str = "rippa"
    fixed_damage: float = 0.1
    fixed_tension: float = 0.175
    fixed_other: float = 0.175
    grid_min: float = 0.05
    grid_max: float = 1.0
    grid_n: int = 10
    share_tol: float = 0.0
    log_damage: bool = True
    smoothing: tuple[float, ...] = (0.0,)
    chunk_rows: int = 8192
    outputs: tuple[str, ...] = DEFAULT_OUTPUTS + ("tension_mean", "surge_mean", "sway_mean")


def rbf_settings(section: Mapping[str, Any] | None = None, source: str = "config.yaml") -> RBFSettings:
    """Build :class:`RBFSettings` from ``config["lifecycle"]["rbf"]``.

    Raises
    ------
    ValueError
        Naming the key and value of an invalid setting.
    """
    s = dict(section or {})
    fixed = dict(s.get("fixed", {}))
    grid = dict(s.get("grid", {}))
    mode = str(s.get("shape", "rippa"))
    if mode not in ("rippa", "fixed"):
        raise ValueError(f"{source}: lifecycle.rbf.shape = {mode!r}; expected 'rippa' or 'fixed'")
    d = RBFSettings()
    out = RBFSettings(
        shape_mode=mode,
        fixed_damage=float(fixed.get("damage", d.fixed_damage)),
        fixed_tension=float(fixed.get("tension", d.fixed_tension)),
        fixed_other=float(fixed.get("other", d.fixed_other)),
        grid_min=float(grid.get("min", d.grid_min)),
        grid_max=float(grid.get("max", d.grid_max)),
        grid_n=int(grid.get("n", d.grid_n)),
        share_tol=float(s.get("share_tol", d.share_tol)),
        log_damage=bool(s.get("log_damage", d.log_damage)),
        smoothing=_smoothing(s.get("smoothing", d.smoothing), source),
        chunk_rows=int(s.get("chunk_rows", d.chunk_rows)),
        outputs=tuple(s.get("outputs", d.outputs)),
    )
    if not 0 < out.grid_min < out.grid_max:
        raise ValueError(f"{source}: lifecycle.rbf.grid needs 0 < min < max, got {out.grid_min}, {out.grid_max}")
    return out


def _smoothing(value: Any, source: str) -> tuple[float, ...]:
    """``lifecycle.rbf.smoothing`` as a tuple of candidates (a number or a list of numbers >= 0)."""
    vals = list(value) if isinstance(value, (list, tuple)) else [value]
    try:
        out = tuple(float(v) for v in vals)
    except (TypeError, ValueError):
        raise ValueError(f"{source}: lifecycle.rbf.smoothing = {value!r}; expected numbers >= 0") from None
    if not out or any(not (v >= 0) for v in out):
        raise ValueError(f"{source}: lifecycle.rbf.smoothing = {value!r}; expected numbers >= 0")
    return out
