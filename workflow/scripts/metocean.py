"""Rule metocean: build the hourly hindcast (synthetic or from a file) as a Zarr store."""

from moorlife.stages import metocean


def main(smk) -> None:
    metocean.run(**smk.input, **smk.output, **smk.params, log=smk.log[0])


if __name__ == "__main__":
    main(snakemake)  # noqa: F821
