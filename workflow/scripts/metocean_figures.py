"""Rule metocean_figures: wind rose, wave rose and Hs-Tp scatter of the hindcast (paper Fig. 3)."""

import matplotlib

matplotlib.use("Agg")

from moorlife.io import log_to, open_zarr, save_figure  # noqa: E402
from moorlife.plots.metocean import plot_hs_tp, plot_wave_rose, plot_wind_rose  # noqa: E402


def main(smk) -> None:
    with log_to(smk.log[0]):
        ds = open_zarr(smk.input[0])
        save_figure(plot_wind_rose(ds), smk.output.wind_rose)
        save_figure(plot_wave_rose(ds), smk.output.wave_rose)
        save_figure(plot_hs_tp(ds), smk.output.hs_tp)


if __name__ == "__main__":
    main(snakemake)  # noqa: F821
