"""S-N and T-N curves of chain and the ``fatigue:`` settings (:class:`FatigueSettings`)."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from moorlife.fatigue.chain import MEAN_STRESS_METHODS
from moorlife.fatigue.counting import RESIDUE_METHODS
from moorlife.fatigue.design import design_fatigue_factor
from moorlife.settings import fill_section, section_defaults

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


#: DNVGL-OS-E301 (Ch.2 Sec.2) S-N and API RP 2SK T-N curves for chain: the
#: ``fatigue.curves`` defaults of the config schema (read from it, not repeated here).
DEFAULT_CURVES: dict[str, dict[str, dict[str, float]]] = section_defaults("fatigue.curves")


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

    Build it with :meth:`from_config` (missing keys take the schema defaults).
    ``corrosion_rate`` is in m/year here (``mm/year`` in the config file).
    """

    curves: Mapping[str, Any]
    design_life: float
    corrosion_rate: float
    corrosion_step: float
    mean_stress: str
    ultimate: float
    yield_: float
    residue: str
    dnv_base: float
    dnv_threshold: float
    dnv_increment: float
    dnv_span: float
    api_factor: float
    rule_sn: str
    rule_tn: str

    @classmethod
    def from_config(cls, section: Mapping[str, Any] | None, source: str = "config.yaml") -> FatigueSettings:
        """Build from the ``fatigue:`` config section.

        Parameters
        ----------
        section : mapping or None
            ``config["fatigue"]``, possibly partial: missing keys take the schema defaults.
        source : str
            Quoted in error messages.

        Raises
        ------
        moorlife.config.ConfigError
            For an unknown key or an invalid value, naming the dotted key.
        """
        s = fill_section("fatigue", section, source)
        cor, ms, df = s["corrosion"], s["mean_stress"], s["design_factor"]
        dnv = df["dnv"]
        method = ms["method"]
        if method not in MEAN_STRESS_METHODS:
            raise ValueError(
                f"{source}: fatigue.mean_stress.method = {method!r}; expected one of {MEAN_STRESS_METHODS}"
            )
        residue = s["residue"]
        if residue not in RESIDUE_METHODS:
            raise ValueError(f"{source}: fatigue.residue = {residue!r}; expected one of {RESIDUE_METHODS}")
        curves = s["curves"]
        for chain in CHAINS:  # fail early with the key named
            try:
                get_curves(chain, curves)
            except ValueError as exc:
                raise ValueError(f"{source}: fatigue.curves: {exc}") from None
        return cls(
            curves=curves,
            design_life=float(s["design_life"]),
            corrosion_rate=float(cor["rate"]) * 1e-3,
            corrosion_step=float(cor["step"]),
            mean_stress=method,
            ultimate=float(ms["ultimate"]),
            yield_=float(ms["yield"]),
            residue=residue,
            dnv_base=float(dnv["base"]),
            dnv_threshold=float(dnv["threshold"]),
            dnv_increment=float(dnv["increment"]),
            dnv_span=float(dnv["span"]),
            api_factor=float(df["api"]),
            rule_sn=str(df["sn"]),
            rule_tn=str(df["tn"]),
        )

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
    """Alias of :meth:`FatigueSettings.from_config` (kept for its callers)."""
    return FatigueSettings.from_config(section, source)
