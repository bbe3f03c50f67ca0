"""Rule lifecycle_figures: results/{ms}/lifecycle.zarr -> validation, LOO map, damage vs metocean."""

from moorlife.stages import lifecycle


def main(smk) -> None:
    lifecycle.figures(**smk.input, **smk.output, **smk.params, log=smk.log[0], ms=smk.wildcards.ms)


if __name__ == "__main__":
    main(snakemake)  # noqa: F821
