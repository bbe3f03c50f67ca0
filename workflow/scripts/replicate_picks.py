"""Rule replicate_picks: the fit -> results/{ms}/replicates/picks.zarr (states to replicate)."""

from moorlife.stages import replicates


def main(smk) -> None:
    # simulation.wind (the turbulent thrust coordinate): from the config, not a param; a change
    # of it reruns the simulations, an input
    replicates.run(**smk.input, **smk.output, **smk.params, wind=smk.config["simulation"]["wind"], log=smk.log[0])


if __name__ == "__main__":
    main(snakemake)  # noqa: F821
