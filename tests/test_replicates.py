"""Seed replicates of the training states that hold the damage (issue 22): the shares, the
picks, the mean of the records, the budget, and the replicates end to end on the tiny study
(conftest.py ``study``: 2 states x 1 seed per system)."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from moorlife import io as mio
from moorlife import lifecycle, names
from moorlife.config import ConfigError, check_cross_keys
from moorlife.selection import replicates as rep
from moorlife.selection import rounds
from moorlife.stages.rounds import merged

SETTINGS = lifecycle.RBFSettings.from_config({"outputs": ["surge_mpm", "tension_mpm", "damage_sn"]})


def _problem():
    from test_rounds import _cases, _hindcast, _sims

    hc = _hindcast()
    cases = _cases(hc)
    return hc, cases, _sims(cases)


# ----------------------------------------------------------------------------- kernels


def test_stream_names_are_the_rules():
    assert [rep.replicate_stream(j) for j in (1, 2, 10)] == ["replicate1", "replicate2", "replicate10"]
    with pytest.raises(ValueError, match="replicate number 0"):
        rep.replicate_stream(0)


def test_damage_shares_sum_the_nearest_hours():
    nearest = np.array([0, 0, 1, 2, 2, 2])
    damage = np.array([[1.0, 0.0], [1.0, 0.0], [2.0, 0.0], [1.0, 0.0], [3.0, 0.0], [0.0, 0.0]])
    s = rep.damage_shares(nearest, damage, 4)
    np.testing.assert_allclose(s[:, 0], [2 / 8, 2 / 8, 4 / 8, 0.0])
    np.testing.assert_array_equal(s[:, 1], 0.0)  # no damage at all: no share, no division by zero
    with pytest.raises(ValueError, match="outside 0 .. 1"):
        rep.damage_shares(nearest, damage, 2)
    with pytest.raises(ValueError, match="finite and >= 0"):
        rep.damage_shares(nearest, -damage, 4)


def test_largest_shares_rank_by_the_worst_line_ties_to_the_lowest():
    s = np.array([[0.1, 0.2], [0.3, 0.0], [0.0, 0.3], [0.05, 0.05]])
    np.testing.assert_array_equal(rep.largest_shares(s, 3), [1, 2, 0])
    with pytest.raises(ValueError, match=r"lifecycle.replicates.states = 5: must be 1 .. 4"):
        rep.largest_shares(s, 5)


def _store(values: np.ndarray, ids, hs) -> xr.Dataset:
    return xr.Dataset(
        {
            "damage_sn": (("case", "line"), values),
            "surge_mpm": ("case", values[:, 0] * 10),
            "hs": ("case", np.asarray(hs, dtype=float)),
            "role": ("case", np.array(["train"] * len(ids))),
        },
        coords={"case": np.asarray(ids), "line": ["M1", "M2"]},
    )


def test_average_is_the_mean_of_the_records_in_order_and_leaves_the_rest():
    rng = np.random.default_rng(3)
    base = _store(rng.random((5, 2)), [0, 1, 2, 7, 9], [0.1, 0.2, 0.3, 1.0 / 3.0, 0.7])
    r1 = _store(rng.random((2, 2)), [7, 1], [1.0 / 3.0, 0.2])
    r2 = _store(rng.random((2, 2)), [7, 1], [1.0 / 3.0, 0.2])
    out = rep.average_replicates(base, [r1, r2])
    for c in (7, 1):
        expect = (base["damage_sn"].sel(case=c).values + r1["damage_sn"].sel(case=c).values) + r2["damage_sn"].sel(
            case=c
        ).values
        np.testing.assert_array_equal(out["damage_sn"].sel(case=c).values, expect / 3)
        np.testing.assert_array_equal(
            out["surge_mpm"].sel(case=c).values,
            np.mean([base["surge_mpm"].sel(case=c), r1["surge_mpm"].sel(case=c), r2["surge_mpm"].sel(case=c)]),
        )
    for c in (0, 2, 9):  # not replicated: the bits of the study
        xr.testing.assert_identical(
            out[["damage_sn", "surge_mpm"]].sel(case=c), base[["damage_sn", "surge_mpm"]].sel(case=c)
        )
    # the sea state is the same in every record: kept as it is, not (a + a + a) / 3
    np.testing.assert_array_equal(out["hs"].values, base["hs"].values)
    np.testing.assert_array_equal(out["n_records"].values, [1, 3, 1, 3, 1])
    assert rep.average_replicates(base, []) is base


def test_average_refuses_stores_that_do_not_match():
    base = _store(np.ones((3, 2)), [0, 1, 2], [1.0, 2.0, 3.0])
    with pytest.raises(ValueError, match=r"replicate 2 holds cases \[0\], replicate 1 \[1\]"):
        rep.average_replicates(base, [_store(np.ones((1, 2)), [1], [2.0]), _store(np.ones((1, 2)), [0], [1.0])])
    with pytest.raises(ValueError, match=r"replicated cases \[5\] are not among the simulations"):
        rep.average_replicates(base, [_store(np.ones((1, 2)), [5], [2.0])])


# ----------------------------------------------------------------------------- the picks


@pytest.fixture(scope="module")
def picks():
    hc, cases, sims = _problem()
    return hc, cases, sims, rep.pick_replicates(hc, cases, sims, settings=SETTINGS, n=5, seeds=2)


def test_picks_are_training_states_of_the_largest_damage_share(picks):
    hc, cases, sims, ds = picks
    role = dict(zip(cases["case"].values.tolist(), (str(r) for r in cases["role"].values)))
    assert ds.sizes["case"] == 5 and all(role[int(c)] == "train" for c in ds["case"].values)
    share = ds["damage_share"].max("line").values
    assert np.all(np.diff(share) <= 0) and share[0] > 0
    assert ds.attrs["replicate_seeds"] == 2 and ds.attrs["n_fit"] == int((cases["role"] == "train").sum())
    # the rows of cases.zarr as they are: the simulate stage reads the same sea states again
    xr.testing.assert_identical(
        ds[list(names.METOCEAN_VARS)].drop_attrs(),
        cases[list(names.METOCEAN_VARS)].sel(case=ds["case"].values).drop_attrs(),
    )
    # the damage is in the storm: the first pick's hours hold more damage than the mean state's
    assert share[0] > 1.0 / ds.attrs["n_fit"]


def test_picks_are_deterministic_and_ignore_the_validation_outputs(picks):
    hc, cases, sims, ds = picks
    again = rep.pick_replicates(hc, cases, sims, settings=SETTINGS, n=5, seeds=2)
    xr.testing.assert_identical(ds, again)
    noisy = sims.copy(deep=True)
    val = cases["role"].values.astype(str) == "validate"
    noisy["damage_sn"].values[val] *= 100.0
    xr.testing.assert_identical(ds, rep.pick_replicates(hc, cases, noisy, settings=SETTINGS, n=5, seeds=2))


def test_ranking_by_the_records_variance_of_the_life_and_of_each_year(picks):
    """``rank: life`` ranks by (G_i / S)^2 of the life-cycle sum; ``years`` sums it over the
    calendar years' sums; the default's picks keep their variables and attributes."""
    from moorlife.lifecycle.records import carried_shares

    hc, cases, sims, ds = picks
    assert "records_variance_share" not in ds and "replicate_rank" not in ds.attrs
    life = rep.pick_replicates(hc, cases, sims, settings=SETTINGS, n=5, seeds=2, rank="life")
    assert life.attrs["replicate_rank"] == "life"
    fitted = lifecycle.fit_reconstruction(cases, sims, settings=SETTINGS)
    model, ids, cols, y = fitted.model, fitted.train_case, fitted.cols, fitted.train_values
    dmg = [j for j, (v, ln) in enumerate(cols) if v == "damage_sn"]
    hp = lifecycle._points(hc, "time")
    g = carried_shares(
        model, hp, lifecycle.predict_outputs(model, hp), y, lifecycle._points(cases.sel(case=ids), "case"), dmg
    )
    share = g**2 / (g**2).sum(axis=0)
    top = np.argsort(-share.max(axis=1), kind="stable")[:5]
    np.testing.assert_array_equal(life["case"].values, ids[top])
    np.testing.assert_allclose(life["records_variance_share"].values, share[top], rtol=1e-12)
    # the hindcast's 2,000 hours lie in one year: its one sum is the life's
    years = rep.pick_replicates(hc, cases, sims, settings=SETTINGS, n=5, seeds=2, rank="years")
    np.testing.assert_array_equal(years["case"].values, life["case"].values)
    # spread over four years, each year's sum counts
    hc4 = hc.assign_coords(time=np.datetime64("2000-01-01T00") + np.arange(hc.sizes["time"]) * np.timedelta64(18, "h"))
    years4 = rep.pick_replicates(hc4, cases, sims, settings=SETTINGS, n=5, seeds=2, rank="years")
    year = hc4["time"].dt.year.values
    assert np.unique(year).size == 5
    by_year = rep.records_variance_shares(
        model,
        hp,
        lifecycle.predict_outputs(model, hp),
        y,
        lifecycle._points(cases.sel(case=ids), "case"),
        dmg,
        [np.flatnonzero(year == v) for v in np.unique(year)],
    )
    top4 = np.argsort(-by_year.max(axis=1), kind="stable")[:5]
    np.testing.assert_array_equal(years4["case"].values, ids[top4])
    assert not np.array_equal(years4["case"].values, life["case"].values)  # a year's records rank higher
    with pytest.raises(ValueError, match=r"lifecycle.replicates.rank = 'storm': must be one of"):
        rep.pick_replicates(hc, cases, sims, settings=SETTINGS, n=5, seeds=2, rank="storm")


def test_budget_refused_at_config_time(tiny_config):
    cfg = tiny_config
    n_tr = cfg["selection"]["n_train"]
    ad = cfg["lifecycle"]["adaptive"]
    taken = ad["rounds"] * ad["per_round"]
    cfg["lifecycle"]["replicates"].update(states=1, seeds=n_tr - taken - 1)  # MDA picks 1
    check_cross_keys(cfg, "tiny.yaml")
    cfg["lifecycle"]["replicates"].update(seeds=n_tr - taken)  # MDA would pick none
    with pytest.raises(
        ConfigError, match=rf"'lifecycle\.replicates\.states' = 1 x 'lifecycle\.replicates\.seeds' = {n_tr - taken}"
    ):
        check_cross_keys(cfg, "tiny.yaml")


def test_replicates_without_the_damage_output_refused_at_config_time(tiny_config):
    cfg = tiny_config
    cfg["lifecycle"]["replicates"].update(states=2, seeds=1)
    cfg["lifecycle"]["rbf"]["outputs"] = ["surge_mpm", "damage_tn"]
    with pytest.raises(ConfigError, match=r"'lifecycle\.rbf\.outputs' = \['surge_mpm', 'damage_tn'\] does not rebuild"):
        check_cross_keys(cfg, "tiny.yaml")


def test_default_study_replicates_nothing(study_config):
    r = study_config["lifecycle"]["replicates"]
    assert r["states"] == 0, "states: 0 keeps the paper's method (one record per training state)"


# ----------------------------------------------------------------------------- end to end


@pytest.mark.workflow
def test_replicates_end_to_end(study):
    """The tiny study: 9 MDA + 3 from a round + 2 states x 1 seed = selection.n_train 14; each
    system's 2 replicated states are fitted on the mean of their two records."""
    cfg = mio.read_yaml(study / "tests" / "data" / "tiny.yaml")
    n, k = cfg["lifecycle"]["replicates"]["states"], cfg["lifecycle"]["replicates"]["seeds"]
    ad = cfg["lifecycle"]["adaptive"]
    assert (n, k) == (2, 1)
    cases = mio.open_zarr(study / "results/selection/cases.zarr")
    n_mda = cfg["selection"]["n_train"] - ad["rounds"] * ad["per_round"] - n * k
    assert cases.attrs["n_train"] == n_mda
    for ms in ("MS1", "MS3"):
        picks = mio.open_zarr(study / f"results/{ms}/replicates/picks.zarr")
        # a replicated state may be one of the round's picks: the training records merged
        _, sims = merged(
            study / "results/selection/cases.zarr",
            study / f"results/{ms}/simulations.zarr",
            [study / f"results/{ms}/rounds/picks_{r}.zarr" for r in range(1, ad["rounds"] + 1)],
            [study / f"results/{ms}/rounds/simulations_{r}.zarr" for r in range(1, ad["rounds"] + 1)],
        )
        r1 = mio.open_zarr(study / f"results/{ms}/replicates/simulations_1.zarr")
        lc = mio.open_zarr(study / f"results/{ms}/lifecycle.zarr", load=False)
        ids = picks["case"].values
        assert picks.sizes["case"] == n and r1.attrs["random_stream"] == "replicate1"
        np.testing.assert_array_equal(r1["case"].values, ids)
        # other phases, so another record of the same sea state
        assert not np.array_equal(r1["damage_sn"].values, sims["damage_sn"].sel(case=ids).values)
        np.testing.assert_array_equal(r1["hs"].values, sims["hs"].sel(case=ids).values)
        assert lc.attrs["replicate_seeds"] == k and lc.sizes["train"] == n_mda + ad["rounds"] * ad["per_round"]
        rec = lc["train_records"].sel(train=ids).values
        assert (rec == 1 + k).all() and int((lc["train_records"].values > 1).sum()) == n
        # the RBF interpolates the training states exactly: at their hours, the mean of the records
        hours = picks["hindcast_index"].values
        mean = (sims["surge_mpm"].sel(case=ids).values + r1["surge_mpm"].sel(case=ids).values) / 2
        got = lc["surge_mpm"].isel(time=hours).values
        np.testing.assert_allclose(got, mean, rtol=1e-6)
        assert not np.allclose(got, sims["surge_mpm"].sel(case=ids).values, rtol=1e-6)
    assert rounds.ROUND_STREAM != rep.REPLICATE_STREAM
