"""Rule sensitivity_cases: n_seeds copies of the section 4.2 sea state -> seed_cases.zarr."""

from moorlife.stages import sensitivity


def main(smk) -> None:
    sensitivity.cases(**smk.input, **smk.output, **smk.params, log=smk.log[0])


if __name__ == "__main__":
    main(snakemake)  # noqa: F821
