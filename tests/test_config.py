"""config/config.yaml, its JSON schema, overlays and the mooring-system table."""

from __future__ import annotations

from pathlib import Path

import pandas as pd
import pytest

from moorlife.config import ConfigError, deep_merge, fingerprint, iter_schema_leaves, undocumented_keys, validate_config
from moorlife.io import read_mooring_systems, read_yaml
from moorlife.tables import validate_mooring_systems

ROOT = Path(__file__).resolve().parents[1]
SCHEMA = ROOT / "workflow" / "schemas" / "config.schema.yaml"
CONFIG = ROOT / "config" / "config.yaml"


@pytest.fixture(scope="module")
def schema():
    return read_yaml(SCHEMA)


@pytest.fixture(scope="module")
def config():
    return read_yaml(CONFIG)


def _leaves(cfg, schema, prefix=""):
    """(dotted key, value) of config.yaml, descending only into schema objects with properties
    (a free-form mapping such as a column map is one value)."""
    for k, v in cfg.items():
        key = f"{prefix}{k}"
        sub = schema.get("properties", {}).get(k, {})
        if isinstance(v, dict) and v and "properties" in sub:
            yield from _leaves(v, sub, f"{key}.")
        else:
            yield key, v


def test_every_schema_key_has_description_and_default(schema):
    assert undocumented_keys(schema) == []


def test_config_values_equal_schema_defaults(schema, config):
    """config.yaml is the schema's defaults written out: no silent divergence."""
    props = dict(iter_schema_leaves(schema))
    for key, value in _leaves(config, schema):
        assert key in props, f"config.yaml key {key!r} is not in the schema"
        sub = props[key]
        if sub.get("type") == "object" and value == {}:
            continue
        assert sub["default"] == value, f"{key}: schema default {sub['default']!r} != config.yaml {value!r}"


def test_config_and_quick_overlay_validate(study_config, quick_config, tiny_config):
    full, quick = study_config, quick_config
    assert tiny_config["selection"]["n_train"] <= quick["selection"]["n_train"]
    assert full["selection"]["n_train"] == 1000 and full["selection"]["n_validate"] == 225
    assert quick["selection"]["n_train"] < full["selection"]["n_train"]
    assert full["hindcast"]["start"].startswith("1985") and full["hindcast"]["end"].startswith("2015")


def test_defaults_are_filled(schema):
    filled = validate_config({}, schema)
    assert filled["seed"] == schema["properties"]["seed"]["default"]
    assert filled["selection"]["n_train"] == 1000


@pytest.mark.parametrize(
    ("patch", "pattern"),
    [
        ({"selection": {"n_train": -5}}, r"'selection\.n_train' = -5 .*minimum"),
        ({"selection": {"n_trian": 10}}, r"unknown config key 'selection\.n_trian'"),
        ({"seed": "abc"}, r"'seed' = 'abc'"),
        ({"hindcast": {"source": "era6"}}, r"'hindcast\.source' = 'era6'"),
        ({"simulation": {"batch_size": 0}}, r"'simulation\.batch_size' = 0"),
        ({"lifecycle": {"rbf": {"smoothing": [0.0, -0.1]}}}, r"'lifecycle\.rbf\.smoothing' = \[0\.0, -0\.1\]"),
    ],
)
def test_bad_config_names_key_and_value(schema, config, patch, pattern):
    with pytest.raises(ConfigError, match=pattern) as err:
        validate_config(deep_merge(config, patch), schema, source="bad.yaml")
    assert "bad.yaml" in str(err.value)


def test_mooring_table_matches_paper_table4():
    df = read_mooring_systems(ROOT / "config" / "mooring_systems.tsv")
    assert list(df.index) == [f"MS{i}" for i in range(1, 7)]
    # methodology Table 4 (Barrera et al. 2019)
    assert df.loc["MS4", "pretension_kN"] == 2735
    assert df.loc["MS6", "MBS_N"] == 28664642
    assert df["mass_kg_per_m"].is_monotonic_increasing


@pytest.mark.parametrize(
    ("edit", "pattern"),
    [
        (lambda d: d.drop(columns="EA_N"), r"missing column\(s\) \['EA_N'\]"),
        (
            lambda d: d.assign(EA_N=[5.43e8, -1, 1, 1, 1, 1]),
            r"row 3 \(MS2\), column 'EA_N': -1(\.0)? must be a positive number",
        ),
        (lambda d: d.assign(mooring_system=["MS1", "MS1", "a", "b", "c", "d"]), r"duplicated id 'MS1'"),
        (lambda d: d.assign(chain=["studless", "studlink", "stud", "stud", "stud", "stud"]), r"row 3, column 'chain'"),
        (lambda d: d.assign(mooring_system=["MS 1", "b", "c", "d", "e", "f"]), r"'MS 1' is not a valid id"),
    ],
)
def test_bad_mooring_table(edit, pattern):
    df = pd.read_csv(ROOT / "config" / "mooring_systems.tsv", sep="\t")
    with pytest.raises(ValueError, match=pattern):
        validate_mooring_systems(edit(df), source="ms.tsv")


def test_fingerprint_is_stable_and_sensitive():
    a = fingerprint({"a": 1, "b": [1.0, 2.0]}, "MS1")
    assert a == fingerprint({"b": [1.0, 2.0], "a": 1}, "MS1")
    assert a != fingerprint({"a": 1, "b": [1.0, 2.0000001]}, "MS1")


def test_config_reference_is_current(schema, tmp_path):
    from moorlife.config import schema_table
    from moorlife.io.reference import reference_block, write_reference

    text = (ROOT / "config" / "README.md").read_text()
    assert reference_block(text, "config/README.md") == schema_table(schema), (
        "config/README.md's configuration reference is stale: run `make config-reference`"
    )
    # the regeneration replaces exactly the block
    stale = tmp_path / "README.md"
    stale.write_text(text.replace("| `seed` |", "| `seed_old` |"))
    assert write_reference(stale, ROOT / "workflow/schemas/config.schema.yaml") is True
    assert stale.read_text() == text
    assert write_reference(stale, ROOT / "workflow/schemas/config.schema.yaml") is False
