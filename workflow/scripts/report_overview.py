"""Rule report_overview: summary.csv + recommendation.yaml -> the report's opening page (rst)."""

from moorlife.io import log_to
from moorlife.io.report import write_overview


def main(smk) -> None:
    with log_to(smk.log[0]):
        write_overview(smk.input.summary, smk.input.recommendation, smk.output[0])


if __name__ == "__main__":
    main(snakemake)  # noqa: F821
