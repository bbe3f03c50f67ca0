"""moorlife.io.report: the report's opening page, drawn from the comparison outputs."""

from __future__ import annotations

import pandas as pd
import pytest
from docutils.core import publish_parts

from moorlife.io.report import overview_rst, write_overview


def _table() -> pd.DataFrame:
    rows = []
    for ms, mass, util in (("MS1", 92.0, 3.2), ("MS3", 200.0, 0.62)):
        for curve in ("sn", "tn"):
            rows.append(
                {
                    "mooring_system": ms,
                    "line": "M1",
                    "curve": curve,
                    "mass_kg_per_m": mass,
                    "lifecycle_damage": 0.0123 * util,
                    "damage_per_year": 0.0123 * util,
                    "discrete_damage": 0.0150 * util,
                    "difference_pct": -21.96,
                    "fatigue_life_years": 81.3 / util,
                    "fatigue_life_low": 20.0 / util,
                    "fatigue_life_high": float("inf"),
                    "design_fatigue_factor": 5.0,
                    "utilisation": util,
                    "passes": util <= 1.0,
                }
            )
    return pd.DataFrame(rows)


REC = {
    "recommended": "MS3",
    "curves": ["sn", "tn"],
    "rule": "lightest system with DFF x design-life damage <= 1 on every line for curves ['sn', 'tn']",
    "max_utilisation": {"MS1": 3.2, "MS3": 0.62},
    "mean_difference_pct": {"sn/M1": -21.96, "tn/M1": -21.96},
}


def _html(rst: str) -> str:
    # halt on any docutils warning: a malformed table must fail here, not render as an error box
    return publish_parts(rst, writer="html", settings_overrides={"halt_level": 2})["html_body"]


def test_overview_names_the_recommendation_and_every_row():
    html = _html(overview_rst(_table(), REC))
    assert "Recommended mooring system: MS3" in html
    assert html.count("<tr>") == (1 + 2) + (1 + 4) + (1 + 2)  # utilisation, life-cycle, matrix tables
    assert "0.0394" in html and "0.048" in html  # MS1 life-cycle and matrix damage, 3 digits
    assert "-22.0" in html and "25.4 [6.25, inf]" in html
    assert "<strong>fail</strong>" in html and "pass" in html


def test_overview_when_no_system_passes():
    rec = {**REC, "recommended": None}
    html = _html(overview_rst(_table(), rec))
    assert "No mooring system passes" in html and "Recommended mooring system" not in html


def test_write_overview_reads_the_outputs(tmp_path):
    csv, yml, out = tmp_path / "summary.csv", tmp_path / "rec.yaml", tmp_path / "report" / "overview.rst"
    _table().to_csv(csv, index=False)
    import yaml

    yml.write_text(yaml.safe_dump(REC))
    write_overview(csv, yml, out)
    assert out.read_text() == overview_rst(pd.read_csv(csv), REC)


@pytest.mark.parametrize("name", ["workflow.rst", "workflow_pending.rst"])
@pytest.mark.parametrize("rounds", [0, 2])
def test_report_descriptions_render(name, rounds, tmp_path, monkeypatch, study_config):
    """The global descriptions as Snakemake renders them: Jinja with the validated config (its
    defaults filled in, as Snakemake's config is at parse time), then docutils."""
    from pathlib import Path

    import jinja2

    text = (Path(__file__).resolve().parents[1] / "workflow" / "report" / name).read_text()
    cfg = study_config
    cfg["lifecycle"]["recommendation"]["curves"] = ["sn", "tn"]
    cfg["lifecycle"]["adaptive"].update(rounds=rounds, per_round=100)
    cfg["fatigue"]["design_life"] = 25.0
    env = jinja2.Environment(undefined=jinja2.StrictUndefined, trim_blocks=True, lstrip_blocks=True)
    rendered = env.from_string(text).render(snakemake=type("S", (), {"config": cfg}), categories={}, files=[])
    rendered += (
        "\n\n.. _Workflow: javascript:show_panel('workflow')\n.. _Statistics: javascript:show_panel('statistics')\n"
    )
    (tmp_path / "results" / "report").mkdir(parents=True)
    (tmp_path / "results" / "report" / "overview.rst").write_text(overview_rst(_table(), REC))
    monkeypatch.chdir(tmp_path)  # Snakemake renders in the working directory: the include is relative
    html = _html(rendered)
    if name == "workflow.rst":
        assert "sn, tn" in html and "25.0" in html and "Recommended mooring system: MS3" in html
        assert ("2 adaptive round(s) of 100 per system" in html) == (rounds == 2)
    else:
        assert "has not run yet" in html


@pytest.mark.parametrize(("attrs", "method"), [({}, "RBF"), ({"rbf_method": "gp"}, "GP")])
def test_validation_figure_names_the_reconstruction(attrs, method):
    """The validation figure's title says which reconstruction was validated: the RBF of the paper
    (no ``rbf_method`` attribute, as the default study's store) or the GP."""
    import numpy as np
    import xarray as xr

    from moorlife.plots.lifecycle import validation_scatter

    outputs = ["surge_mpm", "damage_sn/M1"]
    sim = np.random.default_rng(0).lognormal(size=(6, 2))
    ds = xr.Dataset(
        {
            "validation_simulated": (("validate", "output"), sim),
            "validation_predicted": (("validate", "output"), 1.1 * sim),
            "validation_r": ("output", [0.99, 0.98]),
        },
        coords={"output": outputs},
        attrs=attrs,
    )
    title = validation_scatter(ds, "MS1").get_suptitle()
    assert title == f"MS1 {method} validation on 6 states not used for fitting"
