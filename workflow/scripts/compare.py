"""Rule compare: every lifecycle.zarr and discrete.zarr -> summary.csv + recommendation.yaml."""

from moorlife.stages import compare


def main(smk) -> None:
    compare.run(**smk.input, **smk.output, **smk.params, log=smk.log[0])


if __name__ == "__main__":
    main(snakemake)  # noqa: F821
