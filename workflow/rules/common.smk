# Helpers shared by every stage: config validation, the mooring-system table, targets.
import os

from snakemake.exceptions import WorkflowError

from moorlife.hydro import bem_settings
from moorlife.io import read_yaml
from moorlife.stages import result_settings
from moorlife.stages.check import check_study, check_truth

# Validate before any work: unknown keys, wrong types and bad values stop here, naming the key.
# The same function is the pre-flight command `python -m moorlife.stages.check --configfile ...`.
_cfg_sources = ", ".join(str(f) for f in workflow.configfiles) or "config"
STUDY = check_study(config, read_yaml(workflow.source_path("../schemas/config.schema.yaml")), _cfg_sources)
config.update(STUDY.config)
MOORING = STUDY.mooring
MS_IDS = list(MOORING.index)


def all_cores():
    """The run's ``--cores``, for the rules that use every core of their job.

    ``workflow.cores`` raises "Workflow requires a total number of cores" when the run has no
    ``--cores``: ``snakemake --unlock``, ``--report``, and a cluster executor given ``--jobs``
    only. Those get 1 (nothing runs under ``--unlock``; the SLURM profile sizes these rules with
    ``set-threads``, which overrides this value).
    """
    try:
        return workflow.cores
    except WorkflowError:
        return 1


# The sensitivity study (sensitivity.smk); its seed realisations feed compare's fatigue-life
# band when the sensitivity system is studied.
SENS = config["lifecycle"]["sensitivity"]
SENS_MS = SENS["mooring_system"]
SEEDS = ["results/sensitivity/seeds.zarr"] if SENS_MS in MS_IDS else []


# Adaptive selection (rounds.smk): rounds 1..k per system, numbered at parse time. MDA picks
# selection.n_train - k x per_round - states x seeds (the budget is checked by validate_config).
ADAPTIVE = config["lifecycle"]["adaptive"]
ROUNDS = list(range(1, ADAPTIVE["rounds"] + 1))
# Seed replicates (replicates.smk): lifecycle.replicates.seeds more records of .states states.
REPLICATES = config["lifecycle"]["replicates"]
REPLICATE_SEEDS = list(range(1, REPLICATES["seeds"] + 1)) if REPLICATES["states"] else []
N_MDA = (
    config["selection"]["n_train"] - len(ROUNDS) * ADAPTIVE["per_round"] - len(REPLICATE_SEEDS) * REPLICATES["states"]
)


# What a system's reconstruction is fitted on: the lifecycle rule's inputs, and the truth
# comparison's, which refits it for the records' term of its window.
FIT_INPUTS = dict(
    cases="results/selection/cases.zarr",
    simulations="results/{ms}/simulations.zarr",
    platform_cfg=config["platform"],
    rounds=expand("results/{{ms}}/rounds/picks_{r}.zarr", r=ROUNDS),
    round_simulations=expand("results/{{ms}}/rounds/simulations_{r}.zarr", r=ROUNDS),
    replicates=expand("results/{{ms}}/replicates/simulations_{j}.zarr", j=REPLICATE_SEEDS),
)


def earlier_rounds(kind):
    """Input function: the ``kind`` stores (picks or simulations) of the rounds before ``{r}``."""

    def stores(wildcards):
        r = int(wildcards.r)
        if not 1 <= r <= len(ROUNDS):
            raise ValueError(f"adaptive round {r} is not in 1 .. lifecycle.adaptive.rounds = {len(ROUNDS)}")
        return [f"results/{wildcards.ms}/rounds/{kind}_{i}.zarr" for i in range(1, r)]

    return stores


def mooring_row(ms):
    """The mooring-system table row of one system, as a plain dict (passed as params)."""
    return {k: (v.item() if hasattr(v, "item") else v) for k, v in MOORING.loc[ms].items()}


def _hindcast_file(wildcards):
    """The hindcast file when it is the source (so editing it reruns the rule), else nothing."""
    h = config["hindcast"]
    return [h["path"]] if h["source"] == "file" and h.get("path") else []


def _hydro_inputs(wildcards):
    """The WAMIT files when they are the source (so editing them reruns the rule), else nothing."""
    if config["hydro"]["source"] != "wamit":
        return []
    prefix = config["hydro"]["wamit_prefix"]
    if not prefix:
        raise ValueError("config hydro.wamit_prefix is required when hydro.source is 'wamit'")
    exts = ["1", "3", "hst"] + (["12d"] if os.path.exists(f"{prefix}.12d") else [])
    return [f"{prefix}.{e}" for e in exts]


def truth_checked_hindcast(wildcards):
    """The hindcast (input of truth_hours), after checking the truth keys (names key and value)."""
    check_truth(config, _cfg_sources)
    return "results/metocean/hindcast.zarr"


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
        rules.report_overview,
    )
    if config["lifecycle"]["sensitivity"]["mooring_system"] in MS_IDS:
        shared += _outputs(rules.sensitivity)
    per_ms = _outputs(rules.simulate_cases, rules.simulate_discrete, rules.lifecycle, rules.lifecycle_figures)
    return shared + expand(per_ms, ms=MS_IDS)
