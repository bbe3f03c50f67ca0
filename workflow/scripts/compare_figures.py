"""Rule compare_figures: summary.csv + lifecycle stores -> Fig. 20, Table 7 analogue, offsets, recommendation."""

from moorlife.io import log_to
from moorlife.io.lifecycle import compare_figures


def main(smk) -> None:
    with log_to(smk.log[0]):
        i = smk.input
        compare_figures(i.summary, i.recommendation, list(i.lifecycle), dict(smk.output.items()),
                        systems=smk.params.systems)


if __name__ == "__main__":
    main(snakemake)  # noqa: F821
