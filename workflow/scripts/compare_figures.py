"""Rule compare_figures: summary.csv + lifecycle stores -> Fig. 20, Table 7 analogue, offsets, recommendation."""

from moorlife.stages import compare


def main(smk) -> None:
    compare.figures(**smk.input, **smk.output, **smk.params, log=smk.log[0])


if __name__ == "__main__":
    main(snakemake)  # noqa: F821
