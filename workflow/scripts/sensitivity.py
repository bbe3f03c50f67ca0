"""Rule sensitivity: seed spread (Fig. 21), corrosion evolution (Fig. 22), mean-stress factors (Table 8)."""

from moorlife.io import log_to
from moorlife.io.lifecycle import sensitivity_outputs


def main(smk) -> None:
    with log_to(smk.log[0]):
        i, p = smk.input, smk.params
        sensitivity_outputs(
            i.seeds, i.lifecycle, list(i.lifecycles), i.mooring, dict(smk.output.items()),
            systems=p.systems, mooring_system=p.ms, corrosion_line=p.line, fatigue_cfg=p.fatigue,
        )


if __name__ == "__main__":
    main(snakemake)  # noqa: F821
