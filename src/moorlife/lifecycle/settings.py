"""The ``lifecycle.rbf`` configuration section as a typed record (:class:`RBFSettings`)."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from moorlife import names
from moorlife.settings import fill_section

__all__ = ["GPBounds", "GPSettings", "RBFSettings", "rbf_settings"]


@dataclass(frozen=True)
class GPBounds:
    """Start and bounds of one GP hyperparameter (``lifecycle.rbf.gp.length_scale`` etc.)."""

    initial: float
    min: float
    max: float

    def astuple(self) -> tuple[float, float, float]:
        """``(initial, min, max)``, as :func:`moorlife.gp.fit_gp` takes them."""
        return (self.initial, self.min, self.max)


@dataclass(frozen=True)
class GPSettings:
    """The ``lifecycle.rbf.gp`` config section (the Gaussian process of ``method: gp``).

    Attributes
    ----------
    kernel : {"ard", "isotropic"}
    covariance : {"gaussian", "matern52", "matern32"}
        The correlation family (:mod:`moorlife.gp.covariance`).
    length_scale, signal, noise : GPBounds
        Start and bounds of each hyperparameter (:func:`moorlife.gp.fit_gp`).
    restarts, seed, subsample : int
    thrust : bool
        Add the rotor thrust ``T(W)`` as an input coordinate.
    retransform : {"none", "noise", "predictive"}
        Back-transform of ``log10`` outputs (:mod:`moorlife.gp`).
    indicator : {"loo", "sd"}
        Error indicator (:func:`moorlife.lifecycle.error_indicator`).
    share : {"none", "variable", "all"}
        Outputs that share their hyperparameters (:func:`moorlife.gp.fit_gp`'s ``groups``).
    mean : {"constant", "linear"}
        The prior mean (:func:`moorlife.gp.fit_gp`'s ``prior_mean``).
    wind_term : {"none", "damage", "all"}
        The outputs with an additive term of the wind speed and direction
        (:func:`moorlife.gp.fit_gp`'s ``additive_columns``).
    wind_gate : GPBounds
        Start and bounds of the term's sea-gate scale (:func:`moorlife.gp.fit_gp`'s ``gate_scale``).
    wind_subsample : int
        Training states of the hyperparameter fit of the outputs with the term (0: all).
    wind_start : {"joint", "warm", "frozen"}
        How they start that fit (:func:`moorlife.gp.fit_gp`'s ``additive_start``).
    """

    kernel: str
    covariance: str
    length_scale: GPBounds
    signal: GPBounds
    noise: GPBounds
    restarts: int
    seed: int
    subsample: int
    thrust: bool
    retransform: str
    indicator: str
    share: str
    mean: str
    wind_term: str
    wind_gate: GPBounds
    wind_subsample: int
    wind_start: str

    @classmethod
    def from_section(cls, g: Mapping[str, Any], source: str = "config.yaml") -> GPSettings:
        """Build from the filled ``lifecycle.rbf.gp`` section.

        Raises
        ------
        ValueError
            If a hyperparameter's ``initial`` is outside ``[min, max]``, or ``wind_term: damage``
            is asked with ``share: all`` (one group cannot mix outputs with and without the term).
        """
        triples = {}
        for key in ("length_scale", "signal", "noise", "wind_gate"):
            t = GPBounds(float(g[key]["initial"]), float(g[key]["min"]), float(g[key]["max"]))
            if not t.min <= t.initial <= t.max:
                raise ValueError(f"{source}: lifecycle.rbf.gp.{key} needs min <= initial <= max, got {g[key]}")
            triples[key] = t
        return cls(
            kernel=str(g["kernel"]),
            covariance=str(g["covariance"]),
            length_scale=triples["length_scale"],
            signal=triples["signal"],
            noise=triples["noise"],
            restarts=int(g["restarts"]),
            seed=int(g["seed"]),
            subsample=int(g["subsample"]),
            thrust=bool(g["thrust"]),
            retransform=str(g["retransform"]),
            indicator=str(g["indicator"]),
            share=str(g["share"]),
            mean=str(g["mean"]),
            wind_term=_wind_term(g, source),
            wind_gate=triples["wind_gate"],
            wind_subsample=int(g["wind_subsample"]),
            wind_start=str(g["wind_start"]),
        )


def _wind_term(g: Mapping[str, Any], source: str) -> str:
    term = str(g["wind_term"])
    if term == "damage" and str(g["share"]) == "all":
        raise ValueError(
            f"{source}: lifecycle.rbf.gp.wind_term = 'damage' with share = 'all': one hyperparameter "
            "group cannot mix outputs with and without the wind term (use share none or variable, or wind_term all)"
        )
    return term


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
    choose : {"global", "per_output", "stack"}
        ``global``: the paper's 5-D space for every output, damage by ``log_damage``;
        ``per_output``: space, transform, ``q0`` and smoothing per output by the leave-one-out
        error in the output's units (:func:`moorlife.rbf.choose_per_output`); with ``method:
        gp``, the space only (one GP per candidate, :func:`moorlife.lifecycle.fit_outputs`).
        ``stack`` (``method: gp``): a blend of the GPs of both ``spaces`` per output, weighted by
        the leave-one-out error (:func:`moorlife.lifecycle.stack_weights`).
    stack_resamples, stack_seed : int
        ``choose: stack``: 0, the weight of the smallest leave-one-out error on all training
        states; N > 0, its mean over N bootstrap resamples of them, seeded by ``stack_seed``
        (:func:`moorlife.lifecycle.stack_weights`).
    space : str
        Input space of ``global`` (``names.RBF_SPACES``; ``"paper"``: the paper's method).
    spaces : tuple of str
        Candidate input spaces of ``per_output`` (``names.RBF_SPACES``; with ``method: gp``,
        ``"paper"`` and ``"thrust"`` only).
    thrust_statistic : {"steady", "turbulent_sd"}
        The thrust coordinate of the ``"thrust"`` space: ``T(W)`` or the turbulent thrust
        (:mod:`moorlife.lifecycle.turbulence`).
    thrust_averaging_time : float
        s, the hindcast's averaging time: the turbulence of ``turbulent_sd`` is above its inverse.
    weights : tuple of float
        Weight of each coordinate of the ``"weighted"`` space, ``names.METOCEAN_VARS`` order
        (1 on the directions).
    trend_knots : tuple of float
        Knots (m/s) of the wind-speed trend of the ``"wind_trend"`` space, strictly increasing.
    trend_harmonics : int
        Harmonics of the wind direction multiplying each hinge of that trend.
    transforms, damage_transforms : tuple of str
        Candidate transforms of ``per_output`` (``names.RBF_TRANSFORMS``) of the outputs other
        than the damage, and of the damage.
    retransform : {"none", "smearing", "ratio"}
        Back-transform correction of the ``log10`` outputs (:mod:`moorlife.rbf.transform`).
    chunk_rows : int
    outputs : tuple of str
        Variables of ``simulations.zarr`` to rebuild.
    method : {"rbf", "gp"}
        The RBF (the paper's) or the Gaussian process of ``gp``.
    gp : GPSettings
    """

    shape_mode: str
    fixed_damage: float
    fixed_tension: float
    fixed_other: float
    grid_min: float
    grid_max: float
    grid_n: int
    share_tol: float
    log_damage: bool
    smoothing: tuple[float, ...]
    choose: str
    stack_resamples: int
    stack_seed: int
    space: str
    spaces: tuple[str, ...]
    thrust_statistic: str
    thrust_averaging_time: float
    weights: tuple[float, ...]
    trend_knots: tuple[float, ...]
    trend_harmonics: int
    transforms: tuple[str, ...]
    damage_transforms: tuple[str, ...]
    retransform: str
    chunk_rows: int
    outputs: tuple[str, ...]
    method: str
    gp: GPSettings

    @classmethod
    def from_config(cls, section: Mapping[str, Any] | None, source: str = "config.yaml") -> RBFSettings:
        """Build from ``config["lifecycle"]["rbf"]`` (missing keys take the schema defaults).

        Raises
        ------
        ValueError
            Naming the key and value of an invalid setting (:class:`moorlife.config.ConfigError`
            for an unknown key or a value the schema refuses).
        """
        s = fill_section("lifecycle.rbf", section, source)
        fixed, grid = s["fixed"], s["grid"]
        mode = str(s["shape"])
        if mode not in ("rippa", "fixed"):
            raise ValueError(f"{source}: lifecycle.rbf.shape = {mode!r}; expected 'rippa' or 'fixed'")
        out = cls(
            shape_mode=mode,
            fixed_damage=float(fixed["damage"]),
            fixed_tension=float(fixed["tension"]),
            fixed_other=float(fixed["other"]),
            grid_min=float(grid["min"]),
            grid_max=float(grid["max"]),
            grid_n=int(grid["n"]),
            share_tol=float(s["share_tol"]),
            log_damage=bool(s["log_damage"]),
            smoothing=_smoothing(s["smoothing"], source),
            choose=str(s["choose"]),
            stack_resamples=int(s["stack"]["resamples"]),
            stack_seed=int(s["stack"]["seed"]),
            space=str(s["space"]),
            spaces=tuple(str(v) for v in s["spaces"]),
            thrust_statistic=str(s["thrust"]["statistic"]),
            thrust_averaging_time=float(s["thrust"]["averaging_time"]),
            weights=tuple(1.0 if v in names.DIRECTION_VARS else float(s["weights"][v]) for v in names.METOCEAN_VARS),
            trend_knots=tuple(float(v) for v in s["wind_trend"]["knots"]),
            trend_harmonics=int(s["wind_trend"]["harmonics"]),
            transforms=tuple(str(v) for v in s["transforms"]),
            damage_transforms=tuple(str(v) for v in s["damage_transforms"]),
            retransform=str(s["retransform"]),
            chunk_rows=int(s["chunk_rows"]),
            outputs=tuple(s["outputs"]),
            method=str(s["method"]),
            gp=GPSettings.from_section(s["gp"], source),
        )
        if out.method == "gp" and out.space != names.RBF_SPACE_PAPER:
            raise ValueError(
                f"{source}: lifecycle.rbf.space = {out.space!r} with method 'gp'; the GP's space is set by gp.thrust"
            )
        gp_spaces = (names.RBF_SPACE_PAPER, names.RBF_SPACE_THRUST)
        if out.choose == "stack" and out.method != "gp":
            raise ValueError(
                f"{source}: lifecycle.rbf.choose = 'stack' with method {out.method!r}; the blend is the GP's (method: gp)"
            )
        if out.stack_resamples and out.choose != "stack":
            raise ValueError(
                f"{source}: lifecycle.rbf.stack.resamples = {out.stack_resamples} with choose = {out.choose!r}; "
                "the resampled weights are the blend's (choose: stack)"
            )
        if out.method == "gp" and out.choose in ("per_output", "stack"):
            if out.gp.thrust:
                raise ValueError(
                    f"{source}: lifecycle.rbf.gp.thrust = true with choose = {out.choose!r}; "
                    "the per-output choice takes its spaces from lifecycle.rbf.spaces"
                )
            bad = [v for v in out.spaces if v not in gp_spaces]
            if bad:
                raise ValueError(
                    f"{source}: lifecycle.rbf.spaces = {list(out.spaces)} with method 'gp'; "
                    f"the GP's candidates are {list(gp_spaces)}, not {bad}"
                )
        g = out.gp
        if g.mean == "linear" and (g.retransform == "predictive" or g.indicator == "sd"):
            raise ValueError(
                f"{source}: lifecycle.rbf.gp.mean = 'linear' has no latent variance, so it cannot go with "
                f"gp.retransform = {g.retransform!r} and gp.indicator = {g.indicator!r} (use noise or none, and loo)"
            )
        knots = out.trend_knots
        if any(not b > a for a, b in zip(knots, knots[1:])):
            raise ValueError(f"{source}: lifecycle.rbf.wind_trend.knots = {list(knots)}; expected strictly increasing")
        if not 0 < out.grid_min < out.grid_max:
            raise ValueError(f"{source}: lifecycle.rbf.grid needs 0 < min < max, got {out.grid_min}, {out.grid_max}")
        return out


def rbf_settings(section: Mapping[str, Any] | None = None, source: str = "config.yaml") -> RBFSettings:
    """Alias of :meth:`RBFSettings.from_config` (kept for its callers)."""
    return RBFSettings.from_config(section, source)


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
