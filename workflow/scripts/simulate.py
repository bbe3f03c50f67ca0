"""Rules simulate_cases / simulate_discrete / sensitivity_seeds: sea states -> a simulation store."""

from moorlife.stages import simulate


def main(smk) -> None:
    # simulation.batch_size is scheduling only: read from the config, not a param (no rerun)
    simulate.run(
        **smk.input,
        **smk.output,
        **smk.params,
        log=smk.log[0],
        threads=smk.threads,
        batch_size=smk.config["simulation"]["batch_size"],
    )


if __name__ == "__main__":
    main(snakemake)  # noqa: F821
