"""Stage ``selection``: the sea states to simulate (maximum dissimilarity, paper section 3.2)
and the conventional discrete scatter matrix the life-cycle method is compared against
(section 4.1) (rules ``selection``, ``discrete`` and ``selection_figures``)."""

from __future__ import annotations

import os
from collections.abc import Sequence

import xarray as xr

from moorlife import selection
from moorlife.io import open_zarr, save_figure, write_zarr
from moorlife.stages import logged

__all__ = ["run", "discrete", "figures"]

PathLike = str | os.PathLike[str]


def run(
    *,
    hindcast: PathLike,
    store: PathLike,
    n_train: int,
    n_validate: int,
    rule: str,
    seed: int,
    log: PathLike | None = None,
) -> xr.Dataset:
    """MDA training + validation sea states -> ``results/selection/cases.zarr``.

    Parameters
    ----------
    hindcast : path-like
        ``results/metocean/hindcast.zarr``.
    store : path-like
        The output store.
    n_train, n_validate : int
        Training and validation states (``selection.n_train``, ``selection.n_validate``).
    rule : str
        How the validation states are drawn (``selection.validation_rule``).
    seed : int
        Global seed (``config.yaml: seed``).
    log : path-like, optional
        The rule's log file.
    """
    with logged(log, __name__):
        hc = open_zarr(hindcast)
        cases = selection.select_cases(
            hc, n_train=n_train, n_validate=n_validate, rule=rule, seed=seed, source=str(hindcast)
        )
        write_zarr(cases, store)
        return cases


def discrete(
    *,
    hindcast: PathLike,
    store: PathLike,
    hs_edges: Sequence[float],
    wind_edges: Sequence[float],
    tp_edges: Sequence[float],
    sector: float,
    log: PathLike | None = None,
) -> xr.Dataset:
    """The conventional scatter-matrix sea states -> ``results/selection/discrete.zarr``.

    Parameters
    ----------
    hindcast : path-like
        ``results/metocean/hindcast.zarr``.
    store : path-like
        The output store.
    hs_edges, wind_edges, tp_edges : sequence of float
        Bin edges (``selection.discrete.*``).
    sector : float
        Direction sector width, degrees (``selection.discrete.direction_sector``).
    log : path-like, optional
        The rule's log file.
    """
    with logged(log, __name__):
        hc = open_zarr(hindcast)
        ds = selection.discrete_states(
            hc, hs_edges=hs_edges, wind_edges=wind_edges, tp_edges=tp_edges, sector=sector, source=str(hindcast)
        )
        write_zarr(ds, store)
        return ds


def figures(
    *,
    hindcast: PathLike,
    cases: PathLike,
    discrete: PathLike,
    cloud_fig: PathLike,
    discrete_fig: PathLike,
    log: PathLike | None = None,
) -> None:
    """Paper Fig. 6 (selection cloud) and Fig. 19 (discrete states).

    Parameters
    ----------
    hindcast, cases, discrete : path-like
        The stores of the metocean and selection stages.
    cloud_fig, discrete_fig : path-like
        The two PNG files.
    log : path-like, optional
        The rule's log file.
    """
    from moorlife.plots.selection import plot_discrete_states, plot_selection_cloud

    with logged(log, __name__):
        hc = open_zarr(hindcast)
        save_figure(plot_selection_cloud(hc, open_zarr(cases)), cloud_fig)
        save_figure(plot_discrete_states(hc, open_zarr(discrete)), discrete_fig)
