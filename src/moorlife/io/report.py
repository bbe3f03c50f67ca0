"""The opening page of the Snakemake report: the answer, drawn from the run's own outputs.

Snakemake renders the global report description (``report:`` in the Snakefile) as a Jinja
template that sees only the config, not the outputs; so rule ``report_overview`` writes this
reStructuredText from ``results/comparison/summary.csv`` and ``recommendation.yaml``, and
``workflow/report/workflow.rst`` includes it.
"""

from __future__ import annotations

import math
import os
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import pandas as pd

from moorlife.io import read_yaml

__all__ = ["overview_rst", "write_overview"]

#: (column of summary.csv, heading) of the life-cycle table, in order.
TABLE_COLUMNS = (
    ("mooring_system", "System"),
    ("line", "Line"),
    ("curve", "Curve"),
    ("mass_kg_per_m", "Mass (kg/m)"),
    ("lifecycle_damage", "Life-cycle damage"),
    ("discrete_damage", "Matrix damage"),
    ("difference_pct", "Difference (%)"),
    ("fatigue_life_years", "Fatigue life (years)"),
    ("utilisation", "Utilisation"),
    ("passes", "Verdict"),
)


def _num(x: Any, fmt: str = "{:.3g}") -> str:
    try:
        v = float(x)
    except (TypeError, ValueError):
        return str(x)
    return "n/a" if math.isnan(v) else fmt.format(v)


def _cell(col: str, row: Mapping[str, Any]) -> str:
    v = row[col]
    if col == "passes":
        return "pass" if str(v).lower() in ("true", "1") else "**fail**"
    if col == "fatigue_life_years":
        life = _num(v)
        lo, hi = row.get("fatigue_life_low"), row.get("fatigue_life_high")
        return life if lo is None or hi is None else f"{life} [{_num(lo)}, {_num(hi)}]"
    if col == "difference_pct":
        return _num(v, "{:+.1f}")
    if col == "mass_kg_per_m":
        return _num(v, "{:.0f}")
    if col in ("mooring_system", "line", "curve"):
        return str(v)
    return _num(v)


def _list_table(title: str, header: list[str], rows: list[list[str]]) -> list[str]:
    out = [f".. list-table:: {title}", "   :header-rows: 1", ""]
    for r in [header, *rows]:
        out.append(f"   * - {r[0]}")
        out.extend(f"     - {c}" for c in r[1:])
    return out + [""]


def overview_rst(table: pd.DataFrame, rec: Mapping[str, Any]) -> str:
    """The report's opening section as reStructuredText (no disk access).

    Parameters
    ----------
    table : pandas.DataFrame
        ``results/comparison/summary.csv``: one row per mooring system, line and curve family.
    rec : mapping
        ``results/comparison/recommendation.yaml`` (``recommended``, ``rule``,
        ``max_utilisation``, ``mean_difference_pct``).
    """
    chosen = rec.get("recommended")
    out = ["The answer", "----------", ""]
    if chosen:
        out += [f"**Recommended mooring system: {chosen}**, the {rec.get('rule', '')}.", ""]
    else:
        out += [
            f"**No mooring system passes**: the recommendation is the {rec.get('rule', '')}, "
            "and every system exceeds it (highest utilisation below).",
            "",
        ]
    util = rec.get("max_utilisation") or {}
    if util:
        rows = [[str(ms), _num(u), "pass" if float(u) <= 1.0 else "**fail**"] for ms, u in util.items()]
        out += _list_table(
            "Highest utilisation (DFF x design-life damage) over the lines and curves",
            ["System", "Utilisation", "Verdict"],
            rows,
        )
    cols = [(c, h) for c, h in TABLE_COLUMNS if c in table.columns]
    out += [
        "Life cycle",
        "----------",
        "",
        "Damage of every line over the hindcast (every hour, through the RBF reconstruction) "
        "and from the scatter matrix over the same hours; difference = 100 (life cycle - "
        "matrix) / life cycle; fatigue life with its band [low, high] from the seed scatter "
        "and the RBF validation error; utilisation = DFF x design-life damage "
        "(``results/comparison/summary.csv``, which also holds the damage per year, the "
        "DFF and the largest offsets and tensions).",
        "",
    ]
    rows = [[_cell(c, r) for c, _ in cols] for r in table.to_dict("records")]
    out += _list_table("Life-cycle fatigue per mooring system, line and curve", [h for _, h in cols], rows)
    diff = rec.get("mean_difference_pct") or {}
    if diff:
        out += [
            "Comparison with the scatter matrix",
            "----------------------------------",
            "",
            "The conventional discrete approach (one simulation per Hs-Tp bin, weighted by the "
            "bin's hours) against the life cycle: difference = 100 (life cycle - matrix) / life "
            "cycle, mean over the mooring systems; positive where the matrix underestimates "
            "the damage.",
            "",
        ]
        rows = [[k.split("/")[0], k.split("/", 1)[-1], _num(v, "{:+.1f}")] for k, v in diff.items()]
        out += _list_table(
            "Matrix vs life-cycle damage, mean difference (%)", ["Curve", "Line", "Difference (%)"], rows
        )
    return "\n".join(out) + "\n"


def write_overview(
    summary_csv: str | os.PathLike[str], recommendation_yaml: str | os.PathLike[str], out: str | os.PathLike[str]
) -> None:
    """Read the comparison outputs and write :func:`overview_rst` to ``out``."""
    text = overview_rst(pd.read_csv(summary_csv), read_yaml(recommendation_yaml))
    p = Path(out)
    p.parent.mkdir(parents=True, exist_ok=True)
    p.write_text(text, encoding="utf-8")
