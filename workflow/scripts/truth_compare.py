"""Rule truth_compare: truth, lifecycle and bins of one system -> truth_comparison.zarr/.csv, figures."""

from moorlife.io import log_to
from moorlife.stages.truth import run

FIT = ("cases", "simulations", "platform_cfg", "rounds", "round_simulations", "replicates")


def main(smk) -> None:
    with log_to(smk.log[0]):
        i, p = smk.input, smk.params
        fit = {k: getattr(i, k) for k in FIT} | {"lifecycle": p.lifecycle, "wind": smk.config["simulation"]["wind"]}
        kw = dict(compared=p.outputs, mooring_system=smk.wildcards.ms, second_seed_storm=p.second_seed_storm, fit=fit)
        run(i.truth, i.seed2, i.lifecycle, i.states, i.discrete, dict(smk.output.items()), **kw)


if __name__ == "__main__":
    main(snakemake)  # noqa: F821
