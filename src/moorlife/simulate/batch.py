"""One batch of sea states, from the metocean variables to the statistics (:func:`simulate_batch`)."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from moorlife import environment as env
from moorlife import names
from moorlife.settings import SimulationSettings, StatisticsSettings
from moorlife.simulate.forcing import Forcing, build_forcing
from moorlife.simulate.initial import equilibrium_start
from moorlife.simulate.integration import integrate
from moorlife.simulate.model import ModelInputs
from moorlife.simulate.steady import steady_start
from moorlife.simulate.summary import summarise

__all__ = ["simulate_batch", "batch_forcing"]


def _sim_settings(sim_cfg: Mapping[str, Any] | None) -> SimulationSettings:
    """The ``simulation`` section as typed settings (missing keys take the schema defaults)."""
    s = SimulationSettings.from_config(sim_cfg, source="simulation")
    for key in ("duration", "dt", "kinematics_dt"):
        if not getattr(s, key) > 0:
            raise ValueError(f"config key 'simulation.{key}' = {getattr(s, key)!r} must be positive")
    if s.transient < 0:
        raise ValueError(f"config key 'simulation.transient' = {s.transient!r} must be >= 0")
    return s


def _check_cases(cases: Mapping[str, np.ndarray], case_ids: np.ndarray) -> dict[str, np.ndarray]:
    missing = [k for k in names.METOCEAN_VARS if k not in cases]
    if missing:
        raise ValueError(f"simulate_batch: sea-state variable(s) {missing} missing (got {sorted(cases)})")
    arr = {k: np.atleast_1d(np.asarray(cases[k], dtype=float)) for k in names.METOCEAN_VARS}
    nb = np.size(case_ids)
    for k, v in arr.items():
        if v.shape != (nb,):
            raise ValueError(f"simulate_batch: {k!r} has shape {v.shape}, expected ({nb},) like case_ids")
        bad = ~np.isfinite(v)
        if k in ("hs", "tp", "wind_speed"):
            bad |= v < 0
        if k == "tp":
            bad |= v == 0
        if bad.any():
            i = int(np.flatnonzero(bad)[0])
            raise ValueError(f"simulate_batch: case {case_ids[i]}: {k} = {float(v[i])!r} is invalid")
    return arr


def period_grid(grid: env.RecordGrid) -> env.RecordGrid:
    """The grid of one whole period of ``grid``'s synthesis (``n_steps = n_fft - 1``)."""
    return env.RecordGrid(dt=grid.dt, n_steps=grid.n_fft - 1, n_fft=grid.n_fft, d_omega=grid.d_omega)


def record_part(forcing: Forcing, grid: env.RecordGrid) -> Forcing:
    """The first ``grid.n_steps`` steps of a longer forcing on the same FFT grid (bit for bit the
    forcing :func:`batch_forcing` gives on ``grid`` itself)."""
    n, ke = grid.n_steps, forcing.kin_every
    return Forcing(
        grid=grid,
        force=np.ascontiguousarray(forcing.force[:, : n + 1]),
        wind=np.ascontiguousarray(forcing.wind[:, : n + 1]),
        wind_dir=forcing.wind_dir,
        kin_every=ke,
        kinematics=np.ascontiguousarray(forcing.kinematics[:, : n // ke + 2]),
    )


def batch_forcing(
    sea: Mapping[str, np.ndarray],
    *,
    case_ids: np.ndarray,
    mooring_system: str,
    seed: int,
    model: ModelInputs,
    settings: SimulationSettings,
    stream: str = "case",
    grid: env.RecordGrid | None = None,
) -> Forcing:
    """The waves and wind of a batch of sea states on its record grid (``transient + duration``).

    Parameters
    ----------
    sea : mapping of str to (B,) arrays
        The checked sea-state variables (see :func:`simulate_batch`).
    case_ids : (B,) int
    mooring_system : str
    seed : int
    model : ModelInputs
    settings : SimulationSettings
    stream : str
    grid : environment.RecordGrid, optional
        Another number of steps on the record's FFT grid (e.g. one whole period, ``n_steps =
        n_fft - 1``, for ``validation/transient.py``); default the record's grid.

    Returns
    -------
    Forcing
    """
    s = settings
    ids = np.atleast_1d(np.asarray(case_ids))
    grid = env.record_grid(s.duration, s.transient, s.dt) if grid is None else grid
    n_bins = grid.n_fft // 2 + 1
    wave_ph, wind_ph = env.case_streams(seed, mooring_system, ids, n_bins, stream)
    gamma = env.resolve_gamma(s.gamma, sea["hs"], sea["tp"])
    w_lo, w_hi = float(model.omega.min()), float(model.omega.max())
    waves = env.wave_components(
        grid, sea["hs"], sea["tp"], sea["wave_dir"], gamma, wave_ph, omega_min=w_lo, omega_max=w_hi
    )
    wind_cfg = {**s.wind.as_dict(), "height": float(model.hub[2])}
    wind = env.wind_series(grid, sea["wind_speed"], wind_ph, wind_cfg)
    kin_every = max(1, int(round(s.kinematics_dt / s.dt)))
    return build_forcing(model, grid, waves, wind, sea["wind_dir"], kin_every=kin_every, second_order=s.second_order)


def simulate_batch(
    cases: Mapping[str, np.ndarray],
    *,
    case_ids: np.ndarray,
    mooring_system: str,
    seed: int,
    model_inputs: ModelInputs,
    sim_cfg: Mapping[str, Any],
    fatigue_cfg: Mapping[str, Any] | None,
    stats_cfg: Mapping[str, Any] | None,
    stream: str = "case",
) -> dict[str, np.ndarray]:
    """Simulate a batch of sea states and return their statistics (pure; Dask-friendly).

    Parameters
    ----------
    cases : mapping of str to (B,) arrays
        ``wind_speed`` (m/s, hub height), ``wind_dir`` (deg, from), ``hs`` (m), ``tp`` (s),
        ``wave_dir`` (deg, from); other keys (e.g. ``hindcast_index``) are ignored.
    case_ids : (B,) int
        The case (or bin) ids: with ``seed`` and ``mooring_system`` they fix the random phases.
    mooring_system : str
        E.g. ``"MS3"``.
    seed : int
        The study seed.
    model_inputs : ModelInputs
        From :func:`prepare_model`.
    sim_cfg, fatigue_cfg, stats_cfg : mapping
        The ``simulation``, ``fatigue`` and ``statistics`` config sections.
    stream : str
        The dimension of ``case_ids`` (``"case"`` or ``"bin"``), so that bins and cases with
        the same id draw independent phases.

    Returns
    -------
    dict of numpy.ndarray
        See :func:`summarise`; leading axis the case.
    """
    ids = np.atleast_1d(np.asarray(case_ids))
    sea = _check_cases(cases, ids)
    s = _sim_settings(sim_cfg)
    model = model_inputs
    record_grid = env.record_grid(s.duration, s.transient, s.dt)
    # simulation.start 'steady' needs the whole period of the synthesis; the record is its start
    grid = period_grid(record_grid) if s.start == "steady" else record_grid
    forcing = batch_forcing(
        sea, case_ids=ids, mooring_system=mooring_system, seed=seed, model=model, settings=s, stream=stream, grid=grid
    )
    # simulation.start: at the linear periodic steady state, at rest at the mean equilibrium, or
    # at rest at the trimmed origin
    start = None
    if s.start == "steady":
        start = steady_start(model, forcing, record_grid.n_fft)
        forcing = record_part(forcing, record_grid)
    elif s.start == "equilibrium":
        start = equilibrium_start(model, forcing)
    record = integrate(model, forcing, transient=s.transient, start=start)
    bad = ~np.isfinite(record.motion).all(axis=(1, 2))
    if model.mooring_kind != "linear":
        bad |= ~np.isfinite(record.tension).all(axis=(1, 2))
    if bad.any():
        b = int(np.flatnonzero(bad)[0])
        raise FloatingPointError(
            f"simulate_batch ({mooring_system}): case {ids[b]} diverged (non-finite motion or tension) with "
            f"hs={sea['hs'][b]}, tp={sea['tp'][b]}, wave_dir={sea['wave_dir'][b]}, wind_speed={sea['wind_speed'][b]}, "
            f"wind_dir={sea['wind_dir'][b]}; reduce simulation.dt"
        )
    statistics = StatisticsSettings.from_config(stats_cfg, source="statistics")
    return summarise(
        record,
        line_info=model.line_info,
        fatigue_cfg=fatigue_cfg,
        statistics=statistics,
        mpm_duration=s.mpm_duration,
        keep_timeseries=s.keep_timeseries,
    )
