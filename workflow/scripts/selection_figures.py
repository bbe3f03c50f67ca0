"""Rule selection_figures: paper Fig. 6 (selection cloud) and Fig. 19 (discrete states)."""

from moorlife.stages import selection


def main(smk) -> None:
    selection.figures(**smk.input, **smk.output, **smk.params, log=smk.log[0])


if __name__ == "__main__":
    main(snakemake)  # noqa: F821
