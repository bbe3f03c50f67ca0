"""Rule truth_hours: results/metocean/hindcast.zarr -> results/truth/hours.zarr (the truth window)."""

from moorlife.io import log_to
from moorlife.stages.truth import hours_store


def main(smk) -> None:
    with log_to(smk.log[0]):
        w = smk.params.window
        hours_store(smk.input[0], smk.output[0], start=w["start"], end=w["end"], stride=smk.params.stride)


if __name__ == "__main__":
    main(snakemake)  # noqa: F821
