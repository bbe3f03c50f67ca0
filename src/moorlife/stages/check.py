"""The pre-flight check: what the Snakefile runs at parse time, as a command with an exit status.

``workflow/rules/common.smk`` calls :func:`check_study` when Snakemake parses the workflow (and
:func:`check_truth` when a truth target is requested), so a study the command accepts is one
Snakemake accepts, and the same message stops both::

    python -m moorlife.stages.check --configfile config/quick.yaml my_site.yaml
    python -m moorlife.stages.check --configfile my_site.yaml --truth --inputs

The command reads ``config/config.yaml`` (``--base``) plus the overlays, merged in order as
Snakemake's ``--configfile`` does, with relative paths resolved against the current directory
(as Snakemake's working directory). It runs the schema and cross-key checks, reads the
mooring-system table and checks the config against it, reads ``platform.yaml`` and checks
``DASK_SCHEDULER_ADDRESS`` when it is set. ``--truth`` adds the truth-window check;
``--inputs`` also loads a hindcast *file* (``hindcast.source: file``) and validates it exactly as
the ``metocean`` rule does, without writing its store. Nothing is written.

Exit status: 0 when the study passes (one line on stdout), 1 when it is refused (the message,
naming the file or the config key and the value, on stderr), 2 on a usage error.
"""

from __future__ import annotations

import argparse
import os
import sys
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import pandas as pd

from moorlife.config import check_against_table, deep_merge, validate_config
from moorlife.io import read_mooring_systems, read_yaml
from moorlife.io.platform import read_platform_config

__all__ = ["CheckedStudy", "check_study", "check_truth", "check_inputs", "read_configs", "main"]


@dataclass(frozen=True)
class CheckedStudy:
    """A study that passed :func:`check_study`.

    Attributes
    ----------
    config : dict
        The validated configuration, every schema default filled in.
    mooring : pandas.DataFrame
        The mooring-system table, one row per system (indexed by ``mooring_system``).
    platform : dict
        ``platform.yaml``, read and checked.
    """

    config: dict[str, Any]
    mooring: pd.DataFrame
    platform: dict[str, Any]


def check_study(config: Mapping[str, Any], schema: Mapping[str, Any], source: str = "config") -> CheckedStudy:
    """Every check that needs only the configuration and its small files: the parse-time check.

    Parameters
    ----------
    config : mapping
        The merged configuration (``config.yaml`` plus the overlays).
    schema : mapping
        The JSON schema (``workflow/schemas/config.schema.yaml``).
    source : str
        The configuration files, quoted in messages.

    Returns
    -------
    CheckedStudy

    Raises
    ------
    ValueError
        (:class:`moorlife.config.ConfigError` for the keys) naming the file or the config key
        and the value: a key the schema refuses or two keys that disagree
        (:func:`moorlife.config.validate_config`), a bad mooring-system table or a config key
        that disagrees with it (:func:`moorlife.config.check_against_table`), a bad
        ``platform.yaml``, or a ``DASK_SCHEDULER_ADDRESS`` that is no scheduler address.
    """
    cfg = validate_config(config, schema, source)
    mooring = read_mooring_systems(cfg["mooring_systems"])
    check_against_table(cfg, list(mooring.index), source, dict(mooring["link_diameter_mm"]))
    platform = read_platform_config(cfg["platform"])
    from moorlife.parallel import SCHEDULER_ENV

    if os.environ.get(SCHEDULER_ENV):
        from moorlife.parallel import check_scheduler_address

        check_scheduler_address(os.environ[SCHEDULER_ENV])
    return CheckedStudy(config=cfg, mooring=mooring, platform=platform)


def check_truth(config: Mapping[str, Any], source: str = "config") -> int:
    """The ``truth`` keys against the study period (run when a truth target is in the DAG).

    Returns the number of truth hours; raises ValueError naming the key and the value
    (:func:`moorlife.truth.check_window`).
    """
    from moorlife.truth import check_window

    t, h = config["truth"], config["hindcast"]
    return check_window(
        t["window"]["start"],
        t["window"]["end"],
        t["stride"],
        t["n_second_seed"],
        hindcast_start=h["start"],
        hindcast_end=h["end"],
        source=source,
        second_seed_storm=t["second_seed_storm"],
    )


def check_inputs(config: Mapping[str, Any]) -> int | None:
    """Load and validate a hindcast file as the ``metocean`` rule does, writing nothing.

    Returns the number of hours, or None when the hindcast is synthetic (nothing to read).
    Raises :class:`moorlife.metocean.HindcastError` naming the file, the column, the row and
    the value.
    """
    if config["hindcast"]["source"] != "file":
        return None
    from moorlife.stages.metocean import build_hindcast

    ds = build_hindcast(dict(config["hindcast"]), int(config["seed"]))
    return int(ds.sizes["time"])


def read_configs(base: str | os.PathLike[str], overlays: Sequence[str | os.PathLike[str]]) -> dict[str, Any]:
    """``base`` plus ``overlays``, merged in order as Snakemake merges ``--configfile`` files."""
    merged = read_yaml(base)
    for ov in overlays:
        merged = deep_merge(merged, read_yaml(ov))
    return merged


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="python -m moorlife.stages.check",
        description="Check a study's configuration as Snakemake does at parse time, before any job.",
    )
    p.add_argument("--configfile", nargs="+", default=[], metavar="FILE", help="overlays, as snakemake --configfile")
    p.add_argument("--base", default="config/config.yaml", help="the base configuration (the Snakefile's configfile)")
    p.add_argument("--schema", default=None, help="the JSON schema (default: the one shipped with moorlife)")
    p.add_argument("--truth", action="store_true", help="also check the truth window (as a truth target does)")
    p.add_argument("--inputs", action="store_true", help="also load and validate a hindcast file (writes nothing)")
    return p


def main(argv: Sequence[str] | None = None) -> int:
    """The command: check, report, and return the exit status (0 passed, 1 refused, 2 usage).

    Parameters
    ----------
    argv : sequence of str, optional
        The arguments (default: ``sys.argv[1:]``).
    """
    try:
        args = _parser().parse_args(argv)
    except SystemExit as exc:  # argparse has printed the usage error
        return int(exc.code or 0)
    from yaml import YAMLError

    from moorlife.settings import config_schema

    source = ", ".join(str(f) for f in (args.base, *args.configfile))
    try:
        schema = read_yaml(args.schema) if args.schema else config_schema()
        study = check_study(read_configs(args.base, args.configfile), schema, source)
        hours = check_truth(study.config, source) if args.truth else None
        n_hindcast = check_inputs(study.config) if args.inputs else None
    except (ValueError, OSError, YAMLError) as exc:
        print(f"moorlife check: refused: {exc}", file=sys.stderr)
        return 1
    ids = list(study.mooring.index)
    extra = [f"{hours} truth hours"] if hours is not None else []
    extra += [f"hindcast file of {n_hindcast} hours"] if n_hindcast is not None else []
    print(
        f"moorlife check: {source}: ok, {len(ids)} mooring systems ({', '.join(ids)})"
        + "".join(f", {e}" for e in extra)
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
