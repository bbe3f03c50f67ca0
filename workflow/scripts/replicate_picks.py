"""Rule replicate_picks: the fit -> results/{ms}/replicates/picks.zarr (states to replicate)."""

from moorlife.stages import replicates


def main(smk) -> None:
    replicates.run(**smk.input, **smk.output, **smk.params, log=smk.log[0])


if __name__ == "__main__":
    main(snakemake)  # noqa: F821
