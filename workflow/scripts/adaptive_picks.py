"""Rule adaptive_picks: the fit so far -> results/{ms}/rounds/picks_{r}.zarr (adaptive round r)."""

from moorlife.stages import rounds


def main(smk) -> None:
    rounds.run(**smk.input, **smk.output, **smk.params, log=smk.log[0])


if __name__ == "__main__":
    main(snakemake)  # noqa: F821
