"""Rule selection: MDA training + validation sea states -> results/selection/cases.zarr."""

from moorlife.stages import selection


def main(smk) -> None:
    selection.run(**smk.input, **smk.output, **smk.params, log=smk.log[0])


if __name__ == "__main__":
    main(snakemake)  # noqa: F821
