"""Rule selection_figures: paper Fig. 6 (selection cloud) and Fig. 19 (discrete states)."""

from moorlife.io import log_to, open_zarr, save_figure
from moorlife.plots.selection import plot_discrete_states, plot_selection_cloud


def main(smk) -> None:
    with log_to(smk.log[0]):
        hindcast = open_zarr(smk.input.hindcast)
        save_figure(plot_selection_cloud(hindcast, open_zarr(smk.input.cases)), smk.output.cloud)
        save_figure(plot_discrete_states(hindcast, open_zarr(smk.input.discrete)), smk.output.discrete)


if __name__ == "__main__":
    main(snakemake)  # noqa: F821
