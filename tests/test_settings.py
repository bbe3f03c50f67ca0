"""Typed settings: built from the config schema's defaults, and only from there."""

from __future__ import annotations

import ast
import dataclasses
import tomllib
from pathlib import Path

import pytest

from moorlife import fatigue, lifecycle, metocean, names, settings
from moorlife.config import ConfigError
from moorlife.io import read_yaml
from moorlife.mooring import lines

ROOT = Path(__file__).resolve().parents[1]
SRC = ROOT / "src" / "moorlife"

#: Every settings record, its config section, and the fields equal to the schema value of a key.
#: ``(class, section, {field: dotted key within the section or a function of the filled section})``
RECORDS = [
    (settings.SimulationSettings, "simulation"),
    (settings.WindSettings, "simulation.wind"),
    (settings.HydroSettings, "hydro"),
    (settings.StatisticsSettings, "statistics"),
    (fatigue.FatigueSettings, "fatigue"),
    (lifecycle.RBFSettings, "lifecycle.rbf"),
    (lines.MooringSettings, "mooring"),
    (metocean.SyntheticParams, "hindcast.synthetic"),
    (metocean.SwellParams, "hindcast.synthetic.swell"),
    (metocean.StormParams, "hindcast.synthetic.storms"),
    (metocean.WindParams, "hindcast.synthetic.wind"),
    (metocean.WindSeaParams, "hindcast.synthetic.wind_sea"),
    (metocean.CleaningPolicy, "hindcast.cleaning"),
    (metocean.PlausibleLimits, "hindcast.cleaning.limits"),
]

#: Where a field of a record is not the schema key of the same name: field -> path in the section.
RENAMED = {
    "HydroSettings": {
        "omega_min": "omega.min",
        "omega_max": "omega.max",
        "omega_n": "omega.n",
        "mesh_resolution": "mesh.resolution",
        "panel_size": "mesh.panel_size",
        "around_refinement": "mesh.around_refinement",
        "richardson": "mesh.richardson",
        "rotational_symmetry": "mesh.rotational_symmetry",
        "mirror_symmetry": "mesh.mirror_symmetry",
    },
    "FatigueSettings": {
        "corrosion_rate": "corrosion.rate",
        "corrosion_step": "corrosion.step",
        "mean_stress": "mean_stress.method",
        "ultimate": "mean_stress.ultimate",
        "yield_": "mean_stress.yield",
        "dnv_base": "design_factor.dnv.base",
        "dnv_threshold": "design_factor.dnv.threshold",
        "dnv_increment": "design_factor.dnv.increment",
        "dnv_span": "design_factor.dnv.span",
        "api_factor": "design_factor.api",
        "rule_sn": "design_factor.sn",
        "rule_tn": "design_factor.tn",
    },
    "RBFSettings": {
        "shape_mode": "shape",
        "fixed_damage": "fixed.damage",
        "fixed_tension": "fixed.tension",
        "fixed_other": "fixed.other",
        "grid_min": "grid.min",
        "grid_max": "grid.max",
        "grid_n": "grid.n",
        "trend_knots": "wind_trend.knots",
        "trend_harmonics": "wind_trend.harmonics",
        "thrust_statistic": "thrust.statistic",
        "stack_resamples": "stack.resamples",
        "stack_seed": "stack.seed",
        "thrust_averaging_time": "thrust.averaging_time",
    },
}

#: Unit conversions from the config value to the field: field -> factor.
SCALED = {("FatigueSettings", "corrosion_rate"): 1e-3}


def _schema_default(section: str, key: str):
    sub = settings.section_schema(section)
    for p in key.split("."):
        sub = sub["properties"][p]
    if sub.get("type") == "object" and "properties" in sub:  # a nested section, filled
        return settings.section_defaults(f"{section}.{key}")
    return sub["default"]


def _plain(v):
    if dataclasses.is_dataclass(v):
        return {f.name: _plain(getattr(v, f.name)) for f in dataclasses.fields(v)}
    if isinstance(v, tuple):
        return [_plain(x) for x in v]
    if isinstance(v, dict):
        return {k: _plain(x) for k, x in v.items()}
    return v


@pytest.mark.parametrize(("cls", "section"), RECORDS, ids=[c.__name__ for c, _ in RECORDS])
def test_records_build_from_empty_to_the_schema_defaults(cls, section):
    rec = cls.from_config({})
    assert rec == cls.from_config(None)
    for f in dataclasses.fields(cls):
        # (a) no defaults of their own: the schema is the only place
        assert f.default is dataclasses.MISSING and f.default_factory is dataclasses.MISSING, f.name
        key = RENAMED.get(cls.__name__, {}).get(f.name, f.name)
        expected = _schema_default(section, key)
        if f.name == "smoothing":  # a number or a list of candidates, stored as a tuple
            expected = [expected] if not isinstance(expected, list) else expected
        if f.name == "weights":  # a weight per scalar, stored per coordinate (1 on the directions)
            expected = [expected.get(v, 1.0) for v in names.METOCEAN_VARS]
        expected = expected * SCALED.get((cls.__name__, f.name), 1) if isinstance(expected, float) else expected
        got = _plain(getattr(rec, f.name))
        assert (
            got == expected
            and type(got) is type(expected)
            or (isinstance(expected, int) and type(got) is float and got == expected)
        ), f"{cls.__name__}.{f.name} = {got!r}, schema {section}.{key} = {expected!r}"


#: Keys of a record's section read by another builder: record -> keys (and by whom).
ELSEWHERE = {
    "MooringSettings": {
        "water_depth",
        "line_length",
        "fairlead_radius",
        "fairlead_depth",
        "anchor_radius",
        "line_bearings",
    },  # the geometry, read by mooring.oc4_layout into a Layout
}


def test_every_record_field_is_covered():
    """Every key of each section is read by its record (or by a nested record)."""
    for cls, section in RECORDS:
        renamed = RENAMED.get(cls.__name__, {})
        read = {renamed.get(f.name, f.name).split(".")[0] for f in dataclasses.fields(cls)}
        read |= ELSEWHERE.get(cls.__name__, set())
        keys = set(settings.section_schema(section)["properties"])
        assert keys == read, f"{cls.__name__}: {sorted(keys ^ read)}"


def test_partial_sections_keep_the_other_defaults():
    s = settings.SimulationSettings.from_config({"dt": 0.05, "wind": {"spectrum": "kaimal"}})
    assert s.dt == 0.05 and s.duration == 3600.0 and s.wind.spectrum == "kaimal" and s.wind.f_max == 1.0
    h = settings.HydroSettings.from_config({"omega": {"n": 3}})
    assert (h.omega_min, h.omega_max, h.omega_n) == (0.05, 2.5, 3)  # the sub-object is merged, not replaced
    assert fatigue.FatigueSettings.from_config({"corrosion": {"rate": 0.4}}).corrosion_rate == pytest.approx(0.4e-3)


def test_the_config_file_gives_the_schema_defaults():
    cfg = read_yaml(ROOT / "config/config.yaml")
    assert settings.SimulationSettings.from_config(cfg["simulation"]) == settings.SimulationSettings.from_config({})
    assert fatigue.FatigueSettings.from_config(cfg["fatigue"]) == fatigue.FatigueSettings.from_config({})


@pytest.mark.parametrize(
    ("cls", "section", "match"),
    [
        (settings.SimulationSettings, {"dtt": 0.1}, "unknown config key 'simulation.dtt'"),
        (settings.SimulationSettings, {"wind": {"spectrun": "npd"}}, "unknown config key 'simulation.wind.spectrun'"),
        (settings.SimulationSettings, {"dt": "fast"}, "'simulation.dt' = 'fast' is invalid"),
        (settings.HydroSettings, {"omega": {"n": 2.5}}, "'hydro.omega.n' = 2.5 is invalid"),
        (settings.StatisticsSettings, {"method": "moments"}, "'statistics.method' = 'moments' is invalid"),
        (fatigue.FatigueSettings, {"design_life": [25]}, "'fatigue.design_life' = \\[25\\] is invalid"),
        (lifecycle.RBFSettings, {"grid": {"nn": 3}}, "unknown config key 'lifecycle.rbf.grid.nn'"),
        (lines.MooringSettings, {"gravity": "9.8"}, "'mooring.gravity' = '9.8' is invalid"),
        (metocean.SyntheticParams, {"swell": {"tp_bse": 1.0}}, "unknown config key 'hindcast.synthetic.swell.tp_bse'"),
        (metocean.CleaningPolicy, {"max_gap_hours": 1.5}, "'hindcast.cleaning.max_gap_hours' = 1.5 is invalid"),
    ],
)
def test_unknown_keys_and_wrong_types_name_the_key(cls, section, match):
    with pytest.raises(ConfigError, match=match):
        cls.from_config(section)


def test_schema_ships_with_the_package():
    """The package reads the canonical schema (a link) at run time, also when installed."""
    link = SRC / "schemas" / "config.schema.yaml"
    assert link.resolve() == (ROOT / "workflow/schemas/config.schema.yaml").resolve()
    assert settings.config_schema() == read_yaml(ROOT / "workflow/schemas/config.schema.yaml")
    data = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]["package-data"]
    assert "schemas/config.schema.yaml" in data["moorlife"]


# ------------------------------------------------- no schema default repeated in the code
#: Files still reading config keys with literal fallbacks, each with its reason.
ALLOWED_FILES: dict[str, str] = {}
#: Single reads whose key is also a schema key but which read something else: (file, key): reason.
ALLOWED_READS = {
    ("mooring/lines.py", "mooring_system"): "a row of the mooring-systems table, not the config",
    ("hydro/mesh.py", "name"): "a member of platform.yaml, quoted in an error message",
    ("simulate/prepare.py", "name"): "a member of platform.yaml, quoted in an error message",
    ("fatigue/curves.py", "sn"): "lists the curves available in an error message, not a default",
    ("io/hindcast.py", "hs"): "the file's column label of a variable, quoted in an error message",
    ("io/hindcast.py", "tp"): "the file's column label of a variable, quoted in an error message",
    ("fatigue/curves.py", "tn"): "lists the curves available in an error message, not a default",
}


def _literal(node: ast.AST) -> bool:
    """A constant expression: no names, attributes or calls inside."""
    return not any(isinstance(n, (ast.Name, ast.Attribute, ast.Call)) for n in ast.walk(node))


def _schema_default_reads(path: Path, keys: frozenset[str]) -> list[tuple[int, str]]:
    out = []
    for node in ast.walk(ast.parse(path.read_text())):
        if not (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr == "get"):
            continue
        if len(node.args) != 2 or not isinstance(node.args[0], ast.Constant) or not isinstance(node.args[0].value, str):
            continue
        recv = node.func.value
        if isinstance(recv, ast.Attribute) and recv.attr == "attrs":  # dataset metadata, not config
            continue
        if node.args[0].value in keys and _literal(node.args[1]):
            out.append((node.lineno, node.args[0].value))
    return out


def test_no_schema_default_repeated_in_the_code():
    keys = settings.schema_leaf_names()
    found = []
    for py in sorted(SRC.rglob("*.py")):
        rel = py.relative_to(SRC).as_posix()
        if any(rel == f or (f.endswith("/") and rel.startswith(f)) for f in ALLOWED_FILES):
            continue
        found += [
            f"{rel}:{line} .get({key!r}, <literal>)"
            for line, key in _schema_default_reads(py, keys)
            if (rel, key) not in ALLOWED_READS
        ]
    assert not found, "schema defaults repeated (use the typed settings):\n" + "\n".join(found)


def test_the_guard_catches_a_repeated_default(tmp_path):
    p = tmp_path / "m.py"
    p.write_text(
        'def f(cfg, ds):\n    a = cfg.get("dt", 0.1)\n    b = ds.attrs.get("dt", 0.1)\n'
        '    c = cfg.get("extra_damping", [0.0] * 6)\n    return cfg.get("dt", a)\n'
    )
    assert _schema_default_reads(p, settings.schema_leaf_names()) == [(2, "dt"), (4, "extra_damping")]


def test_the_allow_list_is_not_stale():
    for f in ALLOWED_FILES:
        assert (SRC / f).exists(), f
