"""Figures of the metocean stage (paper Fig. 3): wind rose, wave rose, Hs-Tp scatter."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import numpy.typing as npt
import xarray as xr
from matplotlib import colormaps
from matplotlib.colors import LogNorm
from matplotlib.figure import Figure

from moorlife.metocean import G_2PI

__all__ = ["rose_frequencies", "plot_rose", "plot_wind_rose", "plot_wave_rose", "plot_hs_tp"]

#: Speed classes of the wind rose (m/s at hub height) and height classes of the wave rose (m).
WIND_CLASSES: tuple[float, ...] = (0.0, 4.0, 8.0, 12.0, 16.0, 20.0, 25.0)
HS_CLASSES: tuple[float, ...] = (0.0, 1.0, 2.0, 3.0, 4.5, 6.0)
#: Steepness curves drawn on the Hs-Tp scatter, Hs / (1.56 Tp^2).
STEEPNESS_LINES: tuple[float, ...] = (1.0 / 15.0, 1.0 / 25.0)


def rose_frequencies(
    direction: npt.ArrayLike, magnitude: npt.ArrayLike, n_sectors: int, edges: Sequence[float]
) -> np.ndarray:
    """Percentage of hours per direction sector and magnitude class.

    Parameters
    ----------
    direction : array_like, shape (n,)
        Degrees, coming from; sectors are centred on north, ``360 / n_sectors`` wide.
    magnitude : array_like, shape (n,)
        Wind speed or Hs.
    n_sectors : int
    edges : sequence of float, shape (k,)
        Lower class edges; the last class is open-ended.

    Returns
    -------
    numpy.ndarray, shape (n_sectors, k)
        Percent of all hours; sums to 100.
    """
    d = np.asarray(direction, float) % 360.0
    width = 360.0 / n_sectors
    sector = np.floor((d + width / 2.0) / width).astype(int) % n_sectors
    cls = np.clip(
        np.searchsorted(np.asarray(edges, float), np.asarray(magnitude, float), side="right") - 1, 0, len(edges) - 1
    )
    counts = np.zeros((n_sectors, len(edges)))
    np.add.at(counts, (sector, cls), 1.0)
    return 100.0 * counts / max(d.size, 1)


def plot_rose(
    direction: npt.ArrayLike,
    magnitude: npt.ArrayLike,
    edges: Sequence[float],
    *,
    label: str,
    title: str,
    n_sectors: int = 16,
    cmap: str = "viridis",
) -> Figure:
    """A stacked polar bar rose (north up, clockwise, "coming from")."""
    freq = rose_frequencies(direction, magnitude, n_sectors, edges)
    theta = np.deg2rad(np.arange(n_sectors) * 360.0 / n_sectors)
    width = 2.0 * np.pi / n_sectors * 0.9
    fig = Figure(figsize=(6.5, 6.0), layout="constrained")
    ax = fig.add_subplot(projection="polar")
    ax.set_theta_zero_location("N")
    ax.set_theta_direction(-1)
    colors = colormaps[cmap](np.linspace(0.05, 0.95, len(edges)))
    bottom = np.zeros(n_sectors)
    for j, lo in enumerate(edges):
        hi = f"{edges[j + 1]:g}" if j + 1 < len(edges) else ""
        ax.bar(
            theta,
            freq[:, j],
            width=width,
            bottom=bottom,
            color=colors[j],
            edgecolor="white",
            linewidth=0.4,
            label=f"{lo:g}-{hi} {label}" if hi else f">= {lo:g} {label}",
        )
        bottom += freq[:, j]
    ax.set_xticks(np.deg2rad(np.arange(0, 360, 45)), ["N", "NE", "E", "SE", "S", "SW", "W", "NW"])
    ax.yaxis.set_major_formatter("{x:g} %")
    ax.set_title(title)
    ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize=8, frameon=False)
    return fig


def _site(ds: xr.Dataset) -> str:
    site = ds.attrs.get("site", "")
    t = ds["time"].values
    return f"{site}, {str(t[0])[:4]}-{str(t[-1])[:4]}".strip(", ")


def plot_wind_rose(ds: xr.Dataset, n_sectors: int = 16) -> Figure:
    """Wind rose at hub height (paper Fig. 3): frequency by direction and speed class."""
    return plot_rose(
        ds["wind_dir"].values,
        ds["wind_speed"].values,
        WIND_CLASSES,
        label="m/s",
        n_sectors=n_sectors,
        title=f"Wind at {ds.attrs.get('hub_height', 0):g} m, {_site(ds)}",
    )


def plot_wave_rose(ds: xr.Dataset, n_sectors: int = 16) -> Figure:
    """Wave rose (paper Fig. 3): frequency by wave direction and Hs class."""
    return plot_rose(
        ds["wave_dir"].values,
        ds["hs"].values,
        HS_CLASSES,
        label="m",
        n_sectors=n_sectors,
        cmap="plasma",
        title=f"Waves (Hs), {_site(ds)}",
    )


def plot_hs_tp(ds: xr.Dataset, bins: int = 120) -> Figure:
    """Hs-Tp scatter (paper Fig. 3) as a log density of hours, with steepness limits.

    Left: Hs against Tp with the curves ``Hs = s * 1.56 Tp^2`` for s = 1/15 and 1/25.
    Right: Hs against hub-height wind speed, showing that the largest waves come with the
    strongest winds.
    """
    hs, tp, w = (ds[v].values for v in ("hs", "tp", "wind_speed"))
    fig = Figure(figsize=(11.0, 4.8), layout="constrained")
    ax1, ax2 = fig.subplots(1, 2)
    hmax = float(np.max(hs)) * 1.05
    for ax, x, xlab in ((ax1, tp, "Tp [s]"), (ax2, w, "W [m/s] at hub height")):
        xmax = float(np.max(x)) * 1.03
        h, xe, ye = np.histogram2d(x, hs, bins=bins, range=[[0.0, xmax], [0.0, hmax]])
        mesh = ax.pcolormesh(
            xe,
            ye,
            np.ma.masked_equal(h, 0.0).T,
            cmap="viridis",
            norm=LogNorm(vmin=1, vmax=max(h.max(), 2)),
            rasterized=True,
        )
        ax.set_xlabel(xlab)
        ax.set_ylabel("Hs [m]")
        ax.set_xlim(0.0, xmax)
        ax.set_ylim(0.0, hmax)
        ax.grid(alpha=0.3)
    t = np.linspace(0.1, float(np.max(tp)) * 1.03, 200)
    for s, frac in zip(STEEPNESS_LINES, np.linspace(0.92, 0.75, len(STEEPNESS_LINES))):
        ax1.plot(t, s * G_2PI * t**2, "k--", lw=0.9)
        t_lab = min(float(np.sqrt(frac * hmax / (s * G_2PI))), t[-1])
        ax1.annotate(
            f"s = 1/{1 / s:.0f}",
            (t_lab, s * G_2PI * t_lab**2),
            fontsize=8,
            ha="right",
            va="center",
            xytext=(-4, 0),
            textcoords="offset points",
        )
    fig.colorbar(mesh, ax=[ax1, ax2], label="hours per bin")
    fig.suptitle(f"Hs-Tp and Hs-W, {_site(ds)} ({hs.size:,} hours)")
    return fig
