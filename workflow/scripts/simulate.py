"""Rules simulate_cases / simulate_discrete: sea states -> results/{ms}/simulations.zarr | discrete.zarr."""

from moorlife.io import log_to
from moorlife.io.simulation import simulate_store


def main(smk) -> None:
    with log_to(smk.log[0]) as log:
        p = smk.params
        simulate_store(
            smk.input.cases, smk.input.platform, smk.input.platform_cfg, smk.output[0], dim=p.dim,
            mooring_system=p.ms, mooring_row=p.row, seed=p.seed, sim_cfg=p.simulation, mooring_cfg=p.mooring,
            fatigue_cfg=p.fatigue, stats_cfg=p.statistics, threads=smk.threads, log=log,
        )


if __name__ == "__main__":
    main(snakemake)  # noqa: F821
