"""Rule metocean: build the hourly hindcast (synthetic or from a file) as a Zarr store."""

from moorlife.io import log_to, write_zarr
from moorlife.metocean import build_hindcast


def main(smk) -> None:
    with log_to(smk.log[0]):
        ds = build_hindcast(dict(smk.params.hindcast), int(smk.params.seed), base_dir=".")
        write_zarr(ds, smk.output[0])


if __name__ == "__main__":
    main(snakemake)  # noqa: F821
