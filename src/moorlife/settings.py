"""The configuration schema at run time, and the defaults of its sections.

Every default of the study configuration lives in one place, the JSON schema
``workflow/schemas/config.schema.yaml`` (shipped in the package as
``moorlife/schemas/config.schema.yaml``, a link to that file, so that installed copies and Dask
workers read the same defaults). The typed settings records of the package
(:class:`~moorlife.fatigue.FatigueSettings`, :class:`~moorlife.lifecycle.RBFSettings`,
:class:`~moorlife.metocean.SyntheticParams`, :class:`~moorlife.metocean.CleaningPolicy`,
:class:`~moorlife.mooring.MooringSettings`, :class:`SimulationSettings`,
:class:`HydroSettings`, :class:`StatisticsSettings`) are all built the same way,
``X.from_config(section)``: :func:`fill_section` validates the (possibly partial) section
against its sub-schema, fills the missing keys with the schema defaults, and the class converts
units and types. Their fields have no defaults of their own.
"""

from __future__ import annotations

import copy
import functools
from collections.abc import Mapping
from dataclasses import dataclass
from importlib.resources import files
from typing import Any

import jsonschema
import numpy as np
import yaml

from moorlife.config import fill_defaults, iter_schema_leaves, raise_first_error

__all__ = [
    "SCHEMA_RESOURCE",
    "config_schema",
    "section_schema",
    "section_defaults",
    "fill_section",
    "schema_leaf_names",
    "SimulationSettings",
    "WindSettings",
    "HydroSettings",
    "StatisticsSettings",
]

#: Location of the schema inside the package (a link to ``workflow/schemas/config.schema.yaml``).
SCHEMA_RESOURCE = "schemas/config.schema.yaml"


@functools.cache
def _schema_cached() -> dict[str, Any]:
    text = files("moorlife").joinpath(SCHEMA_RESOURCE).read_text(encoding="utf-8")
    return yaml.safe_load(text)


def config_schema() -> dict[str, Any]:
    """The study configuration's JSON schema (a deep copy; read once per process)."""
    return copy.deepcopy(_schema_cached())


def _parts(path: str) -> list[str]:
    return [p for p in path.split(".") if p]


def section_schema(path: str) -> Mapping[str, Any]:
    """The sub-schema of a dotted config section, e.g. ``"hindcast.synthetic"`` (read-only).

    Raises
    ------
    KeyError
        If the schema has no such section.
    """
    sub: Mapping[str, Any] = _schema_cached()
    for p in _parts(path):
        props = sub.get("properties", {})
        if p not in props:
            raise KeyError(f"config schema has no section '{path}' (no '{p}')")
        sub = props[p]
    return sub


def section_defaults(path: str) -> dict[str, Any]:
    """The schema defaults of a config section, filled to every depth (a fresh copy).

    ``section_defaults("fatigue")["corrosion"]["rate"]`` is ``0.2``; ``section_defaults("")``
    is the whole default configuration.
    """
    sub = section_schema(path)
    return fill_defaults(copy.deepcopy(sub.get("default", {})) if path else {}, sub)


def _plain(value: Any) -> Any:
    """Mappings to dicts, tuples to lists and numpy scalars to Python ones (for jsonschema)."""
    if isinstance(value, Mapping):
        return {k: _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if isinstance(value, np.generic):
        return value.item()
    return value


def fill_section(path: str, section: Mapping[str, Any] | None, source: str = "config") -> dict[str, Any]:
    """Validate a (possibly partial) config section and fill in its schema defaults.

    Parameters
    ----------
    path : str
        Dotted name of the section, e.g. ``"fatigue"`` or ``"lifecycle.rbf"``.
    section : mapping or None
        The section; missing keys (all of them for ``None`` or ``{}``) take the schema defaults.
    source : str
        Where the section came from, quoted in error messages.

    Returns
    -------
    dict
        A deep copy of the section with every default filled in.

    Raises
    ------
    moorlife.config.ConfigError
        For an unknown key or a wrong type or value, naming the full dotted key
        (e.g. ``hindcast.synthetic.swell.tp_bse``).
    """
    prefix = ".".join(_parts(path))
    filled = fill_defaults(_plain(section or {}), section_schema(path))
    raise_first_error(_validator(prefix), filled, source, prefix)
    return filled


@functools.cache
def _validator(path: str) -> jsonschema.Draft202012Validator:
    return jsonschema.Draft202012Validator(section_schema(path))


def schema_leaf_names() -> frozenset[str]:
    """The names (last dotted component) of every key of the schema, at every depth."""
    return frozenset(k.rsplit(".", 1)[-1] for k, _ in iter_schema_leaves(_schema_cached()))


# ----------------------------------------------------------------------------- simulation
@dataclass(frozen=True)
class WindSettings:
    """The ``simulation.wind`` config section (see the schema for each field)."""

    spectrum: str
    turbulence_intensity: float
    length_scale: float
    f_max: float

    @classmethod
    def from_config(cls, section: Mapping[str, Any] | None, source: str = "config") -> WindSettings:
        """Build from ``config["simulation"]["wind"]`` (missing keys take the schema defaults)."""
        return cls._from_filled(fill_section("simulation.wind", section, source))

    @classmethod
    def _from_filled(cls, s: Mapping[str, Any]) -> WindSettings:
        return cls(
            spectrum=str(s["spectrum"]),
            turbulence_intensity=float(s["turbulence_intensity"]),
            length_scale=float(s["length_scale"]),
            f_max=float(s["f_max"]),
        )

    def as_dict(self) -> dict[str, Any]:
        """The section as a plain mapping (what :mod:`moorlife.environment` takes)."""
        return {
            "spectrum": self.spectrum,
            "turbulence_intensity": self.turbulence_intensity,
            "length_scale": self.length_scale,
            "f_max": self.f_max,
        }


@dataclass(frozen=True)
class SimulationSettings:
    """The ``simulation:`` config section (see the schema for each field).

    ``gamma`` is the string ``"dnv"`` (DNV-RP-C205 rule) or a fixed float;
    ``extra_damping`` is a tuple of six floats.
    """

    duration: float
    transient: float
    start: str
    batch_size: int
    dt: float
    gamma: str | float
    second_order: bool
    kinematics_dt: float
    drag_strip_length: float
    radiation: str
    radiation_memory: float
    extra_damping: tuple[float, ...]
    mpm_duration: float
    keep_timeseries: bool
    wind: WindSettings

    @classmethod
    def from_config(cls, section: Mapping[str, Any] | None, source: str = "config") -> SimulationSettings:
        """Build from ``config["simulation"]`` (missing keys take the schema defaults)."""
        s = fill_section("simulation", section, source)
        g = s["gamma"]
        return cls(
            duration=float(s["duration"]),
            transient=float(s["transient"]),
            start=str(s["start"]),
            batch_size=int(s["batch_size"]),
            dt=float(s["dt"]),
            gamma=str(g) if isinstance(g, str) else float(g),
            second_order=bool(s["second_order"]),
            kinematics_dt=float(s["kinematics_dt"]),
            drag_strip_length=float(s["drag_strip_length"]),
            radiation=str(s["radiation"]),
            radiation_memory=float(s["radiation_memory"]),
            extra_damping=tuple(float(v) for v in s["extra_damping"]),
            mpm_duration=float(s["mpm_duration"]),
            keep_timeseries=bool(s["keep_timeseries"]),
            wind=WindSettings._from_filled(s["wind"]),
        )


# ---------------------------------------------------------------------------------- hydro
@dataclass(frozen=True)
class HydroSettings:
    """The ``hydro:`` config section (see the schema for each field).

    ``omega_min``, ``omega_max``, ``omega_n`` are ``hydro.omega``; the ``mesh_*`` fields are
    ``hydro.mesh``, ``panel_size`` a mapping resolution name -> panel edge in m.
    """

    source: str
    wamit_prefix: str | None
    omega_min: float
    omega_max: float
    omega_n: int
    heading_step: float
    mesh_resolution: str
    panel_size: Mapping[str, float]
    around_refinement: float
    rotational_symmetry: int | None
    mirror_symmetry: bool
    richardson: bool
    irregular_frequency_removal: bool
    kochin_directions: int
    deep_water_kh: float | None

    @classmethod
    def from_config(cls, section: Mapping[str, Any] | None, source: str = "config") -> HydroSettings:
        """Build from ``config["hydro"]`` (missing keys take the schema defaults)."""
        return cls._from_filled(fill_section("hydro", section, source))

    @classmethod
    def _from_filled(cls, s: Mapping[str, Any]) -> HydroSettings:
        om, mesh = s["omega"], s["mesh"]
        sym = mesh["rotational_symmetry"]
        return cls(
            source=str(s["source"]),
            wamit_prefix=None if s["wamit_prefix"] is None else str(s["wamit_prefix"]),
            omega_min=float(om["min"]),
            omega_max=float(om["max"]),
            omega_n=int(om["n"]),
            heading_step=float(s["heading_step"]),
            mesh_resolution=str(mesh["resolution"]),
            panel_size={str(k): float(v) for k, v in mesh["panel_size"].items()},
            around_refinement=float(mesh["around_refinement"]),
            rotational_symmetry=None if sym is None else int(sym),
            mirror_symmetry=bool(mesh["mirror_symmetry"]),
            richardson=bool(mesh["richardson"]),
            irregular_frequency_removal=bool(s["irregular_frequency_removal"]),
            kochin_directions=int(s["kochin_directions"]),
            deep_water_kh=None if s["deep_water_kh"] is None else float(s["deep_water_kh"]),
        )


# ----------------------------------------------------------------------------- statistics
@dataclass(frozen=True)
class StatisticsSettings:
    """The ``statistics:`` config section: GEV ``block`` length in s and estimator ``method``."""

    block: float
    method: str

    @classmethod
    def from_config(cls, section: Mapping[str, Any] | None, source: str = "config") -> StatisticsSettings:
        """Build from ``config["statistics"]`` (missing keys take the schema defaults)."""
        s = fill_section("statistics", section, source)
        return cls(block=float(s["block"]), method=str(s["method"]))
