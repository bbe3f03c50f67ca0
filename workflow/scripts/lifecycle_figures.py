"""Rule lifecycle_figures: results/{ms}/lifecycle.zarr -> validation, LOO map, damage vs metocean."""

from moorlife.io import log_to
from moorlife.io.lifecycle import lifecycle_figures


def main(smk) -> None:
    with log_to(smk.log[0]):
        lifecycle_figures(smk.input[0], dict(smk.output.items()), mooring_system=smk.wildcards.ms)


if __name__ == "__main__":
    main(snakemake)  # noqa: F821
