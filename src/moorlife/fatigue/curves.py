"""S-N and T-N curves of chain and the ``fatigue:`` settings (:class:`FatigueSettings`)."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import numpy.typing as npt

from moorlife.fatigue.chain import MEAN_STRESS_METHODS
from moorlife.fatigue.counting import RESIDUE_METHODS
from moorlife.fatigue.design import design_fatigue_factor

CHAINS = ("studless", "stud")


@dataclass(frozen=True)
class SNCurve:
    """S-N curve ``N = a_d * S**-m`` (``S`` stress range in MPa)."""

    a_d: float
    m: float

    def __post_init__(self) -> None:
        if not (self.a_d > 0 and self.m > 0):
            raise ValueError(f"S-N curve needs a_d > 0 and m > 0, got a_d={self.a_d!r}, m={self.m!r}")


@dataclass(frozen=True)
class TNCurve:
    """T-N curve ``N * (T_range / RBS)**m = k``."""

    k: float
    m: float

    def __post_init__(self) -> None:
        if not (self.k > 0 and self.m > 0):
            raise ValueError(f"T-N curve needs k > 0 and m > 0, got k={self.k!r}, m={self.m!r}")


#: DNVGL-OS-E301 (Ch.2 Sec.2) S-N and API RP 2SK T-N curves for chain; also the
#: ``fatigue.curves`` defaults of ``config/config.yaml``.
DEFAULT_CURVES: dict[str, dict[str, dict[str, float]]] = {
    "sn": {"studless": {"a_d": 6.0e10, "m": 3.0}, "stud": {"a_d": 1.2e11, "m": 3.0}},
    "tn": {"studless": {"k": 316.0, "m": 3.0}, "stud": {"k": 1000.0, "m": 3.0}},
}


def get_curves(chain: str = "studless", curves: Mapping[str, Any] | None = None) -> tuple[SNCurve, TNCurve]:
    """The S-N and T-N curves of a chain type.

    Parameters
    ----------
    chain : {"studless", "stud"}
        Chain type (column ``chain`` of ``config/mooring_systems.tsv``).
    curves : mapping, optional
        ``{"sn": {chain: {"a_d", "m"}}, "tn": {chain: {"k", "m"}}}`` as in the
        ``fatigue.curves`` config section; :data:`DEFAULT_CURVES` if omitted.

    Raises
    ------
    ValueError
        If the chain type or a curve entry is missing or invalid.
    """
    curves = DEFAULT_CURVES if curves is None else curves
    try:
        sn = curves["sn"][chain]
        tn = curves["tn"][chain]
    except KeyError as exc:
        raise ValueError(
            f"fatigue curves: no entry for chain {chain!r} ({exc.args[0]!r} missing); "
            f"available S-N: {sorted(curves.get('sn', {}))}, T-N: {sorted(curves.get('tn', {}))}"
        ) from None
    if isinstance(sn, SNCurve) and isinstance(tn, TNCurve):
        return sn, tn
    try:
        return SNCurve(float(sn["a_d"]), float(sn["m"])), TNCurve(float(tn["k"]), float(tn["m"]))
    except KeyError as exc:
        raise ValueError(f"fatigue curves for chain {chain!r}: key {exc.args[0]!r} missing") from None


@dataclass(frozen=True)
class FatigueSettings:
    """The ``fatigue:`` config section, in the units the kernels take.

    Build it with :func:`fatigue_settings`. ``corrosion_rate`` is in m/year here
    (``mm/year`` in the config file).
    """

    curves: Mapping[str, Any] = field(default_factory=lambda: DEFAULT_CURVES)
    design_life: float = 25.0
    corrosion_rate: float = 0.2e-3
    corrosion_step: float = 5.0
    mean_stress: str = "none"
    ultimate: float = 960.0
    yield_: float = 700.0
    residue: str = "half"
    dnv_base: float = 5.0
    dnv_threshold: float = 0.8
    dnv_increment: float = 3.0
    dnv_span: float = 0.2
    api_factor: float = 3.0
    rule_sn: str = "dnv"
    rule_tn: str = "api"

    def damage_kwargs(self) -> dict[str, Any]:
        """Keyword arguments of :func:`hourly_damage` (without corrosion age)."""
        return {
            "curves": self.curves,
            "mean_stress": self.mean_stress,
            "ultimate": self.ultimate,
            "yield_": self.yield_,
            "residue": self.residue,
            "corrosion_rate": self.corrosion_rate,
        }

    def design_factor(self, curve: str, damage_ratio: npt.ArrayLike = 0.0) -> np.ndarray:
        """Design fatigue factor for a curve family (``"sn"`` or ``"tn"``), see
        :func:`design_fatigue_factor`; the rule per family is ``design_factor.sn|tn``."""
        rule = {"sn": self.rule_sn, "tn": self.rule_tn}.get(curve)
        if rule is None:
            raise ValueError(f"curve must be 'sn' or 'tn', got {curve!r}")
        if rule == "api":
            return np.broadcast_to(np.float64(self.api_factor), np.shape(damage_ratio)).copy()
        return design_fatigue_factor(
            damage_ratio,
            base=self.dnv_base,
            threshold=self.dnv_threshold,
            increment=self.dnv_increment,
            span=self.dnv_span,
        )


def fatigue_settings(section: Mapping[str, Any] | None = None, source: str = "config.yaml") -> FatigueSettings:
    """Build :class:`FatigueSettings` from the ``fatigue:`` config section.

    Parameters
    ----------
    section : mapping, optional
        The validated ``config["fatigue"]`` (schema defaults filled in). Missing keys
        take the defaults of the schema.
    source : str
        Quoted in error messages.
    """
    s = dict(section or {})
    cor = dict(s.get("corrosion", {}))
    ms = dict(s.get("mean_stress", {}))
    df = dict(s.get("design_factor", {}))
    dnv = dict(df.get("dnv", {}))
    method = ms.get("method", "none")
    if method not in MEAN_STRESS_METHODS:
        raise ValueError(f"{source}: fatigue.mean_stress.method = {method!r}; expected one of {MEAN_STRESS_METHODS}")
    residue = s.get("residue", "half")
    if residue not in RESIDUE_METHODS:
        raise ValueError(f"{source}: fatigue.residue = {residue!r}; expected one of {RESIDUE_METHODS}")
    curves = s.get("curves", DEFAULT_CURVES)
    for chain in CHAINS:  # fail early with the key named
        try:
            get_curves(chain, curves)
        except ValueError as exc:
            raise ValueError(f"{source}: fatigue.curves: {exc}") from None
    return FatigueSettings(
        curves=curves,
        design_life=float(s.get("design_life", 25.0)),
        corrosion_rate=float(cor.get("rate", 0.2)) * 1e-3,
        corrosion_step=float(cor.get("step", 5.0)),
        mean_stress=method,
        ultimate=float(ms.get("ultimate", 960.0)),
        yield_=float(ms.get("yield", 700.0)),
        residue=residue,
        dnv_base=float(dnv.get("base", 5.0)),
        dnv_threshold=float(dnv.get("threshold", 0.8)),
        dnv_increment=float(dnv.get("increment", 3.0)),
        dnv_span=float(dnv.get("span", 0.2)),
        api_factor=float(df.get("api", 3.0)),
        rule_sn=str(df.get("sn", "dnv")),
        rule_tn=str(df.get("tn", "api")),
    )
