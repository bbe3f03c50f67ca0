"""Rule lifecycle: hindcast + cases + simulations -> results/{ms}/lifecycle.zarr."""

from moorlife.io import log_to
from moorlife.io.lifecycle import lifecycle_store


def main(smk) -> None:
    with log_to(smk.log[0]):
        lifecycle_store(smk.input.hindcast, smk.input.cases, smk.input.simulations, smk.output[0],
                        lifecycle_cfg=smk.params.lifecycle, fatigue_cfg=smk.params.fatigue, threads=smk.threads)


if __name__ == "__main__":
    main(snakemake)  # noqa: F821
