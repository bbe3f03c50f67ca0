"""Rule hydro: BEM (Capytaine) or WAMIT import -> results/hydro/platform.nc."""

from moorlife.stages import hydro


def main(smk) -> None:
    hydro.run(**smk.input, **smk.output, **smk.params, log=smk.log[0], threads=smk.threads)


if __name__ == "__main__":
    main(snakemake)  # noqa: F821
