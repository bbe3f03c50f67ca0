"""Figures of the selection stage: the hindcast cloud with the selected states (paper Fig. 6)
and the conventional discrete sea states (paper Fig. 19)."""

from __future__ import annotations

import numpy as np
import xarray as xr
from matplotlib.colors import LogNorm
from matplotlib.figure import Figure

from moorlife import names

__all__ = ["axis_label", "plot_selection_cloud", "plot_discrete_states"]

_SYMBOL = {"wind_speed": "W", "wind_dir": "beta", "hs": "Hs", "tp": "Tp", "wave_dir": "alpha"}
_UNIT = {"m s-1": "m/s", "degree": "deg"}


def axis_label(var: str) -> str:
    """``"Hs [m]"``-style label of a metocean variable."""
    unit = names.METOCEAN_ATTRS[var]["units"]
    return f"{_SYMBOL.get(var, var)} [{_UNIT.get(unit, unit)}]"


def _limits(values: np.ndarray, var: str) -> tuple[float, float]:
    if var in names.DIRECTION_VARS:
        return 0.0, 360.0
    return 0.0, float(np.max(values)) * 1.03


def _density(ax, x: np.ndarray, y: np.ndarray, xlim, ylim, bins: int = 120):
    """Grey log-density of the hindcast hours (fast for 10^5-10^6 points)."""
    h, xe, ye = np.histogram2d(x, y, bins=bins, range=[xlim, ylim])
    h = np.ma.masked_equal(h, 0.0)
    return ax.pcolormesh(xe, ye, h.T, cmap="Greys", norm=LogNorm(vmin=1, vmax=max(h.max(), 2)), rasterized=True)


def plot_selection_cloud(hindcast: xr.Dataset, cases: xr.Dataset) -> Figure:
    """The hindcast and the selected sea states in every 2-D projection (paper Fig. 6).

    Parameters
    ----------
    hindcast : xarray.Dataset
        Dim ``time``; the five metocean variables.
    cases : xarray.Dataset
        ``results/selection/cases.zarr``: dim ``case``; the five variables and ``role``.

    Returns
    -------
    matplotlib.figure.Figure
        Lower triangle of the pairs of (W, beta, Hs, Tp, alpha): hindcast hours as a grey
        log-density, training states (MDA) as red dots, validation states as blue crosses.
    """
    vars_ = list(names.METOCEAN_VARS)
    n = len(vars_)
    role = cases["role"].values  # numpy StringDType after a Zarr round trip: compare, never cast
    train, valid = np.asarray(role == "train", bool), np.asarray(role == "validate", bool)
    fig = Figure(figsize=(13, 12), layout="constrained")
    axes = fig.subplots(n - 1, n - 1, squeeze=False)
    mesh = None
    for r in range(1, n):
        for c in range(n - 1):
            ax = axes[r - 1, c]
            if c >= r:
                ax.set_axis_off()
                continue
            xv, yv = vars_[c], vars_[r]
            x, y = hindcast[xv].values, hindcast[yv].values
            xlim, ylim = _limits(x, xv), _limits(y, yv)
            mesh = _density(ax, x, y, xlim, ylim)
            cx, cy = cases[xv].values, cases[yv].values
            ax.scatter(cx[train], cy[train], s=4, c="tab:red", lw=0, label="training (MDA)")
            ax.scatter(cx[valid], cy[valid], s=12, c="tab:blue", marker="x", lw=0.8, label="validation")
            ax.set_xlim(xlim)
            ax.set_ylim(ylim)
            if r == n - 1:
                ax.set_xlabel(axis_label(xv))
            if c == 0:
                ax.set_ylabel(axis_label(yv))
    handles, labels = axes[1, 0].get_legend_handles_labels() if n > 2 else axes[0, 0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="upper right", bbox_to_anchor=(0.98, 0.98), markerscale=3, frameon=False)
    if mesh is not None:
        fig.colorbar(mesh, ax=axes[0, -1], location="left", shrink=0.8, label="hindcast hours per cell")
    n_t, n_v = int(train.sum()), int(valid.sum())
    fig.suptitle(
        f"Maximum dissimilarity selection: {n_t} training + {n_v} validation states "
        f"out of {hindcast.sizes[names.TIME]:,} hourly sea states"
    )
    return fig


def plot_discrete_states(hindcast: xr.Dataset, discrete: xr.Dataset) -> Figure:
    """The conventional discrete sea states over the hindcast (paper Fig. 19).

    Parameters
    ----------
    hindcast : xarray.Dataset
        Dim ``time``; the five metocean variables.
    discrete : xarray.Dataset
        ``results/selection/discrete.zarr``: dim ``bin``; the five variables, ``probability``,
        and the attributes ``hs_edges``, ``wind_edges``, ``tp_edges``.

    Returns
    -------
    matplotlib.figure.Figure
        (a) Hs-W and (b) Hs-Tp planes: hindcast density, class edges, representative states
        sized by probability and numbered; (c) probability of occurrence per bin;
        (d) the representative wave and wind directions per bin.
    """
    fig = Figure(figsize=(13, 9), layout="constrained")
    (ax_w, ax_tp), (ax_p, ax_d) = fig.subplots(2, 2)
    p = discrete["probability"].values
    size = 20.0 + 1200.0 * p / max(p.max(), 1e-12)
    num = np.arange(1, p.size + 1)
    hs_e = list(discrete.attrs.get("hs_edges", []))
    for ax, var, edges_key in ((ax_w, "wind_speed", "wind_edges"), (ax_tp, "tp", "tp_edges")):
        x, y = hindcast[var].values, hindcast["hs"].values
        xlim, ylim = _limits(x, var), _limits(y, "hs")
        _density(ax, x, y, xlim, ylim)
        for e in discrete.attrs.get(edges_key, [])[1:]:
            ax.axvline(e, color="0.4", lw=0.8, ls="--")
        for e in hs_e[1:]:
            ax.axhline(e, color="0.4", lw=0.8, ls="--")
        ax.scatter(discrete[var].values, discrete["hs"].values, s=size, facecolor="none", edgecolor="tab:red", lw=1.2)
        for k, (xi, yi) in enumerate(zip(discrete[var].values, discrete["hs"].values, strict=True)):
            ax.annotate(str(num[k]), (xi, yi), fontsize=7, ha="center", va="center", color="tab:red")
        ax.set_xlim(xlim)
        ax.set_ylim(ylim)
        ax.set_xlabel(axis_label(var))
        ax.set_ylabel(axis_label("hs"))
    ax_w.set_title("(a) representative states, Hs-W (size ~ probability)")
    ax_tp.set_title("(b) representative states, Hs-Tp")
    ax_p.bar(num, 100.0 * p, color="tab:red")
    ax_p.set_xlabel("discrete sea state")
    ax_p.set_ylabel("occurrence [%]")
    ax_p.set_title(f"(c) probability of occurrence ({p.size} non-empty bins)")
    ax_d.scatter(num, discrete["wave_dir"].values, marker="o", c="tab:blue", label="alpha (waves)")
    ax_d.scatter(num, discrete["wind_dir"].values, marker="^", c="tab:green", label="beta (wind)")
    ax_d.set_ylim(0, 360)
    ax_d.set_yticks(np.arange(0, 361, 45))
    ax_d.set_xlabel("discrete sea state")
    ax_d.set_ylabel("most likely direction, coming from [deg]")
    sector = float(discrete.attrs.get("direction_sector", np.nan))
    ax_d.set_title(f"(d) most likely directions ({sector:g}-deg sectors)")
    ax_d.legend(frameon=False)
    for ax in (ax_p, ax_d):
        ax.set_xticks(num)
        ax.tick_params(axis="x", labelsize=6)
    fig.suptitle("Conventional discrete sea states: hindcast binned by Hs, then W, then Tp")
    return fig
