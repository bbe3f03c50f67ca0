"""Rule lifecycle: hindcast + cases + simulations -> results/{ms}/lifecycle.zarr."""

from moorlife.stages import lifecycle


def main(smk) -> None:
    # lifecycle.rbf.chunk_rows changes memory only: read from the config, not a param (no rerun)
    lifecycle.run(
        **smk.input,
        **smk.output,
        **smk.params,
        log=smk.log[0],
        threads=smk.threads,
        chunk_rows=smk.config["lifecycle"]["rbf"]["chunk_rows"],
    )


if __name__ == "__main__":
    main(snakemake)  # noqa: F821
