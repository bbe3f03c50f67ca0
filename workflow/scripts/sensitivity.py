"""Rule sensitivity: seed spread (Fig. 21), corrosion evolution (Fig. 22), mean-stress factors (Table 8)."""

from moorlife.stages import sensitivity


def main(smk) -> None:
    sensitivity.run(**smk.input, **smk.output, **smk.params, log=smk.log[0])


if __name__ == "__main__":
    main(snakemake)  # noqa: F821
