"""Rule truth_hours_seed2: results/truth/hours.zarr -> hours_seed2.zarr (the noise-floor subset)."""

from moorlife.io import log_to
from moorlife.stages.truth import seed2_store


def main(smk) -> None:
    with log_to(smk.log[0]):
        seed2_store(smk.input[0], smk.output[0], n=smk.params.n, storm=smk.params.storm)


if __name__ == "__main__":
    main(snakemake)  # noqa: F821
