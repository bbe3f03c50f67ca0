"""Rule metocean_figures: wind rose, wave rose and Hs-Tp scatter of the hindcast (paper Fig. 3)."""

from moorlife.stages import metocean


def main(smk) -> None:
    metocean.figures(**smk.input, **smk.output, **smk.params, log=smk.log[0])


if __name__ == "__main__":
    main(snakemake)  # noqa: F821
