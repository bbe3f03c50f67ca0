"""Adaptive selection in rounds (issue 22, item 1): the budget, the picks, the merge, and the
rounds end to end on the tiny study (conftest.py ``study``: one round of 3 states per system)."""

from __future__ import annotations

import re
import shutil
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from moorlife import io as mio
from moorlife import lifecycle, names
from moorlife.config import ConfigError, check_cross_keys
from moorlife.selection import rounds

ROOT = Path(__file__).resolve().parents[1]
SETTINGS = lifecycle.RBFSettings.from_config({"outputs": ["surge_mpm", "tension_mpm", "damage_sn"]})


def _hindcast(n: int = 2000, seed: int = 0) -> xr.Dataset:
    """test_lifecycle's random hindcast, 2,000 hours by default."""
    from test_lifecycle import _hindcast as lifecycle_hindcast

    return lifecycle_hindcast(n, seed)


def _cases(hc: xr.Dataset, n_train: int = 60, n_val: int = 20, seed: int = 1) -> xr.Dataset:
    idx = np.random.default_rng(seed).choice(hc.sizes["time"], n_train + n_val, replace=False)
    ds = xr.Dataset(
        {v: ("case", hc[v].values[idx]) for v in names.METOCEAN_VARS},
        coords={"case": np.arange(idx.size), "time": ("case", hc["time"].values[idx])},
    )
    ds["hindcast_index"] = ("case", idx.astype(np.int64))
    ds["role"] = ("case", np.array(["train"] * n_train + ["validate"] * n_val))
    return ds


def _ridge(w: np.ndarray) -> np.ndarray:
    """A thrust-like ridge: a sharp rise and fall around 12 m/s."""
    return np.exp(-(((w - 12.0) / 1.2) ** 2))


def _sims(cases: xr.Dataset) -> xr.Dataset:
    """Outputs of the sea states: a ridge in the wind speed (the hard part) on smooth trends."""
    hs, w = cases["hs"].values, cases["wind_speed"].values
    ds = xr.Dataset(coords={"case": cases["case"].values, "line": list(names.LINES)})
    ds["surge_mpm"] = ("case", 2.0 + 0.5 * hs + 8.0 * _ridge(w))
    ds["tension_mpm"] = (("case", "line"), np.outer(1e6 + 1e5 * hs + 4e5 * _ridge(w), [1.0, 1.2, 0.9]))
    ds["damage_sn"] = (("case", "line"), np.outer(1e-6 * (1 + hs**2) * (1 + 5 * _ridge(w)), [1.0, 3.0, 0.5]))
    for v in (*names.METOCEAN_VARS, "hindcast_index", "role"):
        ds[v] = cases[v].reset_coords(drop=True)
    ds.attrs["mooring_system"] = "MS2"
    return ds


def _picks_store(hc, cases, picks: xr.Dataset) -> xr.Dataset:
    """The picks as the simulate stage returns them: outputs plus the case variables."""
    return _sims(picks).assign(round=picks["round"])


@pytest.fixture(scope="module")
def round1():
    hc = _hindcast()
    cases = _cases(hc)
    sims = _sims(cases)
    picks = rounds.pick_round(hc, cases, sims, settings=SETTINGS, n=10, number=1)
    return hc, cases, sims, picks


# ----------------------------------------------------------------------------- the budget


def test_mda_budget_is_the_rest_of_n_train():
    assert rounds.mda_budget(1000, 0, 100) == 1000
    assert rounds.mda_budget(1000, 2, 100) == 800
    with pytest.raises(ValueError, match=r"rounds = 4 x per_round = 3 = 12 reach selection.n_train = 12"):
        rounds.mda_budget(12, 4, 3)


@pytest.mark.parametrize(("k", "n", "ok"), [(1, 3, True), (3, 3, True), (4, 3, False), (1, 12, False), (0, 50, True)])
def test_budget_refused_at_config_time(tiny_config, k, n, ok):
    cfg = tiny_config
    cfg["selection"]["n_train"] = 12
    cfg["lifecycle"]["replicates"]["states"] = 0  # the rounds' budget alone (test_replicates: both)
    cfg["lifecycle"]["adaptive"].update(rounds=k, per_round=n)
    if ok:
        check_cross_keys(cfg, "tiny.yaml")
        return
    with pytest.raises(
        ConfigError, match=rf"'lifecycle\.adaptive\.rounds' = {k} x 'lifecycle\.adaptive\.per_round' = {n}"
    ):
        check_cross_keys(cfg, "tiny.yaml")


def test_default_study_has_no_rounds(study_config):
    a = study_config["lifecycle"]["adaptive"]
    assert a["rounds"] == 0, "rounds: 0 keeps the paper's selection (maximum dissimilarity only)"
    assert rounds.mda_budget(study_config["selection"]["n_train"], a["rounds"], a["per_round"]) == 1000


# ----------------------------------------------------------------------------- the picks


def test_picks_are_new_hours_never_validation_and_deterministic(round1):
    hc, cases, sims, picks = round1
    h = picks["hindcast_index"].values
    assert h.size == 10 and np.unique(h).size == 10
    assert not set(h) & set(cases["hindcast_index"].values.tolist()), "a simulated or validation hour was picked"
    np.testing.assert_array_equal(picks["case"].values, rounds.ROUND_CASE_OFFSET + h)
    for v in names.METOCEAN_VARS:
        np.testing.assert_array_equal(picks[v].values, hc[v].values[h])
    np.testing.assert_array_equal(picks["time"].values, hc["time"].values[h])
    assert set(picks["role"].values.tolist()) == {"train"} and (picks["round"].values == 1).all()
    assert picks.attrs["n_fit"] == 60 and picks.attrs["round"] == 1
    again = rounds.pick_round(hc, cases, sims, settings=SETTINGS, n=10, number=1)
    xr.testing.assert_identical(again, picks)


def test_first_pick_is_the_least_sure_allowed_hour(round1):
    """The picks are the hours of largest error indicator (the fit of the MDA states alone),
    spread greedily: the first is the argmax over the hours that may be picked."""
    hc, cases, sims, picks = round1
    train = np.array([str(r) == "train" for r in cases["role"].values])
    cols = lifecycle.output_columns(sims, "case", SETTINGS.outputs)
    y = lifecycle.stack_outputs(sims, "case", cols)[train]
    pts = np.column_stack([hc[v].values for v in names.METOCEAN_VARS])
    x = pts[cases["hindcast_index"].values[train]]
    model = lifecycle.fit_outputs(x, y, cols, SETTINGS)
    loo = lifecycle.loo_errors_in_units(model, y, cols)
    ind, dist = lifecycle.error_indicator(model, pts, y.std(axis=0), loo, population=True)
    ind[cases["hindcast_index"].values] = -1.0
    h = picks["hindcast_index"].values
    assert h[0] == int(np.argmax(ind))
    np.testing.assert_array_equal(picks["error_indicator"].values, ind[h])
    np.testing.assert_array_equal(picks["nearest_train_distance"].values, dist[h])
    assert (ind[h] > np.median(ind[ind >= 0])).all(), "every pick is among the less sure half of the hours"


def test_indicator_weighs_damage_errors_in_damage_units():
    """A log10 damage fit is worst, in log10 units, where the damage is negligible; in damage units
    (what the life-cycle sum and the per-hour r weigh) it is worst where the damage is large.

    Constructed: 1-D-like damage ``1e-9`` for W < 10 m/s with a wild factor-10 scatter, and a
    smooth but steep ``1e-4 exp(W / 3)`` above; the unit-weighted indicator must point at the
    steep, damaging side, the log-weighted one mostly at the negligible scatter and the jump.
    """
    rng = np.random.default_rng(3)
    n = 120
    x = np.column_stack(
        [
            rng.uniform(0, 25, n),
            rng.uniform(0, 360, n),
            rng.uniform(0.5, 4, n),
            rng.uniform(4, 14, n),
            rng.uniform(0, 360, n),
        ]
    )
    w = x[:, 0]
    y = np.where(w < 10, 1e-9 * 10 ** rng.uniform(-1, 1, n), 1e-4 * np.exp(w / 3.0))[:, None]
    cols = [("damage_sn", "M1")]
    model = lifecycle.fit_outputs(x, y, cols, SETTINGS)
    loo = lifecycle.loo_errors_in_units(model, y, cols)
    worst_units = int(np.argmax(np.abs(loo[:, 0])))
    worst_log = int(np.argmax(np.abs(model.loo_error[:, 0])))
    assert w[worst_units] >= 10 and w[worst_log] < 10
    grid = np.column_stack(
        [rng.uniform(0, 25, 2000), rng.uniform(0, 360, 2000), rng.uniform(0.5, 4, 2000), rng.uniform(4, 14, 2000)]
        + [rng.uniform(0, 360, 2000)]
    )
    ind_units, _ = lifecycle.error_indicator(model, grid, y.std(axis=0), loo)
    ind_log, _ = lifecycle.error_indicator(model, grid, [1.0])
    top = 50  # the hours a round of 50 would draw from

    def damage(rows):
        g = grid[rows, 0]
        return np.where(g < 10, 1e-9, 1e-4 * np.exp(g / 3.0))

    assert (grid[np.argsort(-ind_units)[:top], 0] >= 10).mean() > 0.9
    assert np.median(damage(np.argsort(-ind_units)[:top])) > 100 * np.median(damage(np.argsort(-ind_log)[:top]))


def test_population_weighs_errors_by_the_hours_they_affect():
    """Equal leave-one-out errors everywhere: with ``population`` the indicator is largest where
    the hours crowd (the hindcast's calm, common states), without it it ignores them."""
    rng = np.random.default_rng(5)
    m = 80
    x = np.column_stack(
        [rng.uniform(0, 25, m), rng.uniform(0, 360, m), rng.uniform(0.5, 4, m), rng.uniform(4, 14, m)]
        + [rng.uniform(0, 360, m)]
    )
    cols = [("surge_mpm", None)]
    model = lifecycle.fit_outputs(x, (1.0 + x[:, 0])[:, None], cols, SETTINGS)
    loo = np.ones((m, 1))
    crowd = np.column_stack([rng.normal(5, 1, 3000), rng.normal(270, 10, 3000), rng.normal(1.5, 0.2, 3000)])
    crowd = np.column_stack([crowd, rng.normal(8, 0.5, 3000), rng.normal(280, 10, 3000)])
    hours = np.vstack([crowd, x[:40] + 0.3])  # a crowd of 3,000 calm hours and 40 hours spread out
    with_pop, _ = lifecycle.error_indicator(model, hours, [1.0], loo, population=True)
    without, dist = lifecycle.error_indicator(model, hours, [1.0], loo)
    top = np.argsort(-with_pop)[:20]
    assert (top < 3000).all(), "the picks go to the crowd when the errors are equal"
    np.testing.assert_allclose(without / without.max(), dist / dist.max())  # without: the distance alone
    assert with_pop[:3000].mean() / with_pop[3000:].mean() > without[:3000].mean() / without[3000:].mean()


def test_picks_do_not_depend_on_the_thread_count(round1):
    import numba

    hc, cases, sims, picks = round1
    before = numba.get_num_threads()
    try:
        numba.set_num_threads(1)
        one = rounds.pick_round(hc, cases, sims, settings=SETTINGS, n=10, number=1)
    finally:
        numba.set_num_threads(before)
    xr.testing.assert_identical(one, picks)


def test_validation_outputs_never_steer_the_picks(round1):
    hc, cases, sims, picks = round1
    bent = sims.copy(deep=True)
    val = np.array([str(r) == "validate" for r in cases["role"].values])
    for v in ("surge_mpm", "tension_mpm", "damage_sn"):
        bent[v].values[val] *= 3.0
    xr.testing.assert_identical(rounds.pick_round(hc, cases, bent, settings=SETTINGS, n=10, number=1), picks)


def test_exclusion_counts_and_shortfall_is_refused():
    hc = _hindcast(40)
    cases = _cases(hc, n_train=20, n_val=10)
    sims = _sims(cases)
    picks = rounds.pick_round(hc, cases, sims, settings=SETTINGS, n=10, number=1)
    assert sorted(set(picks["hindcast_index"].values) | set(cases["hindcast_index"].values)) == list(range(40))
    with pytest.raises(ValueError, match=r"only 10 of the 11 hours asked \(lifecycle\.adaptive\.per_round\)"):
        rounds.pick_round(hc, cases, sims, settings=SETTINGS, n=11, number=1)


def test_a_point_equal_to_a_validation_state_is_never_picked():
    hc = _hindcast(300)
    cases = _cases(hc, n_train=30, n_val=10)
    sims = _sims(cases)
    first = rounds.pick_round(hc, cases, sims, settings=SETTINGS, n=1, number=1)
    h = int(first["hindcast_index"].values[0])
    val = int(cases["hindcast_index"].values[-1])
    twin = hc.copy(deep=True)
    for v in names.METOCEAN_VARS:  # make a validation hour the twin of the favourite pick
        twin[v].values[val] = hc[v].values[h]
    cases2 = cases.copy(deep=True)
    for v in names.METOCEAN_VARS:
        cases2[v].values[-1] = hc[v].values[h]
    again = rounds.pick_round(twin, cases2, sims, settings=SETTINGS, n=1, number=1)
    assert int(again["hindcast_index"].values[0]) not in (h, val)


# ----------------------------------------------------------------------------- the merge


def test_with_rounds_merges_and_refits_on_every_state(round1, tmp_path):
    hc, cases, sims, picks = round1
    assert rounds.with_rounds(cases, []) is cases
    cs2 = rounds.with_rounds(cases, [picks])
    sm2 = rounds.with_rounds(sims, [_picks_store(hc, cases, picks)])
    assert cs2.sizes["case"] == 90 and sm2.sizes["case"] == 90
    np.testing.assert_array_equal(cs2["round"].values, [0] * 80 + [1] * 10)
    assert cs2.attrs == cases.attrs
    ds = lifecycle.reconstruct_lifecycle(hc, cs2, sm2, settings=SETTINGS, n_suggest=3, compare_transforms=False)
    ds = rounds.annotate_lifecycle(ds, cs2)
    assert ds.sizes["train"] == 70 and ds.attrs["n_train"] == 70
    assert ds.attrs["n_train_mda"] == 60 and ds.attrs["adaptive_rounds"] == 1
    assert set(ds["train"].values[ds["train_round"].values == 1]) == set(picks["case"].values)
    nxt = rounds.pick_round(hc, cs2, sm2, settings=SETTINGS, n=5, number=2)
    assert not set(nxt["hindcast_index"].values) & set(cs2["hindcast_index"].values)
    with pytest.raises(ValueError, match="case ids repeat"):
        rounds.with_rounds(cases, [picks, picks])


# ----------------------------------------------------------------------------- the workflow


def test_round_stream_is_the_rules():
    text = (ROOT / "workflow" / "rules" / "rounds.smk").read_text()
    assert f'stream="{rounds.ROUND_STREAM}"' in text


@pytest.mark.workflow
def test_rounds_end_to_end(study):
    """The tiny study (1 round of 3 states per system): the budget, the picks, the lifecycle."""
    cfg = mio.read_yaml(study / "tests" / "data" / "tiny.yaml")["lifecycle"]["adaptive"]
    k, n = cfg["rounds"], cfg["per_round"]
    assert (k, n) == (1, 3)
    cases = mio.open_zarr(study / "results/selection/cases.zarr")
    role = np.array([str(r) for r in cases["role"].values])
    n_train = 12  # training states fitted: 9 MDA + 3 (tiny.yaml's other 2 simulations are seed replicates)
    assert (role == "train").sum() == n_train - k * n and cases.attrs["n_train"] == n_train - k * n
    mda_h = set(cases["hindcast_index"].values[role == "train"].tolist())
    val_h = set(cases["hindcast_index"].values[role == "validate"].tolist())
    for ms in ("MS1", "MS3"):
        picks = mio.open_zarr(study / f"results/{ms}/rounds/picks_1.zarr")
        sims = mio.open_zarr(study / f"results/{ms}/rounds/simulations_1.zarr")
        lc = mio.open_zarr(study / f"results/{ms}/lifecycle.zarr", load=False)
        h = set(picks["hindcast_index"].values.tolist())
        assert len(h) == n and not h & mda_h and not h & val_h, ms
        assert picks.attrs["n_fit"] == n_train - k * n
        np.testing.assert_array_equal(sims["case"].values, picks["case"].values)
        assert sims.attrs["random_stream"] == rounds.ROUND_STREAM and np.isfinite(sims["damage_sn"].values).all()
        # the lifecycle fitted every training state: MDA + the round, n_train in all
        assert lc.sizes["train"] == n_train and lc.attrs["n_train"] == n_train
        assert lc.attrs["n_train_mda"] == n_train - k * n and lc.attrs["adaptive_rounds"] == k
        rnd = lc["train_round"].values
        assert set(lc["train"].values[rnd == 1].tolist()) == set(picks["case"].values.tolist())
        np.testing.assert_array_equal(
            lc["train_points"].values[rnd == 1][:, 2], picks["hs"].sel(case=lc["train"].values[rnd == 1]).values
        )
        assert (study / f"results/figures/loo_error_{ms}.png").stat().st_size > 0
    assert (study / "results/report/overview.rst").exists()


@pytest.mark.workflow
def test_kill_inside_a_round_then_resume_is_bit_identical(study, tmp_path):
    """SIGKILL the simulation of round 1 mid-fan-out (one worker), resume with two: the bits of
    the study's store, the finished sea states reused and the picks not recomputed."""
    from test_workflow import OVERLAYS, SNAKEMAKE, clone_study, kill_during_fanout, smk

    work = clone_study(study, tmp_path / "k")
    target = "results/MS1/rounds/simulations_1.zarr"
    shutil.rmtree(work / target)
    (work / "slow.yaml").write_text("simulation:\n  batch_size: 1\n")
    overlays = [*OVERLAYS, "slow.yaml"]
    part = mio.partial_path(work / target)
    # one worker: the 3 batches run one after the other (a sea state takes about a second here)
    cmd = [SNAKEMAKE, "--cores", "1", target, "--configfile", *overlays]
    n_before = kill_during_fanout(work, cmd, part, 1, poll=0.01)
    assert not (work / target).exists(), "the run was not killed during the fan-out"
    assert 1 <= n_before < 3
    smk(work, "--unlock", overlays=overlays)
    res = smk(work, target, overlays=overlays)
    assert not re.search(r"^rule adaptive_picks:", res.stdout + res.stderr, flags=re.M), "the picks were recomputed"
    m = re.search(
        r"resuming .*: (\d+) of (\d+) batches already done", (work / "logs/MS1/rounds/simulate_1.log").read_text()
    )
    assert m and int(m.group(1)) >= n_before and int(m.group(2)) == 3
    xr.testing.assert_identical(mio.open_zarr(work / target).drop_attrs(), mio.open_zarr(study / target).drop_attrs())
