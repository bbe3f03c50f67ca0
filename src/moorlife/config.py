"""Configuration validation against the JSON schema, and config fingerprints.

Pure functions: dictionaries in, dictionaries out. Reading the YAML files is done in
:mod:`moorlife.io`.
"""

from __future__ import annotations

import copy
import hashlib
import json
import math
from collections.abc import Iterator, Mapping
from typing import Any

import jsonschema

__all__ = [
    "ConfigError",
    "fill_defaults",
    "raise_first_error",
    "validate_config",
    "check_cross_keys",
    "check_against_table",
    "STEPS_PER_PERIOD",
    "KINEMATICS_PER_PERIOD",
    "MIN_BLOCKS",
    "undocumented_keys",
    "iter_schema_leaves",
    "fingerprint",
    "deep_merge",
    "schema_table",
]


class ConfigError(ValueError):
    """A configuration value is invalid; the message names the file, key and value."""


def _key_parts(error: jsonschema.ValidationError) -> list[str]:
    """The dotted path of the offending key, relative to the validated instance."""
    parts = [str(p) for p in error.absolute_path]
    if error.validator == "additionalProperties":
        # the offending key is in the message, not in the path
        extra = sorted(set(error.instance) - set(error.schema.get("properties", {})))
        parts.append(extra[0] if extra else "?")
    elif error.validator == "required":
        missing = [r for r in error.validator_value if r not in error.instance]
        parts.append(missing[0] if missing else "?")
    return parts


def raise_first_error(validator: jsonschema.Validator, instance: Any, source: str, prefix: str = "") -> None:
    """Raise :class:`ConfigError` for the first (deepest) violation of ``instance``, if any.

    The message names ``source``, the dotted key (``prefix`` before the key of a validated
    section, e.g. ``"hindcast.synthetic"``), the value and the rule.
    """
    errors = sorted(validator.iter_errors(instance), key=lambda e: (-len(e.absolute_path), str(e.path)))
    if not errors:
        return
    err = errors[0]
    key = ".".join([prefix, *_key_parts(err)] if prefix else _key_parts(err)) or "<root>"
    if err.validator == "additionalProperties":
        raise ConfigError(f"{source}: unknown config key '{key}' (not in the schema; check its spelling)")
    if err.validator == "required":
        raise ConfigError(f"{source}: config key '{key}' is required")
    raise ConfigError(f"{source}: config key '{key}' = {err.instance!r} is invalid: {err.message}")


def fill_defaults(instance: Any, schema: Mapping[str, Any]) -> Any:
    """Fill, in place and at every depth, the keys of ``instance`` missing from ``schema``'s defaults."""
    if schema.get("type") == "object" and isinstance(instance, dict):
        for name, sub in schema.get("properties", {}).items():
            if name not in instance and "default" in sub:
                instance[name] = copy.deepcopy(sub["default"])
            if name in instance:
                instance[name] = fill_defaults(instance[name], sub)
    return instance


def validate_config(config: Mapping[str, Any], schema: Mapping[str, Any], source: str = "config") -> dict[str, Any]:
    """Validate a configuration and fill in the schema defaults.

    Parameters
    ----------
    config : mapping
        The merged configuration (``config.yaml`` plus any overlay).
    schema : mapping
        The JSON schema (``workflow/schemas/config.schema.yaml``).
    source : str
        Where the configuration came from, quoted in error messages.

    Returns
    -------
    dict
        A deep copy of ``config`` with every default filled in.

    Raises
    ------
    ConfigError
        On the first (deepest) violation, naming the dotted key, the value and the rule.
    """
    filled = fill_defaults(copy.deepcopy(dict(config)), schema)
    raise_first_error(jsonschema.Draft202012Validator(schema), filled, source)
    check_cross_keys(filled, source)
    return filled


#: Integration steps per shortest wave period (classical RK4 on the platform): 10 keeps the
#: phase error of an undamped oscillator at omega dt = 2 pi / 10 below 1e-4 per period and the
#: amplitude error below 1e-3; dt = 1 s (2.5 steps per 2.5 s wave) moved damage by 0.45-2.6x.
STEPS_PER_PERIOD: int = 10
#: Samples of the wave kinematics per shortest wave period (linear interpolation in between):
#: 8 keeps the interpolation error of the shortest component below (pi / 8)^2 / 2 = 7.7 %.
KINEMATICS_PER_PERIOD: int = 8
#: Blocks per record a GEV fit of block maxima needs (moorlife.stats.MIN_BLOCKS).
MIN_BLOCKS: int = 5


def _get(cfg: Mapping[str, Any], key: str) -> Any:
    node: Any = cfg
    for part in key.split("."):
        if not isinstance(node, Mapping) or part not in node:
            return None
        node = node[part]
    return node


def _timestamp(cfg: Mapping[str, Any], key: str, source: str) -> Any:
    import pandas as pd

    value = _get(cfg, key)
    try:
        t = pd.Timestamp(value)
    except (ValueError, TypeError):
        t = pd.NaT
    if t is pd.NaT:
        raise ConfigError(f"{source}: config key '{key}' = {value!r} is not an ISO 8601 time (e.g. '2000-01-01T00:00')")
    if t.tzinfo is not None:
        t = t.tz_convert("UTC").tz_localize(None)
    if t != t.floor("h"):
        raise ConfigError(f"{source}: config key '{key}' = {value!r} is not on a whole hour (the hindcast is hourly)")
    return t


def check_cross_keys(cfg: Mapping[str, Any], source: str = "config") -> None:
    """Every check that needs the configuration only, beyond the schema (run before any job).

    * ``hindcast.start``/``end``: ISO 8601 times on whole hours, end not before start; the
      period holds at least ``selection.n_train + selection.n_validate`` hours; a file source
      names ``hindcast.path``; the sensitivity sea state is below the breaking steepness.
    * ``lifecycle.adaptive.rounds`` x ``per_round`` is below ``selection.n_train`` (the total of
      training simulations, of which maximum dissimilarity picks the rest), and so is that plus
      ``lifecycle.replicates.states`` x ``seeds``; replicates need ``damage_sn`` among
      ``lifecycle.rbf.outputs`` (their ranking).
    * ``lifecycle.rbf.thrust.statistic: turbulent_sd`` has a turbulent wind
      (``simulation.wind.spectrum`` not ``none``) above ``1 / lifecycle.rbf.thrust.averaging_time``
      and below ``simulation.wind.f_max``.
    * ``simulation.dt`` resolves the shortest wave period ``2 pi / hydro.omega.max`` with
      :data:`STEPS_PER_PERIOD` steps; ``simulation.kinematics_dt``, as the simulator rounds it
      (to a whole number of steps, at least one), samples that period
      :data:`KINEMATICS_PER_PERIOD` times. (A WAMIT source is checked against its own
      frequencies by the simulator only.)
    * ``statistics.block`` is at least two steps and the kept record ``simulation.duration``
      holds :data:`MIN_BLOCKS` blocks.
    * Lower/upper pairs are ordered (``hydro.omega``, ``lifecycle.rbf.grid``, the synthetic Tp
      clip); class edges of ``selection.discrete`` increase; ``hydro.heading_step`` and
      ``selection.discrete.direction_sector`` divide 360; ``hydro.wamit_prefix`` is set for a
      WAMIT source; the synthetic generator's per-regime and per-direction lists have equal
      lengths.

    Raises
    ------
    ConfigError
        Naming the source, the key(s) and the value(s).
    """

    def fail(msg: str) -> None:
        raise ConfigError(f"{source}: {msg}")

    # ------------------------------------------------------------------ the study period
    if _get(cfg, "hindcast.start") is not None and _get(cfg, "hindcast.end") is not None:
        t0 = _timestamp(cfg, "hindcast.start", source)
        t1 = _timestamp(cfg, "hindcast.end", source)
        if t1 < t0:
            fail(
                f"config key 'hindcast.end' = {_get(cfg, 'hindcast.end')!r} is before 'hindcast.start' = "
                f"{_get(cfg, 'hindcast.start')!r}"
            )
        hours = int((t1 - t0) / _hour()) + 1
        n_tr, n_va = _get(cfg, "selection.n_train"), _get(cfg, "selection.n_validate")
        if isinstance(n_tr, int) and isinstance(n_va, int) and n_tr + n_va > hours:
            fail(
                f"config keys 'selection.n_train' = {n_tr} + 'selection.n_validate' = {n_va} sea states exceed the "
                f"{hours} hour(s) of the study period hindcast.start .. hindcast.end"
            )
    n_tr = _get(cfg, "selection.n_train")
    k, n = _get(cfg, "lifecycle.adaptive.rounds"), _get(cfg, "lifecycle.adaptive.per_round")
    if all(isinstance(v, int) for v in (n_tr, k, n)) and k > 0 and k * n >= n_tr:
        fail(
            f"config keys 'lifecycle.adaptive.rounds' = {k} x 'lifecycle.adaptive.per_round' = {n} = {k * n} adaptive "
            f"states reach 'selection.n_train' = {n_tr}, the total of training simulations: maximum dissimilarity "
            "would pick none (rounds x per_round must be below n_train)"
        )
    rs, rk = _get(cfg, "lifecycle.replicates.states"), _get(cfg, "lifecycle.replicates.seeds")
    outs = _get(cfg, "lifecycle.rbf.outputs")
    if all(isinstance(v, int) for v in (n_tr, k, n, rs, rk)) and rs > 0:
        adaptive = k * n if k > 0 else 0
        n_mda = n_tr - adaptive - rs * rk
        if n_mda <= 0:
            fail(
                f"config keys 'lifecycle.replicates.states' = {rs} x 'lifecycle.replicates.seeds' = {rk} = {rs * rk} "
                f"replicate simulations (with {adaptive} adaptive states) reach 'selection.n_train' = "
                f"{n_tr}, the total of training simulations: maximum dissimilarity would pick none"
            )
        elif isinstance(outs, list) and "damage_sn" not in outs:
            fail(
                f"config key 'lifecycle.replicates.states' = {rs} ranks the training states by their S-N damage, but "
                f"'lifecycle.rbf.outputs' = {outs!r} does not rebuild 'damage_sn'"
            )
        elif rs > n_mda + adaptive:
            fail(
                f"config key 'lifecycle.replicates.states' = {rs} exceeds the {n_mda + adaptive} "
                "training states there are to replicate"
            )
    if _get(cfg, "lifecycle.rbf.thrust.statistic") == "turbulent_sd":
        spectrum, f_max = _get(cfg, "simulation.wind.spectrum"), _get(cfg, "simulation.wind.f_max")
        t_avg = _get(cfg, "lifecycle.rbf.thrust.averaging_time")
        if spectrum == "none":
            fail(
                "config key 'lifecycle.rbf.thrust.statistic' = 'turbulent_sd' needs a turbulent wind, but "
                "'simulation.wind.spectrum' = 'none' (a steady wind: the coordinate would be zero everywhere)"
            )
        if isinstance(t_avg, (int, float)) and isinstance(f_max, (int, float)) and 1.0 / t_avg >= f_max:
            fail(
                f"config key 'lifecycle.rbf.thrust.averaging_time' = {t_avg} s leaves no turbulence below "
                f"'simulation.wind.f_max' = {f_max} Hz (1 / averaging_time must be below f_max)"
            )
    if _get(cfg, "hindcast.source") == "file" and not _get(cfg, "hindcast.path"):
        fail("config key 'hindcast.path' = None: a path is required when 'hindcast.source' is 'file'")
    if _get(cfg, "hydro.source") == "wamit" and not _get(cfg, "hydro.wamit_prefix"):
        fail("config key 'hydro.wamit_prefix' = None: a path prefix is required when 'hydro.source' is 'wamit'")
    hs, tp = _get(cfg, "lifecycle.sensitivity.sea_state.hs"), _get(cfg, "lifecycle.sensitivity.sea_state.tp")
    if isinstance(hs, (int, float)) and isinstance(tp, (int, float)) and tp > 0:
        from moorlife.cleaning import BREAKING_STEEPNESS, G_OVER_2PI, TP_FLOOR

        st = hs / (G_OVER_2PI * tp * tp)
        if st > BREAKING_STEEPNESS or tp < TP_FLOOR:
            fail(
                f"config keys 'lifecycle.sensitivity.sea_state.hs' = {hs!r}, '.tp' = {tp!r}: not a possible sea state "
                f"(steepness Hs / (1.56 Tp^2) = {st:.3g}, breaking limit 1/7; Tp floor {TP_FLOOR:g} s)"
            )

    # ------------------------------------------------------------------ time steps
    dt = _get(cfg, "simulation.dt")
    w_max = _get(cfg, "hydro.omega.max") if _get(cfg, "hydro.source") != "wamit" else None
    if isinstance(dt, (int, float)) and dt > 0:
        if isinstance(w_max, (int, float)) and w_max > 0:
            t_min = 2.0 * math.pi / w_max
            if dt > t_min / STEPS_PER_PERIOD * (1 + 1e-9):
                fail(
                    f"config key 'simulation.dt' = {dt!r} s cannot resolve the shortest wave period, 2 pi / "
                    f"'hydro.omega.max' = 2 pi / {w_max!r} = {t_min:.3g} s: the integrator needs "
                    f"{STEPS_PER_PERIOD} steps per period, dt <= {t_min / STEPS_PER_PERIOD:.3g} s"
                )
        kin = _get(cfg, "simulation.kinematics_dt")
        if isinstance(kin, (int, float)) and kin > 0 and isinstance(w_max, (int, float)) and w_max > 0:
            t_min = 2.0 * math.pi / w_max
            step = max(1, int(round(kin / dt))) * dt  # the simulator samples every k-th step
            if step > t_min / KINEMATICS_PER_PERIOD * (1 + 1e-9):
                fail(
                    f"config key 'simulation.kinematics_dt' = {kin!r} s (sampled every {step:g} s with "
                    f"'simulation.dt' = {dt!r} s) samples the shortest wave period 2 pi / 'hydro.omega.max' = "
                    f"{t_min:.3g} s fewer than {KINEMATICS_PER_PERIOD} times: the step must be <= "
                    f"{t_min / KINEMATICS_PER_PERIOD:.3g} s"
                )
        block, dur, tr = (
            _get(cfg, "statistics.block"),
            _get(cfg, "simulation.duration"),
            _get(cfg, "simulation.transient"),
        )
        if isinstance(block, (int, float)) and isinstance(dur, (int, float)) and block > 0 and dur > 0:
            ns = int(round(block / dt))
            if ns < 2:
                fail(
                    f"config key 'statistics.block' = {block!r} s is shorter than two steps of 'simulation.dt' = {dt!r} s"
                )
            tr = float(tr or 0.0)
            kept = int(math.ceil((dur + tr) / dt - 1e-9)) - int(round(tr / dt))
            if kept // ns < MIN_BLOCKS:
                fail(
                    f"config key 'statistics.block' = {block!r} s: the kept record 'simulation.duration' = {dur!r} s "
                    f"holds {kept // ns} block(s); the GEV fit needs at least {MIN_BLOCKS}: statistics.block <= "
                    f"{dur / MIN_BLOCKS:g} s"
                )

    # ------------------------------------------------------------------ ordered pairs, grids, lists
    for lo_key, hi_key in (
        ("hydro.omega.min", "hydro.omega.max"),
        ("lifecycle.rbf.grid.min", "lifecycle.rbf.grid.max"),
        ("hindcast.synthetic.tp_min", "hindcast.synthetic.tp_max"),
    ):
        lo, hi = _get(cfg, lo_key), _get(cfg, hi_key)
        if isinstance(lo, (int, float)) and isinstance(hi, (int, float)) and not lo < hi:
            fail(f"config key '{lo_key}' = {lo!r} must be below '{hi_key}' = {hi!r}")
    for key in ("selection.discrete.hs_edges", "selection.discrete.wind_edges", "selection.discrete.tp_edges"):
        e = _get(cfg, key)
        if isinstance(e, list) and any(not b > a for a, b in zip(e[:-1], e[1:])):
            fail(f"config key '{key}' = {e!r}: the class edges must increase strictly")
    for key in ("hydro.heading_step", "selection.discrete.direction_sector"):
        w = _get(cfg, key)
        if isinstance(w, (int, float)) and w > 0 and abs(360.0 / w - round(360.0 / w)) > 1e-9:
            fail(f"config key '{key}' = {w!r} deg must divide 360")
    groups = (
        (
            "hindcast.synthetic.wind",
            (
                "regime_directions",
                "regime_spreads",
                "regime_probabilities",
                "regime_seasonal_amplitudes",
                "regime_speed_factors",
            ),
        ),
        ("hindcast.synthetic.wind_sea", ("fetch_directions", "fetch_km")),
    )
    for prefix, keys in groups:
        lists = {k: _get(cfg, f"{prefix}.{k}") for k in keys}
        sizes = {k: len(v) for k, v in lists.items() if isinstance(v, list)}
        if len(set(sizes.values())) > 1:
            fail(
                f"config keys {', '.join(f'{prefix}.{k} ({n} values)' for k, n in sizes.items())} must have "
                "the same length (one value per regime or direction)"
            )


def check_against_table(
    cfg: Mapping[str, Any],
    ids: list[str],
    source: str = "config",
    link_diameters_mm: Mapping[str, float] | None = None,
) -> None:
    """Checks of the configuration against the mooring-system table (``config['mooring_systems']``).

    Parameters
    ----------
    cfg : mapping
        The validated configuration.
    ids : list of str
        The table's mooring systems.
    source : str
        Where the configuration came from, quoted in error messages.
    link_diameters_mm : mapping, optional
        ``mooring_system -> link_diameter_mm``; checks the corrosion allowance if given.

    Raises
    ------
    ConfigError
        ``lifecycle.sensitivity.mooring_system`` is not in the table (the sensitivities would
        silently drop out of the DAG), or ``fatigue.corrosion.rate`` over
        ``fatigue.design_life`` consumes a system's link (which failed at the end of lifecycle).
    """
    ms = _get(cfg, "lifecycle.sensitivity.mooring_system")
    if ms is not None and ms not in ids:
        raise ConfigError(
            f"{source}: config key 'lifecycle.sensitivity.mooring_system' = {ms!r} is not a mooring system of "
            f"the table {_get(cfg, 'mooring_systems')} ({', '.join(ids)})"
        )
    rate, life = _get(cfg, "fatigue.corrosion.rate"), _get(cfg, "fatigue.design_life")
    if link_diameters_mm and isinstance(rate, (int, float)) and isinstance(life, (int, float)):
        for name, d0 in link_diameters_mm.items():
            if float(d0) - rate * life <= 0.0:
                raise ConfigError(
                    f"{source}: config keys 'fatigue.corrosion.rate' = {rate!r} mm/year over 'fatigue.design_life' = "
                    f"{life!r} years remove {rate * life:g} mm, the whole {float(d0):g} mm link of {name} "
                    f"({_get(cfg, 'mooring_systems')})"
                )


def _hour() -> Any:
    import pandas as pd

    return pd.Timedelta(hours=1)


def iter_schema_leaves(schema: Mapping[str, Any], prefix: str = "") -> Iterator[tuple[str, Mapping[str, Any]]]:
    """Yield ``(dotted key, sub-schema)`` for every property, at every depth."""
    for name, sub in schema.get("properties", {}).items():
        key = f"{prefix}{name}"
        yield key, sub
        if sub.get("type") == "object" and "properties" in sub:
            yield from iter_schema_leaves(sub, prefix=f"{key}.")


def undocumented_keys(schema: Mapping[str, Any]) -> list[str]:
    """Keys of the schema that lack a ``description`` or a ``default``."""
    return [k for k, sub in iter_schema_leaves(schema) if "description" not in sub or "default" not in sub]


def deep_merge(base: Mapping[str, Any], overlay: Mapping[str, Any]) -> dict[str, Any]:
    """Recursively merge ``overlay`` into a copy of ``base`` (as Snakemake's ``--configfile``)."""
    out = copy.deepcopy(dict(base))
    for k, v in overlay.items():
        if isinstance(v, Mapping) and isinstance(out.get(k), Mapping):
            out[k] = deep_merge(out[k], v)
        else:
            out[k] = copy.deepcopy(v)
    return out


def fingerprint(*parts: Any) -> str:
    """A SHA-256 hex digest of JSON-serialisable parts (keys sorted, floats by repr)."""
    text = json.dumps(parts, sort_keys=True, default=str, separators=(",", ":"))
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def schema_table(schema: Mapping[str, Any]) -> str:
    """A Markdown table of every config key: dotted key, default and description.

    The README's configuration reference is this table; a test keeps them equal.
    """
    rows = ["| key | default | description |", "|---|---|---|"]
    for key, sub in iter_schema_leaves(schema):
        if sub.get("type") == "object" and "properties" in sub:
            continue
        default = json.dumps(sub.get("default"), separators=(", ", ": "))
        text = " ".join(str(sub.get("description", "")).split()).replace("|", "\\|")
        rows.append(f"| `{key}` | `{default}` | {text} |")
    return "\n".join(rows)
