"""Configuration validation against the JSON schema, and config fingerprints.

Pure functions: dictionaries in, dictionaries out. Reading the YAML files is done in
:mod:`moorlife.io`.
"""

from __future__ import annotations

import copy
import hashlib
import json
from collections.abc import Iterator, Mapping
from typing import Any

import jsonschema

__all__ = [
    "ConfigError",
    "validate_config",
    "undocumented_keys",
    "iter_schema_leaves",
    "fingerprint",
    "deep_merge",
    "schema_table",
]


class ConfigError(ValueError):
    """A configuration value is invalid; the message names the file, key and value."""


def _key_path(error: jsonschema.ValidationError) -> str:
    parts = [str(p) for p in error.absolute_path]
    if error.validator == "additionalProperties":
        # the offending key is in the message, not in the path
        extra = sorted(set(error.instance) - set(error.schema.get("properties", {})))
        parts.append(extra[0] if extra else "?")
    elif error.validator == "required":
        missing = [r for r in error.validator_value if r not in error.instance]
        parts.append(missing[0] if missing else "?")
    return ".".join(parts) or "<root>"


def _fill_defaults(instance: Any, schema: Mapping[str, Any]) -> Any:
    if schema.get("type") == "object" and isinstance(instance, dict):
        for name, sub in schema.get("properties", {}).items():
            if name not in instance and "default" in sub:
                instance[name] = copy.deepcopy(sub["default"])
            if name in instance:
                instance[name] = _fill_defaults(instance[name], sub)
    return instance


def validate_config(
    config: Mapping[str, Any], schema: Mapping[str, Any], source: str = "config"
) -> dict[str, Any]:
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
    filled = _fill_defaults(copy.deepcopy(dict(config)), schema)
    validator = jsonschema.Draft202012Validator(schema)
    errors = sorted(validator.iter_errors(filled), key=lambda e: (-len(e.absolute_path), str(e.path)))
    if errors:
        err = errors[0]
        key = _key_path(err)
        if err.validator == "additionalProperties":
            raise ConfigError(f"{source}: unknown config key '{key}' (not in the schema; check its spelling)")
        if err.validator == "required":
            raise ConfigError(f"{source}: config key '{key}' is required")
        raise ConfigError(f"{source}: config key '{key}' = {err.instance!r} is invalid: {err.message}")
    return filled


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
