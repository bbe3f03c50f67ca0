"""Rule sensitivity_cases: n_seeds copies of the section 4.2 sea state -> seed_cases.zarr."""

from moorlife.io import log_to
from moorlife.io.lifecycle import seed_cases_store


def main(smk) -> None:
    with log_to(smk.log[0]):
        p = smk.params
        seed_cases_store(smk.output[0], sea_state=p.sea_state, n_seeds=p.n_seeds, case_offset=p.case_offset)


if __name__ == "__main__":
    main(snakemake)  # noqa: F821
