"""Model inputs of the coupled simulator: :class:`ModelInputs` and :func:`build_model`."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from moorlife import environment as env

__all__ = ["ModelInputs", "build_model"]


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
    static_mooring : object or None
        The quasi-static model of the same lines (a ``moorlife.mooring.QuasiStaticMooring``),
        for the static equilibria of :mod:`moorlife.simulate.initial`; None: built when needed.
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
    static_mooring: Any = None


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
    scalars = (
        "mooring_kind",
        "mooring_args",
        "static_mooring",
        "line_info",
        "depth",
        "rho",
        "gravity",
        "kernel_dt",
        "kernel_pairs",
    )
    arrays = {
        k: (np.asarray(v, dtype=complex if k == "excitation" else float) if k not in scalars else v)
        for k, v in kw.items()
    }
    if "kernel_pairs" in arrays:
        arrays["kernel_pairs"] = np.asarray(arrays["kernel_pairs"], dtype=np.int64).reshape(-1, 2)
    m = ModelInputs(**arrays)
    for key, shape in (("mass", (6, 6)), ("stiffness", (6, 6)), ("damping", (6, 6))):
        if getattr(m, key).shape != shape:
            raise ValueError(f"ModelInputs.{key}: expected shape {shape}, got {getattr(m, key).shape}")
    nr = m.rad_a.shape[0]
    if m.rad_b.shape != (nr, 6) or m.rad_c.shape != (6, nr):
        raise ValueError(
            f"radiation state space: inconsistent shapes {m.rad_a.shape}, {m.rad_b.shape}, {m.rad_c.shape}"
        )
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
