"""Rule lifecycle: hindcast + cases + simulations -> results/{ms}/lifecycle.zarr."""

import os

# One BLAS thread (set before numpy loads): the RBF fit is then bitwise identical whatever the
# rule's threads; the prediction uses smk.threads numba threads, which never changes the numbers.
os.environ.update(OPENBLAS_NUM_THREADS="1", MKL_NUM_THREADS="1", OMP_NUM_THREADS="1")

from moorlife.io import log_to  # noqa: E402
from moorlife.io.lifecycle import lifecycle_store  # noqa: E402


def main(smk) -> None:
    with log_to(smk.log[0]):
        lifecycle_store(smk.input.hindcast, smk.input.cases, smk.input.simulations, smk.output[0],
                        lifecycle_cfg=smk.params.lifecycle, fatigue_cfg=smk.params.fatigue, threads=smk.threads)


if __name__ == "__main__":
    main(snakemake)  # noqa: F821
