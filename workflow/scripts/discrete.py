"""Rule discrete: the conventional scatter-matrix sea states -> results/selection/discrete.zarr."""

from moorlife.io import log_to, open_zarr, write_zarr
from moorlife.selection import discrete_states


def main(smk) -> None:
    with log_to(smk.log[0]):
        p = smk.params
        hindcast = open_zarr(smk.input[0])
        ds = discrete_states(
            hindcast, hs_edges=p.hs_edges, wind_edges=p.wind_edges, tp_edges=p.tp_edges, sector=p.sector,
            source=smk.input[0],
        )
        write_zarr(ds, smk.output[0])


if __name__ == "__main__":
    main(snakemake)  # noqa: F821
