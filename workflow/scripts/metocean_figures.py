"""Rule metocean_figures: wind rose, wave rose and Hs-Tp scatter of the hindcast (paper Fig. 3)."""

import matplotlib

matplotlib.use("Agg")

from moorlife.io import log_to, open_zarr  # noqa: E402
from moorlife.plots.metocean import plot_hs_tp, plot_wave_rose, plot_wind_rose  # noqa: E402


def main(smk) -> None:
    with log_to(smk.log[0]):
        ds = open_zarr(smk.input[0])
        plot_wind_rose(ds).savefig(smk.output.wind_rose, dpi=150)
        plot_wave_rose(ds).savefig(smk.output.wave_rose, dpi=150)
        plot_hs_tp(ds).savefig(smk.output.hs_tp, dpi=150)


if __name__ == "__main__":
    main(snakemake)  # noqa: F821
