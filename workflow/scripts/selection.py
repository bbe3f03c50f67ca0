"""Rule selection: MDA training + validation sea states -> results/selection/cases.zarr."""

from moorlife.io import log_to, open_zarr, write_zarr
from moorlife.selection import select_cases


def main(smk) -> None:
    with log_to(smk.log[0]):
        p = smk.params
        hindcast = open_zarr(smk.input[0])
        cases = select_cases(
            hindcast, n_train=p.n_train, n_validate=p.n_validate, rule=p.rule, seed=p.seed, source=smk.input[0]
        )
        write_zarr(cases, smk.output[0])


if __name__ == "__main__":
    main(snakemake)  # noqa: F821
