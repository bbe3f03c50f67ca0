# Helpers shared by every stage: config validation, the mooring-system table, targets.
import os

from moorlife.config import validate_config
from moorlife.io import read_mooring_systems, read_yaml

# Validate before any work: unknown keys, wrong types and bad values stop here, naming the key.
_cfg_sources = ", ".join(str(f) for f in workflow.configfiles) or "config"
config.update(
    validate_config(
        config, read_yaml(workflow.source_path("../schemas/config.schema.yaml")), _cfg_sources
    )
)
MOORING = read_mooring_systems(config["mooring_systems"])
MS_IDS = list(MOORING.index)


def mooring_row(ms):
    """The mooring-system table row of one system, as a plain dict (passed as params)."""
    return {k: (v.item() if hasattr(v, "item") else v) for k, v in MOORING.loc[ms].items()}


def _outputs(*rule_objs):
    return [str(f) for r in rule_objs for f in r.output]


def final_targets():
    """Targets of the default run (every stage, for every mooring system)."""
    shared = _outputs(
        rules.metocean,
        rules.metocean_figures,
        rules.selection,
        rules.discrete,
        rules.selection_figures,
        rules.hydro,
        rules.compare,
        rules.compare_figures,
    )
    if config["lifecycle"]["sensitivity"]["mooring_system"] in MS_IDS:
        shared += _outputs(rules.sensitivity)
    per_ms = _outputs(rules.simulate_cases, rules.simulate_discrete, rules.lifecycle, rules.lifecycle_figures)
    return shared + expand(per_ms, ms=MS_IDS)
