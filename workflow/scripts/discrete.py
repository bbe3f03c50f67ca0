"""Rule discrete: the conventional scatter-matrix sea states -> results/selection/discrete.zarr."""

from moorlife.stages import selection


def main(smk) -> None:
    selection.discrete(**smk.input, **smk.output, **smk.params, log=smk.log[0])


if __name__ == "__main__":
    main(snakemake)  # noqa: F821
