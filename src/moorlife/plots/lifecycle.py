"""Figures of the life-cycle, comparison and sensitivity stages (paper Figs. 10-18, 20-22, Table 8).

Every function takes in-memory data (xarray / pandas) and returns a
:class:`matplotlib.figure.Figure`; nothing here touches the disk or pyplot state.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
import pandas as pd
import xarray as xr
from matplotlib.figure import Figure

from moorlife import names

__all__ = [
    "CONTRACT_OUTPUTS",
    "binned_damage",
    "validation_scatter",
    "loo_error_map",
    "damage_vs_metocean",
    "damage_vs_mass",
    "difference_bars",
    "offsets_tensions",
    "recommendation_table",
    "seed_spread",
    "corrosion_evolution",
    "mean_stress_table",
]

CONTRACT_OUTPUTS: tuple[str, ...] = names.SIM_SCALAR_VARS + names.SIM_LINE_VARS
LINE_COLOURS = {"M1": "tab:blue", "M2": "tab:red", "M3": "tab:green"}
CURVE_LABEL = {"sn": "S-N (DNVGL-OS-E301)", "tn": "T-N (API RP 2SK)"}
_UNITS = {
    "surge_mpm": "m",
    "sway_mpm": "m",
    "heave_mpm": "m",
    "tension_mpm": "kN",
    "damage_sn": "1/h",
    "damage_tn": "1/h",
    "accel_mpm": "m/s$^2$",
    "accel_p90": "m/s$^2$",
    "accel_p95": "m/s$^2$",
    "accel_p99": "m/s$^2$",
}
_METOCEAN_LABEL = {
    "wind_speed": "W (m/s)",
    "wind_dir": r"$\beta$ wind from (deg)",
    "hs": "Hs (m)",
    "tp": "Tp (s)",
    "wave_dir": r"$\alpha$ waves from (deg)",
}


def _grid(n: int, ncols: int, size: float = 2.6) -> tuple[Figure, np.ndarray]:
    nrows = int(np.ceil(n / ncols))
    fig = Figure(figsize=(size * ncols, size * nrows), layout="constrained")
    axes = np.atleast_2d(fig.subplots(nrows, ncols, squeeze=False)).ravel()
    for ax in axes[n:]:
        ax.set_visible(False)
    return fig, axes


def validation_scatter(ds: xr.Dataset, title: str = "") -> Figure:
    """Rebuilt vs simulated value on the validation states, with the bisector and a linear fit
    (paper Figs. 10-13), one panel per contract output.

    Parameters
    ----------
    ds : xarray.Dataset
        ``lifecycle.zarr`` (``validation_predicted``, ``validation_simulated`` on
        (``validate``, ``output``), ``validation_r``, ``validation_rmse``; ``validation_r_low``
        and ``validation_r_high``, the bootstrap interval, when present). The figure's title names
        the reconstruction: the GP where the attribute ``rbf_method`` is ``gp``, else the RBF.
    title : str
    """
    labels = [str(o) for o in ds["output"].values if str(o).split("/")[0] in CONTRACT_OUTPUTS]
    fig, axes = _grid(len(labels), 4)
    for ax, lab in zip(axes, labels):
        var = lab.split("/")[0]
        scale = 1e-3 if var == "tension_mpm" else 1.0
        s = ds["validation_simulated"].sel(output=lab).values * scale
        p = ds["validation_predicted"].sel(output=lab).values * scale
        ax.scatter(s, p, s=7, alpha=0.6, color="tab:blue", edgecolor="none")
        lo, hi = float(min(s.min(), p.min())), float(max(s.max(), p.max()))
        ax.plot([lo, hi], [lo, hi], color="k", lw=0.8, label="bisector")
        if np.ptp(s) > 0:
            a, b = np.polyfit(s, p, 1)
            ax.plot([lo, hi], [a * lo + b, a * hi + b], color="tab:red", lw=0.9, ls="--", label=f"fit {a:.2f}x")
        r = float(ds["validation_r"].sel(output=lab))
        span = ""
        if "validation_r_low" in ds:  # the bootstrap interval over the validation states
            span = f" ({float(ds['validation_r_low'].sel(output=lab)):.3f}-{float(ds['validation_r_high'].sel(output=lab)):.3f})"
        ax.set_title(f"{lab}\nr = {r:.3f}{span}", fontsize=8)
        ax.set_xlabel(f"simulated ({_UNITS.get(var, '')})", fontsize=7)
        ax.set_ylabel("rebuilt", fontsize=7)
        ax.tick_params(labelsize=6)
        ax.ticklabel_format(axis="both", style="sci", scilimits=(-3, 4))
    axes[0].legend(fontsize=6)
    method = "GP" if ds.attrs.get("rbf_method") == "gp" else "RBF"  # the attribute is written for the GP only
    n = ds.sizes.get("validate", 0)
    fig.suptitle(f"{title} {method} validation on {n} states not used for fitting".strip())
    return fig


def loo_error_map(ds: xr.Dataset, title: str = "") -> Figure:
    """Leave-one-out error of each training state (largest over outputs, in units of each
    output's spread) in the (Hs, Tp) and (W, wind direction) planes, with the adaptive
    selection suggestions."""
    pts = ds["train_points"].transpose("train", "metocean_var")
    loo = np.abs(ds["loo_error"].values)
    sim_spread = ds["validation_simulated"].std("validate").values if "validation_simulated" in ds else None
    logt = ds["log_transform"].values.astype(bool)
    spread = np.where(logt, 1.0, sim_spread if sim_spread is not None else loo.std(axis=0))
    spread = np.where(spread > 0, spread, 1.0)
    err = np.max(loo / spread, axis=1)
    fig = Figure(figsize=(11, 4.4), layout="constrained")
    axes = fig.subplots(1, 2)
    sugg = ds["suggested_hour"].values
    for ax, (xv, yv) in zip(axes, (("tp", "hs"), ("wind_dir", "wind_speed"))):
        x = pts.sel(metocean_var=xv).values
        y = pts.sel(metocean_var=yv).values
        sc = ax.scatter(x, y, c=err, s=10, cmap="viridis", vmin=0, vmax=float(np.quantile(err, 0.98)) or 1.0)
        if "train_round" in ds and (ds["train_round"].values > 0).any():
            adaptive = ds["train_round"].values > 0
            ax.scatter(
                x[adaptive],
                y[adaptive],
                s=40,
                facecolors="none",
                edgecolors="tab:orange",
                label=f"{int(adaptive.sum())} picked by {int(ds['train_round'].max())} adaptive round(s)",
            )
        if sugg.size:
            ax.scatter(
                ds[xv].values[sugg],
                ds[yv].values[sugg],
                marker="x",
                color="tab:red",
                s=25,
                label=f"{sugg.size} suggested next states",
            )
        if sugg.size or "train_round" in ds:
            ax.legend(fontsize=7, loc="upper right")
        ax.set_xlabel(_METOCEAN_LABEL[xv])
        ax.set_ylabel(_METOCEAN_LABEL[yv])
    fig.colorbar(sc, ax=axes, label="|LOO error| / output spread (max over outputs)")
    fig.suptitle(f"{title} leave-one-out error map of the training states".strip())
    return fig


def binned_damage(values: np.ndarray, damage: np.ndarray, edges: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Mean hourly damage and share of the total damage per class of a metocean variable.

    Parameters
    ----------
    values : numpy.ndarray, shape (n,)
    damage : numpy.ndarray, shape (n, k)
    edges : numpy.ndarray, shape (b + 1,)

    Returns
    -------
    mean : numpy.ndarray, shape (b, k)
        NaN for empty classes.
    share : numpy.ndarray, shape (b, k)
        Percentage of the total damage of each column.
    """
    idx = np.clip(np.digitize(values, edges) - 1, 0, edges.size - 2)
    count = np.bincount(idx, minlength=edges.size - 1).astype(float)
    sums = np.stack(
        [np.bincount(idx, weights=damage[:, j], minlength=edges.size - 1) for j in range(damage.shape[1])], 1
    )
    with np.errstate(invalid="ignore", divide="ignore"):
        mean = sums / count[:, None]
        share = 100.0 * sums / sums.sum(axis=0)
    return mean, share


def damage_vs_metocean(ds: xr.Dataset, title: str = "", curve: str = "sn") -> Figure:
    """Rebuilt hourly damage against W, wind direction, Hs, Tp and wave direction (paper
    Figs. 14-18): mean hourly damage per class (top) and share of the life damage (bottom)."""
    var = {"sn": "damage_sn", "tn": "damage_tn"}[curve]
    dmg = np.clip(ds[var].transpose(names.TIME, names.LINE).values, 0, None)
    lines = [str(v) for v in ds[names.LINE].values]
    fig = Figure(figsize=(16, 6), layout="constrained")
    axes = fig.subplots(2, 5)
    for j, mv in enumerate(names.METOCEAN_VARS):
        x = ds[mv].values
        edges = np.linspace(0, 360, 25) if mv in names.DIRECTION_VARS else np.linspace(np.min(x), np.max(x), 25)
        mean, share = binned_damage(x, dmg, edges)
        mid = 0.5 * (edges[1:] + edges[:-1])
        for k, ln in enumerate(lines):
            axes[0, j].plot(mid, mean[:, k], marker=".", color=LINE_COLOURS.get(ln), label=ln)
            axes[1, j].bar(
                mid + (k - 1) * np.diff(edges)[0] / 4,
                share[:, k],
                width=np.diff(edges)[0] / 4,
                color=LINE_COLOURS.get(ln),
                label=ln,
            )
        axes[0, j].set_yscale("log")
        axes[1, j].set_xlabel(_METOCEAN_LABEL[mv])
    axes[0, 0].set_ylabel("mean hourly damage")
    axes[1, 0].set_ylabel("share of life damage (%)")
    axes[0, 0].legend(fontsize=7)
    fig.suptitle(f"{title} rebuilt {CURVE_LABEL[curve]} damage over {ds.sizes[names.TIME]} hindcast hours".strip())
    return fig


def damage_vs_mass(table: pd.DataFrame) -> Figure:
    """Life-cycle damage against line mass per line and curve family (paper Fig. 20)."""
    curves = [c for c in ("sn", "tn") if c in set(table["curve"])]
    fig = Figure(figsize=(5.5 * len(curves), 4.5), layout="constrained")
    axes = np.atleast_1d(fig.subplots(1, len(curves)))
    for ax, c in zip(axes, curves):
        sub = table[table["curve"] == c]
        for ln, g in sub.groupby("line"):
            g = g.sort_values("mass_kg_per_m")
            ax.plot(
                g["mass_kg_per_m"],
                g["lifecycle_damage"],
                marker="o",
                color=LINE_COLOURS.get(ln),
                label=f"{ln} life cycle",
            )
            ax.plot(
                g["mass_kg_per_m"],
                g["discrete_damage"],
                marker="s",
                ls="--",
                mfc="none",
                color=LINE_COLOURS.get(ln),
                label=f"{ln} discrete matrix",
            )
        for ms, g in sub.groupby("mooring_system"):
            ax.annotate(
                ms,
                (g["mass_kg_per_m"].iloc[0], g["lifecycle_damage"].max()),
                fontsize=7,
                textcoords="offset points",
                xytext=(2, 4),
            )
        ax.set_yscale("log")
        ax.set_xlabel("line mass (kg/m)")
        ax.set_ylabel("damage over the hindcast")
        ax.set_title(CURVE_LABEL[c])
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=7)
    return fig


def difference_bars(table: pd.DataFrame) -> Figure:
    """Percentage by which the discrete matrix underestimates life-cycle damage (Table 7 analogue)."""
    curves = [c for c in ("sn", "tn") if c in set(table["curve"])]
    fig = Figure(figsize=(5.5 * len(curves), 4), layout="constrained")
    axes = np.atleast_1d(fig.subplots(1, len(curves), sharey=True))
    systems = list(dict.fromkeys(table["mooring_system"]))
    x = np.arange(len(systems))
    for ax, c in zip(axes, curves):
        sub = table[table["curve"] == c]
        lines = sorted(set(sub["line"]))
        for k, ln in enumerate(lines):
            vals = [
                float(sub[(sub.mooring_system == ms) & (sub.line == ln)]["difference_pct"].iloc[0]) for ms in systems
            ]
            ax.bar(x + (k - 1) * 0.27, vals, width=0.27, color=LINE_COLOURS.get(ln), label=ln)
        ax.axhline(0, color="k", lw=0.7)
        ax.set_xticks(x, systems)
        ax.set_title(CURVE_LABEL[c])
        ax.set_ylabel("(life cycle - discrete) / life cycle (%)")
        ax.grid(axis="y", alpha=0.3)
    axes[0].legend(fontsize=7)
    return fig


def offsets_tensions(dists: Mapping[str, Mapping[str, xr.DataArray]]) -> Figure:
    """Distribution over the hindcast of the rebuilt offset and tension MPM per system."""
    fig = Figure(figsize=(11, 4.2), layout="constrained")
    ax1, ax2 = fig.subplots(1, 2)
    systems = list(dists)
    off = [np.hypot(d["surge_mpm"].values, d.get("sway_mpm", 0 * d["surge_mpm"]).values) for d in dists.values()]
    ten = [d["tension_mpm"].max(names.LINE).values * 1e-3 for d in dists.values()]
    for ax, data, lab in ((ax1, off, "horizontal offset MPM (m)"), (ax2, ten, "largest line tension MPM (kN)")):
        ax.boxplot(data, whis=(1, 99), showfliers=False)
        ax.plot(np.arange(1, len(data) + 1), [np.max(v) for v in data], "v", color="tab:red", label="hindcast maximum")
        ax.legend(fontsize=7, loc="upper left")
        ax.set_xticks(np.arange(1, len(systems) + 1), systems)
        ax.set_ylabel(lab)
        ax.grid(axis="y", alpha=0.3)
    fig.suptitle("rebuilt hourly extremes over the hindcast (box: quartiles, whiskers 1-99 %)")
    return fig


def recommendation_table(table: pd.DataFrame, rec: Mapping[str, Any]) -> Figure:
    """Per system: mass, shortest fatigue life and largest utilisation per curve, verdict."""
    curves = rec["curves"]  # always written by the lifecycle stage (moorlife.io.lifecycle)
    rows = []
    for ms, g in table.groupby("mooring_system", sort=False):
        row = [ms, f"{g['mass_kg_per_m'].iloc[0]:.1f}"]
        for c in ("sn", "tn"):
            gc = g[g.curve == c]
            row += (
                [f"{gc['fatigue_life_years'].min():.1f}", f"{gc['utilisation'].max():.2f}"] if len(gc) else ["-", "-"]
            )
        row.append("pass" if g[g.curve.isin(curves)]["passes"].all() else "fail")
        rows.append(row)
    fig = Figure(figsize=(9, 0.45 * len(rows) + 1.6), layout="constrained")
    ax = fig.subplots()
    ax.axis("off")
    cols = ["system", "kg/m", "S-N min life (y)", "S-N max DFF*D", "T-N min life (y)", "T-N max DFF*D", "verdict"]
    tab = ax.table(cellText=rows, colLabels=cols, loc="center", cellLoc="center")
    tab.scale(1, 1.4)
    for i, r in enumerate(rows, start=1):
        if r[0] == rec.get("recommended"):
            for j in range(len(cols)):
                tab[i, j].set_facecolor("#cfe8cf")
    verdict = rec.get("recommended") or "none of the systems"
    ax.set_title(f"Recommended: {verdict}\n({rec.get('rule', '')})", fontsize=10)
    return fig


def seed_spread(df: pd.DataFrame, title: str = "") -> Figure:
    """Fatigue life of each random-phase realisation per line and curve (paper Fig. 21)."""
    curves = [c for c in ("sn", "tn") if c in set(df["curve"])]
    fig = Figure(figsize=(5.5 * len(curves), 4), layout="constrained")
    axes = np.atleast_1d(fig.subplots(1, len(curves)))
    for ax, c in zip(axes, curves):
        sub = df[df.curve == c]
        for k, (ln, g) in enumerate(sub.groupby("line")):
            y = g["life_years"].values
            ax.scatter(np.full(y.size, k) + np.linspace(-0.15, 0.15, y.size), y, color=LINE_COLOURS.get(ln), s=14)
            ax.hlines(y.mean(), k - 0.25, k + 0.25, color="k")
            ax.annotate(
                f"mean {y.mean():.2f} y\nspread {np.ptp(y):.2f} y",
                (k, y.max()),
                fontsize=7,
                textcoords="offset points",
                xytext=(0, 5),
                ha="center",
            )
        ax.set_xticks(range(sub["line"].nunique()), sorted(set(sub["line"])))
        if sub["life_years"].max() > 10 * sub["life_years"].min():
            ax.set_yscale("log")
        ax.set_ylabel("fatigue life if the state repeats (years)")
        ax.set_title(CURVE_LABEL[c])
        ax.grid(axis="y", alpha=0.3)
    fig.suptitle(title)
    return fig


def corrosion_evolution(df: pd.DataFrame, title: str = "") -> Figure:
    """Accumulated damage with and without corrosion (paper Fig. 22)."""
    fig = Figure(figsize=(6.5, 4.2), layout="constrained")
    ax = fig.subplots()
    for c, g in df.groupby("curve"):
        col = "tab:blue" if c == "sn" else "tab:orange"
        ax.plot(g["years"], g["corroded"], marker="o", color=col, label=f"{CURVE_LABEL.get(c, c)}, corroding")
        ax.plot(g["years"], g["intact"], ls="--", color=col, label=f"{CURVE_LABEL.get(c, c)}, no corrosion")
    ax.axhline(1.0, color="k", lw=0.7)
    ax.set_xlabel("years in service")
    ax.set_ylabel("accumulated damage")
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)
    ax.set_title(title, fontsize=9)
    return fig


def mean_stress_table(df: pd.DataFrame) -> Figure:
    """Mean-stress correction ratios per system and block (paper Table 8) as a table figure."""
    cols = ["mooring_system", "block", "mean_tension_kN", "mean_stress_mpa", "goodman", "soderberg", "gerber"]
    fmt = {
        "mean_tension_kN": "{:.1f}",
        "mean_stress_mpa": "{:.4f}",
        "goodman": "{:.4f}",
        "soderberg": "{:.4f}",
        "gerber": "{:.4f}",
    }
    cells = [
        [fmt[c].format(r[c]) if c in fmt and np.isfinite(r[c]) else str(r[c]) for c in cols] for _, r in df.iterrows()
    ]
    fig = Figure(figsize=(9, 0.32 * len(cells) + 1.2), layout="constrained")
    ax = fig.subplots()
    ax.axis("off")
    tab = ax.table(
        cellText=cells,
        colLabels=["system", "block", "mean T (kN)", "mean stress (MPa)", "Goodman", "Soderberg", "Gerber"],
        loc="center",
        cellLoc="center",
    )
    tab.scale(1, 1.25)
    ax.set_title(r"mean-stress correction $\Delta\sigma/\Delta\sigma_0 = 1 - (\sigma_m/\sigma_R)^n$", fontsize=10)
    return fig
