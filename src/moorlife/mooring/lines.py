"""Chain properties (paper Tables 3 and 4, R4S formulas) and the OC4 mooring layout.

Pure functions, SI units. A row of ``config/mooring_systems.tsv`` becomes a frozen
:class:`LineProperties`; the ``mooring:`` section of the study configuration becomes a
:class:`Layout` (anchor and fairlead positions) and a :class:`MooringSettings`
(hydrodynamic coefficients, seabed and numerical settings).

Conventions (see :mod:`moorlife.conventions`): global frame ``x`` east, ``y`` north, ``z`` up,
origin at the still water line on the platform centreline. Line bearings are nautical
(degrees clockwise from north) of the direction from the platform towards the anchor:
M1 30 deg (north-east), M2 270 deg (west), M3 150 deg (south-east), as OC4 lines 1-3.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from moorlife.settings import fill_section, section_defaults

__all__ = [
    "R4S_ULTIMATE_MPA",
    "R4S_YIELD_MPA",
    "DEFAULTS",
    "LineProperties",
    "Layout",
    "MooringSettings",
    "r4s_break_load",
    "r4s_proof_load",
    "chain_mass_per_length",
    "wet_weight_per_length",
    "nominal_section_area",
    "line_properties",
    "check_r4s",
    "oc4_layout",
    "mooring_settings",
    "line_angles",
]

#: R4S ultimate tensile strength and yield strength (paper Table 3), MPa.
R4S_ULTIMATE_MPA = 960.0
R4S_YIELD_MPA = 700.0

#: Defaults of the ``mooring:`` configuration section (read from the config schema).
DEFAULTS: dict[str, Any] = section_defaults("mooring")


@dataclass(frozen=True)
class LineProperties:
    """Structural and hydrostatic properties of one chain line type (SI units).

    Attributes
    ----------
    name : str
        Mooring-system id, e.g. ``"MS2"``.
    link_diameter : float
        Nominal link diameter d, m.
    equivalent_diameter : float
        Hydrodynamic (volume-equivalent) diameter, m; used for buoyancy, drag and added mass.
    mass : float
        Mass per unit length in air, kg/m.
    wet_weight : float
        Submerged weight per unit length, ``(mass - rho_w * pi/4 * D_eq**2) * g``, N/m.
    EA : float
        Axial stiffness, N.
    MBS : float
        Minimum breaking strength, N.
    pretension : float
        Published fairlead pretension at rest (paper Table 4), N.
    chain : str
        ``"studless"`` or ``"stud"``.
    """

    name: str
    link_diameter: float
    equivalent_diameter: float
    mass: float
    wet_weight: float
    EA: float
    MBS: float
    pretension: float
    chain: str

    @property
    def nominal_area(self) -> float:
        """Nominal steel section of the two link legs, ``2 * pi * d**2 / 4``, m2."""
        return float(nominal_section_area(self.link_diameter))


@dataclass(frozen=True)
class Layout:
    """Geometry of the three-line spread (global frame, m).

    Attributes
    ----------
    anchors : numpy.ndarray, shape (3, 3)
        Anchor positions ``(line, xyz)``, on the seabed ``z = -depth``.
    fairleads_body : numpy.ndarray, shape (3, 3)
        Fairlead positions ``(line, xyz)`` in the body frame (platform at rest: equal to the
        global positions).
    length : float
        Unstretched line length, m.
    depth : float
        Water depth, m.
    """

    anchors: np.ndarray
    fairleads_body: np.ndarray
    length: float
    depth: float

    @property
    def n_lines(self) -> int:
        """Number of lines."""
        return int(self.anchors.shape[0])


@dataclass(frozen=True)
class MooringSettings:
    """Environment, hydrodynamic and numerical settings of the line models.

    See the ``mooring:`` section of ``workflow/schemas/config.schema.yaml`` for each field.
    Build it with :meth:`from_config` (or :func:`mooring_settings` from a whole study config).
    """

    model: str
    n_segments: int
    water_density: float
    gravity: float
    cd_normal: float
    cd_axial: float
    ca_normal: float
    ca_axial: float
    internal_damping_ratio: float
    seabed_stiffness: float
    seabed_damping: float
    friction_coefficient: float
    friction_slip_velocity: float
    integrator: str
    max_time_step: float
    relaxation_time: float
    table_span_range: float
    table_height_range: float
    table_resolution: float

    @classmethod
    def from_config(cls, section: Mapping[str, Any] | None, source: str = "config") -> MooringSettings:
        """Build from ``config["mooring"]`` (missing keys take the schema defaults).

        Raises
        ------
        ValueError
            If a value is out of range, naming the key and value
            (:class:`moorlife.config.ConfigError` for an unknown key or a wrong type).
        """
        s = fill_section("mooring", section, source)
        if s["model"] not in ("quasistatic", "dynamic"):
            raise ValueError(f"config key 'mooring.model' = {s['model']!r} must be 'quasistatic' or 'dynamic'")
        if s["integrator"] not in ("bdf2", "ros2"):
            raise ValueError(f"config key 'mooring.integrator' = {s['integrator']!r} must be 'bdf2' or 'ros2'")
        if int(s["n_segments"]) < 2:
            raise ValueError(f"config key 'mooring.n_segments' = {s['n_segments']!r} must be at least 2")
        names = cls.__dataclass_fields__
        kw = {k: s[k] for k in names}
        for k in names:
            if k in ("model", "n_segments", "integrator"):
                continue
            kw[k] = float(kw[k])
            if kw[k] < 0 or not np.isfinite(kw[k]):
                raise ValueError(f"config key 'mooring.{k}' = {s[k]!r} must be a finite non-negative number")
        for k in ("water_density", "gravity", "max_time_step", "table_resolution", "friction_slip_velocity"):
            if kw[k] <= 0:
                raise ValueError(f"config key 'mooring.{k}' = {s[k]!r} must be positive")
        kw["n_segments"] = int(s["n_segments"])
        return cls(**kw)


def r4s_break_load(d_mm: float | np.ndarray) -> np.ndarray:
    """R4S chain minimum break load (paper Table 3), N.

    ``MBL [kN] = 0.0304 * d**2 * (44 - 0.08 * d)``, d the link diameter in mm.
    """
    d = np.asarray(d_mm, dtype=float)
    return 1e3 * 0.0304 * d**2 * (44.0 - 0.08 * d)


def r4s_proof_load(d_mm: float | np.ndarray, chain: str = "studless") -> np.ndarray:
    """R4S studless chain proof load (paper Table 3), N: ``0.0213 * d**2 * (44 - 0.08 d)`` kN."""
    if chain != "studless":
        raise ValueError(f"R4S proof load formula given for studless chain only, got chain={chain!r}")
    d = np.asarray(d_mm, dtype=float)
    return 1e3 * 0.0213 * d**2 * (44.0 - 0.08 * d)


def chain_mass_per_length(d_mm: float | np.ndarray, chain: str = "studless") -> np.ndarray:
    """Chain mass per metre in air (paper Table 3), kg/m: ``0.02 d**2`` studless, ``0.0219 d**2`` stud."""
    factors = {"studless": 0.02, "stud": 0.0219}
    if chain not in factors:
        raise ValueError(f"chain must be 'studless' or 'stud', got {chain!r}")
    return factors[chain] * np.asarray(d_mm, dtype=float) ** 2


def wet_weight_per_length(
    mass: float,
    equivalent_diameter: float,
    water_density: float = DEFAULTS["water_density"],
    gravity: float = DEFAULTS["gravity"],
) -> float:
    """Submerged weight per unit length, N/m: ``(mass - rho_w * pi / 4 * D_eq**2) * g``.

    Parameters
    ----------
    mass : float
        Mass per unit length in air, kg/m.
    equivalent_diameter : float
        Volume-equivalent diameter, m.
    water_density, gravity : float
        kg/m3 and m/s2.
    """
    return float((mass - water_density * np.pi / 4.0 * equivalent_diameter**2) * gravity)


def nominal_section_area(link_diameter: float | np.ndarray) -> np.ndarray:
    """Steel section of a chain link's two legs, ``2 * pi * d**2 / 4`` (m2 for d in m)."""
    return 2.0 * np.pi * np.asarray(link_diameter, dtype=float) ** 2 / 4.0


_ROW_KEYS = (
    "mooring_system",
    "mass_kg_per_m",
    "pretension_kN",
    "link_diameter_mm",
    "equivalent_diameter_m",
    "EA_N",
    "MBS_N",
    "chain",
)


def _positive(row: Mapping[str, Any], key: str, name: str) -> float:
    try:
        value = float(row[key])
    except (TypeError, ValueError):
        raise ValueError(f"mooring system {name!r}: column {key!r} = {row[key]!r} is not a number") from None
    if not (np.isfinite(value) and value > 0):
        raise ValueError(f"mooring system {name!r}: column {key!r} = {row[key]!r} must be a positive number")
    return value


def line_properties(
    row: Mapping[str, Any],
    water_density: float = DEFAULTS["water_density"],
    gravity: float = DEFAULTS["gravity"],
) -> LineProperties:
    """Line properties from one row of ``config/mooring_systems.tsv``.

    Parameters
    ----------
    row : mapping
        Keys ``mooring_system, mass_kg_per_m, pretension_kN, link_diameter_mm,
        equivalent_diameter_m, EA_N, MBS_N, chain`` (a ``pandas.Series`` works).
    water_density, gravity : float
        For the wet weight, kg/m3 and m/s2.

    Returns
    -------
    LineProperties
        SI units. The wet weight uses the equivalent diameter (buoyancy of the chain volume).

    Raises
    ------
    ValueError
        Naming the mooring system, column and value when a field is missing or invalid.
    """
    missing = [k for k in _ROW_KEYS if k not in row]
    name = str(row.get("mooring_system", "?"))
    if missing:
        raise ValueError(f"mooring system {name!r}: missing column(s) {missing}")
    chain = str(row["chain"])
    if chain not in ("studless", "stud"):
        raise ValueError(f"mooring system {name!r}: column 'chain' = {chain!r} must be 'studless' or 'stud'")
    mass = _positive(row, "mass_kg_per_m", name)
    deq = _positive(row, "equivalent_diameter_m", name)
    wet = wet_weight_per_length(mass, deq, water_density, gravity)
    if wet <= 0:
        raise ValueError(
            f"mooring system {name!r}: mass_kg_per_m = {mass} with equivalent_diameter_m = {deq} "
            "gives a non-positive wet weight (the line would float)"
        )
    return LineProperties(
        name=name,
        link_diameter=_positive(row, "link_diameter_mm", name) * 1e-3,
        equivalent_diameter=deq,
        mass=mass,
        wet_weight=wet,
        EA=_positive(row, "EA_N", name),
        MBS=_positive(row, "MBS_N", name),
        pretension=_positive(row, "pretension_kN", name) * 1e3,
        chain=chain,
    )


def check_r4s(props: LineProperties, rtol: float = 0.02) -> dict[str, float]:
    """Compare a line's mass and MBS with the R4S formulas of its link diameter.

    Parameters
    ----------
    props : LineProperties
    rtol : float
        Largest accepted relative difference.

    Returns
    -------
    dict
        ``{"mass": rel. difference, "MBS": rel. difference}`` (table / formula - 1).

    Raises
    ------
    ValueError
        If a difference exceeds ``rtol``, naming the system, the quantity and both values.
    """
    d_mm = props.link_diameter * 1e3
    ref = {
        "mass": float(chain_mass_per_length(d_mm, props.chain)),
        "MBS": float(r4s_break_load(d_mm)),
    }
    got = {"mass": props.mass, "MBS": props.MBS}
    out = {k: got[k] / ref[k] - 1.0 for k in ref}
    for k, rel in out.items():
        if abs(rel) > rtol:
            raise ValueError(
                f"mooring system {props.name!r}: {k} = {got[k]:.6g} differs by {100 * rel:.2f} % from the "
                f"R4S formula for d = {d_mm:g} mm ({ref[k]:.6g}); tolerance {100 * rtol:g} %"
            )
    return out


_STUDY_KEYS = frozenset({"seed", "mooring_systems", "platform", "hindcast", "selection", "simulation"})


def _raw_section(cfg: Mapping[str, Any] | None) -> Mapping[str, Any]:
    """The ``mooring`` section of a study config, or the section itself, as given."""
    if cfg is None:
        sec: Mapping[str, Any] = {}
    elif "mooring" in cfg:
        sec = cfg["mooring"] or {}
    elif set(cfg) & _STUDY_KEYS:
        sec = {}  # a study configuration without a mooring section
    else:
        sec = cfg
    return sec


def _section(cfg: Mapping[str, Any] | None) -> dict[str, Any]:
    """The ``mooring`` section (of a study config, or the section itself) over the schema defaults."""
    return fill_section("mooring", _raw_section(cfg))


def line_angles(bearings_deg: Sequence[float]) -> np.ndarray:
    """Mathematical angles (rad, counter-clockwise from ``+x``) of nautical bearings (deg)."""
    return np.deg2rad(90.0 - np.asarray(bearings_deg, dtype=float))


def oc4_layout(cfg: Mapping[str, Any] | None = None) -> Layout:
    """The OC4 three-line layout from the ``mooring:`` configuration section.

    Parameters
    ----------
    cfg : mapping, optional
        The study configuration (with a ``mooring`` key) or the ``mooring`` section itself;
        missing keys take :data:`DEFAULTS` (OC4: 3 lines at 120 deg, M2 west, fairleads at
        radius 40.868 m and 14 m below the still water line, anchors at radius 837.6 m on a
        200 m deep seabed, unstretched length 835.5 m).

    Returns
    -------
    Layout
        ``anchors (3, 3)`` and ``fairleads_body (3, 3)``; e.g. M2's anchor is at
        ``(-837.6, 0, -200)`` and M1's at ``(418.8, 725.383, -200)``.

    Raises
    ------
    ValueError
        If a value is out of range, naming the key and value.
    """
    s = _section(cfg)
    for key in ("water_depth", "line_length", "fairlead_radius", "anchor_radius"):
        if not float(s[key]) > 0:
            raise ValueError(f"config key 'mooring.{key}' = {s[key]!r} must be positive")
    depth = float(s["water_depth"])
    zf = -float(s["fairlead_depth"])
    if not -depth < zf <= 0:
        raise ValueError(f"config key 'mooring.fairlead_depth' = {s['fairlead_depth']!r} must be in [0, water_depth)")
    bearings = np.asarray(s["line_bearings"], dtype=float)
    if bearings.shape != (3,):
        raise ValueError(f"config key 'mooring.line_bearings' = {s['line_bearings']!r} must list 3 bearings")
    th = line_angles(bearings)
    u = np.stack([np.cos(th), np.sin(th), np.zeros(3)], axis=1)
    anchors = u * float(s["anchor_radius"])
    anchors[:, 2] = -depth
    fair = u * float(s["fairlead_radius"])
    fair[:, 2] = zf
    span = float(s["anchor_radius"]) - float(s["fairlead_radius"])
    if float(s["line_length"]) <= np.hypot(span, depth + zf):
        raise ValueError(
            f"config key 'mooring.line_length' = {s['line_length']!r} is not longer than the straight "
            f"anchor-fairlead distance {np.hypot(span, depth + zf):.3f} m (the line would be taut)"
        )
    anchors.setflags(write=False)
    fair.setflags(write=False)
    return Layout(anchors=anchors, fairleads_body=fair, length=float(s["line_length"]), depth=depth)


def mooring_settings(cfg: Mapping[str, Any] | None = None) -> MooringSettings:
    """Hydrodynamic, seabed and numerical settings from the ``mooring:`` section.

    Raises
    ------
    ValueError
        If a value is out of range, naming the key and value.
    """
    return MooringSettings.from_config(_raw_section(cfg))
