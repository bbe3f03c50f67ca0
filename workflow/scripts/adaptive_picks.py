"""Rule adaptive_picks: the fit so far -> results/{ms}/rounds/picks_{r}.zarr (adaptive round r)."""

from moorlife.stages import rounds


def main(smk) -> None:
    # simulation.wind (the turbulent thrust coordinate): from the config, not a param; a change
    # of it reruns the simulations, an input
    rounds.run(**smk.input, **smk.output, **smk.params, wind=smk.config["simulation"]["wind"], log=smk.log[0])


if __name__ == "__main__":
    main(snakemake)  # noqa: F821
