"""Rule lifecycle: hindcast + cases + simulations -> results/{ms}/lifecycle.zarr."""

from moorlife.stages import lifecycle


def main(smk) -> None:
    # not params: chunk_rows is memory only; a change of simulation.wind reruns the simulations
    lifecycle.run(
        **smk.input,
        **smk.output,
        **smk.params,
        log=smk.log[0],
        threads=smk.threads,
        chunk_rows=smk.config["lifecycle"]["rbf"]["chunk_rows"],
        wind=smk.config["simulation"]["wind"],
    )


if __name__ == "__main__":
    main(snakemake)  # noqa: F821
