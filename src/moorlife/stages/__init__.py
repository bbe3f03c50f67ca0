"""The stage layer: one module per Snakemake stage, each reading its inputs, calling the domain
modules and writing its outputs.

=================  =========================================================================
module             rules (``workflow/rules/<stage>.smk``) -> function
=================  =========================================================================
``metocean``       ``metocean`` -> :func:`metocean.run`, ``metocean_figures`` -> ``figures``
``selection``      ``selection`` -> :func:`selection.run`, ``discrete`` -> ``discrete``,
                   ``selection_figures`` -> ``figures``
``hydro``          ``hydro`` -> :func:`hydro.run`
``simulate``       ``simulate_cases``, ``simulate_discrete``, ``sensitivity_seeds`` ->
                   :func:`simulate.run`
``rounds``         ``adaptive_picks`` -> :func:`rounds.run` (``simulate_round`` is ``simulate``)
``lifecycle``      ``lifecycle`` -> :func:`lifecycle.run`, ``lifecycle_figures`` -> ``figures``
``compare``        ``compare`` -> :func:`compare.run`, ``compare_figures`` -> ``figures``
``sensitivity``    ``sensitivity_cases`` -> :func:`sensitivity.cases`, ``sensitivity`` ->
                   :func:`sensitivity.run`
``check``          parse time (``common.smk``) -> :func:`check.check_study`; also the
                   pre-flight command ``python -m moorlife.stages.check``
=================  =========================================================================

The layers: the domain modules (every module of :mod:`moorlife` outside ``io`` and
``stages``, ``plots`` included) never import :mod:`moorlife.io` or :mod:`moorlife.stages`;
:mod:`moorlife.io` holds formats and stores only; the stages sit on top of both, and only
they (with :mod:`moorlife.io`) touch the disk. ``tests/test_structure.py`` enforces this.

The adapter convention (every script in ``workflow/scripts/`` is one call)::

    from moorlife.stages import simulate

    def main(smk):
        simulate.run(**smk.input, **smk.output, **smk.params, log=smk.log[0], threads=smk.threads,
                     batch_size=smk.config["simulation"]["batch_size"])

- every input the stage reads and every output is *named* in the rule, and the name is the
  keyword of the stage function (inputs that only make Snakemake rerun the rule when a file
  changes, such as the hindcast file or the WAMIT files, stay unnamed and are not passed);
- every ``params:`` entry is a keyword of the stage function, named after its config section
  where it is one (``simulation``, ``fatigue``, ...);
- ``log=smk.log[0]`` always: the stage logs there (:func:`moorlife.io.log_to`);
- ``threads=smk.threads`` where the rule declares ``threads:``, and wildcards the stage needs
  by keyword (``ms=smk.wildcards.ms``);
- settings that change scheduling or memory only, never the numbers (:data:`SCHEDULING_KEYS`),
  are read from ``smk.config`` by the adapter and never put in ``params:``: a params change
  makes Snakemake rerun the rule, and the stages keep them out of every store fingerprint too.
  The rules' params hold :func:`result_settings` of their config sections instead.

Each stage function also works without Snakemake (``log=None`` logs to the ``moorlife``
logger only), which is how the tests call them.
"""

from __future__ import annotations

import contextlib
import copy
import logging
import os
from collections.abc import Iterator, Mapping, Sequence
from typing import Any

__all__ = ["SCHEDULING_KEYS", "result_settings", "scheduling_free", "logged", "thrust_for"]

#: Config keys that change scheduling or memory only, never the numbers, per section, as key
#: paths inside the section. Kept out of the rules' params and out of every fingerprint.
SCHEDULING_KEYS: dict[str, tuple[tuple[str, ...], ...]] = {
    "simulation": (("batch_size",),),
    "lifecycle": (("rbf", "chunk_rows"),),
}


def scheduling_free(section: str, values: Mapping[str, Any] | None) -> dict[str, Any]:
    """A deep copy of one config section without its :data:`SCHEDULING_KEYS`.

    Parameters
    ----------
    section : str
        The section's name (``simulation``, ``lifecycle``, ...).
    values : mapping or None
        The section (None: empty).
    """
    out = copy.deepcopy(dict(values or {}))
    for path in SCHEDULING_KEYS.get(section, ()):
        node: Any = out
        for key in path[:-1]:
            node = node.get(key) if isinstance(node, Mapping) else None
        if isinstance(node, dict):
            node.pop(path[-1], None)
    return out


def result_settings(config: Mapping[str, Any], section: str, keys: Sequence[str] | None = None) -> dict[str, Any]:
    """``config[section]`` without the keys that never change the numbers: a rule's params.

    Parameters
    ----------
    config : mapping
        The validated study config.
    section : str
        The section's name.
    keys : sequence of str, optional
        Keep only these sub-sections: those the rule's stage reads. A rule whose params held
        the whole section would rerun for a key it never reads (``lifecycle.uncertainty``
        changes the compare stage's band, not the fit of ``lifecycle.zarr``). A key the
        validated section lacks raises ``KeyError`` (a misspelt key would otherwise hand the
        stage an empty sub-section, filled with the schema's defaults).
    """
    out = scheduling_free(section, config.get(section, {}))
    return out if keys is None else {k: out[k] for k in keys}


@contextlib.contextmanager
def logged(log: str | os.PathLike[str] | None, name: str = "moorlife.stages") -> Iterator[logging.Logger]:
    """The logger ``name`` (a child of ``moorlife``), sent to the rule's log file when ``log`` is
    a path (:func:`moorlife.io.log_to`).

    BLAS is limited to one thread inside the block either way: the model's set-up uses BLAS,
    whose sums depend on its thread count, so a runner called without a log (a test, a
    notebook) must give the bits of the rule, whatever ``OMP_NUM_THREADS`` says.
    """
    if log is None:
        from threadpoolctl import threadpool_limits

        with threadpool_limits(limits=1):
            yield logging.getLogger(name)
        return
    from moorlife.io import log_to

    with log_to(log):
        yield logging.getLogger(name)


def thrust_for(
    settings: Any, platform_cfg: str | os.PathLike[str] | None, wind: Mapping[str, Any] | None = None
) -> Any:
    """The thrust coordinate of ``config/platform.yaml`` when the RBF fit may use the thrust space.

    ``settings`` is a :class:`moorlife.lifecycle.RBFSettings`; None unless ``choose`` is
    ``per_output`` or ``stack`` with ``"thrust"`` among its ``spaces``, ``global`` with ``space`` ``"thrust"``,
    or ``method`` is ``gp`` with ``gp.thrust`` (the lifecycle, rounds and replicates stages).
    The steady curve (:class:`moorlife.lifecycle.ThrustCurve`), or with
    ``thrust.statistic: turbulent_sd`` its turbulent thrust
    (:class:`moorlife.lifecycle.TurbulentThrust`), which needs ``wind``: the ``simulation.wind``
    section (read from the config, not a rule parameter: a change of it reruns the simulations,
    an input of every stage that fits).
    """
    from moorlife import lifecycle, names
    from moorlife.io.platform import read_platform_config

    gp_thrust = settings.method == "gp" and settings.gp.thrust
    per_output = settings.choose in ("per_output", "stack")
    candidates = settings.spaces if per_output else (settings.space,)
    if not gp_thrust and names.RBF_SPACE_THRUST not in candidates:
        return None
    if platform_cfg is None:
        key = "gp.thrust is true" if gp_thrust else ("spaces has" if per_output else "space is") + " 'thrust'"
        raise ValueError(f"lifecycle.rbf.{key}: the stage needs platform_cfg (config/platform.yaml)")
    platform = read_platform_config(platform_cfg)
    curve = lifecycle.thrust_curve(platform, str(platform_cfg))
    if settings.thrust_statistic == "steady":
        return curve
    if wind is None:
        raise ValueError(
            f"lifecycle.rbf.thrust.statistic = {settings.thrust_statistic!r}: the stage needs simulation.wind"
        )
    height = float(platform["turbine"]["hub_height"])
    return lifecycle.turbulent_thrust(curve, {**wind, "height": height}, settings.thrust_averaging_time)
