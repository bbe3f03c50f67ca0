"""Rules truth_simulate / truth_simulate_seed2: truth hours -> results/{ms}/truth.zarr | truth_seed2.zarr."""

from moorlife.io import log_to
from moorlife.stages.truth import simulate


def main(smk) -> None:
    with log_to(smk.log[0]) as log:
        simulate(smk.input.cases, smk.input.platform, smk.input.platform_cfg, smk.output[0],
                 stream=smk.params.stream, params=smk.params, threads=smk.threads, log=log)


if __name__ == "__main__":
    main(snakemake)  # noqa: F821
