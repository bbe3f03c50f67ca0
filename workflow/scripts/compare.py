"""Rule compare: every lifecycle.zarr and discrete.zarr -> summary.csv + recommendation.yaml."""

from moorlife.io import log_to
from moorlife.io.lifecycle import compare_outputs


def main(smk) -> None:
    with log_to(smk.log[0]):
        i = smk.input
        compare_outputs(
            list(i.lifecycle), list(i.discrete), i.bins, i.mooring, smk.output.summary, smk.output.recommendation,
            systems=smk.params.systems, lifecycle_cfg=smk.params.lifecycle, fatigue_cfg=smk.params.fatigue,
            seeds=(list(i.seeds) or [None])[0],
        )


if __name__ == "__main__":
    main(snakemake)  # noqa: F821
