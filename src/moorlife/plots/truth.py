"""Figures of the truth comparison: truth vs reconstruction per hour, cumulative window damage.

Every function takes in-memory data (xarray) and returns a :class:`matplotlib.figure.Figure`;
nothing here touches the disk or pyplot state.
"""

from __future__ import annotations

import math

import numpy as np
import xarray as xr
from matplotlib.figure import Figure
from matplotlib.ticker import NullFormatter

from moorlife import names

__all__ = ["truth_scatter", "cumulative_damage"]

_CURVE_LABEL = {"sn": "S-N", "tn": "T-N"}


def truth_scatter(cmp: xr.Dataset, *, title: str = "") -> Figure:
    """One panel per output: reconstruction against simulated truth over the window's hours.

    Each panel carries the bisector, r, and (when a second seed exists) the noise-floor r.
    """
    labels = [str(v) for v in cmp["output"].values]
    ncol = min(5, len(labels))
    nrow = math.ceil(len(labels) / ncol)
    fig = Figure(figsize=(3.0 * ncol, 2.8 * nrow), layout="constrained")
    axes = fig.subplots(nrow, ncol, squeeze=False)
    for j, lab in enumerate(labels):
        ax = axes.flat[j]
        t = cmp["truth"].values[:, j]
        r = cmp["reconstruction"].values[:, j]
        ax.scatter(t, r, s=4, alpha=0.5, color="tab:blue", edgecolors="none")
        lo, hi = float(np.nanmin([t.min(), r.min()])), float(np.nanmax([t.max(), r.max()]))
        ax.plot([lo, hi], [lo, hi], color="k", lw=0.8)
        if lab.startswith("damage") and lo > 0:
            ax.set_xscale("log")
            ax.set_yscale("log")
            for axis in (ax.xaxis, ax.yaxis):
                axis.set_minor_formatter(NullFormatter())
        text = f"r = {float(cmp['r'].values[j]):.3f}"
        if "ceiling_r" in cmp:
            text += f"\nceiling = {float(cmp['ceiling_r'].values[j]):.3f}"
        ax.text(0.04, 0.96, text, transform=ax.transAxes, va="top", fontsize=8)
        ax.set_title(lab, fontsize=9)
        ax.tick_params(labelsize=7)
    for ax in list(axes.flat)[len(labels) :]:
        ax.set_visible(False)
    fig.supxlabel("simulated truth")
    fig.supylabel("reconstruction (lifecycle.zarr)")
    fig.suptitle(f"{title}: {cmp.attrs.get('n_hours', '')} truth hours" if title else "")
    return fig


def cumulative_damage(cmp: xr.Dataset, *, title: str = "") -> Figure:
    """Cumulative damage over the window per curve and line: truth, reconstruction, 35 bins."""
    curves = [str(v) for v in cmp[names.CURVE].values]
    lines = [str(v) for v in cmp[names.LINE].values]
    fig = Figure(figsize=(3.6 * len(lines), 2.9 * len(curves)), layout="constrained")
    axes = fig.subplots(len(curves), len(lines), squeeze=False, sharex=True)
    x = cmp[names.TIME].values if names.TIME in cmp.coords else cmp["hour"].values
    for i, cv in enumerate(curves):
        for k, ln in enumerate(lines):
            ax = axes[i, k]
            sel = {names.CURVE: cv, names.LINE: ln}
            for key, colour, label in (
                ("truth_cumulative", "k", "truth"),
                ("reconstruction_cumulative", "tab:blue", "reconstruction"),
                ("bins_cumulative", "tab:red", "35 bins"),
            ):
                ax.plot(x, cmp[key].sel(sel).values, color=colour, lw=1.0, label=label)
            err_r = float(cmp["reconstruction_error_pct"].sel(sel))
            err_b = float(cmp["bins_error_pct"].sel(sel))
            ax.set_title(f"{_CURVE_LABEL.get(cv, cv)} {ln}: rec {err_r:+.1f} %, bins {err_b:+.1f} %", fontsize=9)
            ax.tick_params(labelsize=7)
            if k == 0:
                ax.set_ylabel("cumulative damage")
    axes[0, 0].legend(fontsize=7, loc="upper left")
    for ax in axes[-1]:
        for lab in ax.get_xticklabels():
            lab.set_rotation(30)
    fig.suptitle(title)
    return fig
