"""The training records' seed noise in a reconstructed sum (moorlife.lifecycle.records)."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from moorlife import lifecycle, names
from moorlife.lifecycle.records import carried_shares, records_sum_cv

LINES = list(names.LINES)


def _stores(n_hours: int = 1500, n_train: int = 60, n_val: int = 10, seed: int = 3):
    rng = np.random.default_rng(seed)
    hc = xr.Dataset(
        {
            "wind_speed": ("time", rng.uniform(0, 25, n_hours)),
            "wind_dir": ("time", rng.uniform(0, 360, n_hours)),
            "hs": ("time", rng.uniform(0.3, 6, n_hours)),
            "tp": ("time", rng.uniform(4, 18, n_hours)),
            "wave_dir": ("time", rng.uniform(0, 360, n_hours)),
        },
        coords={"time": np.arange(n_hours).astype("timedelta64[h]") + np.datetime64("2000-01-01T00")},
    )
    idx = rng.choice(n_hours, n_train + n_val, replace=False)
    cases = xr.Dataset(
        {v: ("case", hc[v].values[idx]) for v in names.METOCEAN_VARS}, coords={"case": np.arange(idx.size)}
    )
    cases["role"] = ("case", np.array(["train"] * n_train + ["validate"] * n_val))
    hs, w = cases["hs"].values, cases["wind_speed"].values
    # a storm-weighted damage, with the seed scatter of one record per state
    base = 1e-7 * np.exp(0.9 * hs) * (1 + 0.03 * w)
    noise = np.exp(0.1 * rng.standard_normal((idx.size, 3)))
    sims = xr.Dataset(coords={"case": cases["case"].values, "line": LINES})
    sims["damage_sn"] = (("case", "line"), base[:, None] * np.array([1.0, 2.0, 0.5]) * noise)
    sims["surge_mpm"] = ("case", 2.0 + 0.5 * hs)
    return hc, cases, sims


def _settings(**kw) -> lifecycle.RBFSettings:
    return lifecycle.RBFSettings.from_config({"shape": "fixed", "outputs": ["damage_sn", "surge_mpm"], **kw})


def _sum_after(cases, sims, settings, hp, case, line, factor, var="damage_sn"):
    s2 = sims.copy(deep=True)
    s2[var].loc[{"case": case, "line": line}] = s2[var].sel(case=case, line=line).values * factor
    f2 = lifecycle.fit_reconstruction(cases, s2, settings=settings)
    j = f2.cols.index((var, line))
    return np.clip(lifecycle.predict_outputs(f2.model, hp)[:, j], 0, None).sum()


@pytest.mark.parametrize("log_damage", [True, False])
def test_carried_shares_are_the_first_order_effect_of_a_record_on_the_sum(log_damage):
    hc, cases, sims = _stores()
    settings = _settings(log_damage=log_damage)
    fitted = lifecycle.fit_reconstruction(cases, sims, settings=settings)
    hp = lifecycle._points(hc, "time")
    pred = lifecycle.predict_outputs(fitted.model, hp)
    dmg = [j for j, c in enumerate(fitted.cols) if c[0] == "damage_sn"]
    t = fitted.train
    g = carried_shares(fitted.model, hp, pred, fitted.values[t], fitted.points[t], dmg)
    assert g.shape == (int(t.sum()), 3)
    j = fitted.cols.index(("damage_sn", "M2"))
    s = np.clip(pred[:, j], 0, None).sum()
    e = 1e-6
    for i in np.argsort(-np.abs(g[:, 1]))[:3]:  # the states that carry the most of M2's sum
        moved = _sum_after(cases, sims, settings, hp, fitted.case[t][i], "M2", 1 + e) / s - 1
        assert moved == pytest.approx(g[i, 1] * e, rel=1e-3)
    # a share is of the sum itself: the shares of a log fit add to about one (a constant carried)
    if log_damage:
        assert g[:, 1].sum() == pytest.approx(1.0, abs=0.05)


def test_records_sum_cv_divides_each_record_by_its_replicates():
    g = np.array([[0.6, 0.1], [0.3, 0.1], [0.1, 0.8]])
    np.testing.assert_allclose(records_sum_cv(g), np.sqrt((g * g).sum(axis=0)))
    np.testing.assert_allclose(
        records_sum_cv(g, [4, 1, 1]), [np.sqrt(0.36 / 4 + 0.09 + 0.01), np.sqrt(0.0025 + 0.01 + 0.64)]
    )
    with pytest.raises(ValueError, match="records must be >= 1"):
        records_sum_cv(g, [1, 0, 1])
    with pytest.raises(ValueError, match="one per training state"):
        records_sum_cv(g, [1, 1])


def test_one_record_carrying_a_sum_gives_its_own_cv():
    """A sum that one training state carries alone has that record's scatter: c |G| / S = c."""
    g = np.zeros((5, 1))
    g[2] = 1.0
    assert records_sum_cv(g)[0] == 1.0
    assert records_sum_cv(np.full((400, 1), 1 / 400))[0] == pytest.approx(1 / 20)


def test_lifecycle_store_carries_the_records_term_and_the_band_takes_it():
    hc, cases, sims = _stores()
    settings = _settings()
    lc = lifecycle.reconstruct_lifecycle(hc, cases, sims, settings=settings, n_suggest=2)
    rc = lc["records_sum_cv"]
    assert np.isnan(rc.sel(output="surge_mpm"))
    fitted = lifecycle.fit_reconstruction(cases, sims, settings=settings)
    hp = lifecycle._points(hc, "time")
    expect = lifecycle.records_term(fitted, hp, lifecycle.predict_outputs(fitted.model, hp))
    np.testing.assert_array_equal(rc.values, expect)
    # the fit given (a harness's, which also takes a window's term) gives the same store
    again = lifecycle.reconstruct_lifecycle(hc, cases, sims, settings=settings, n_suggest=2, fitted=fitted)
    xr.testing.assert_identical(again, lc)
    other = lifecycle.fit_reconstruction(cases, sims.isel(case=slice(1, None)), settings=settings)
    with pytest.raises(ValueError, match=r"the fit given holds cases 69 \(\[1, 2, 3\] \.\.\.\), the stores 70"):
        lifecycle.reconstruct_lifecycle(hc, cases, sims, settings=settings, fitted=other)
    # 60 records for 1,500 hours: the records' term is far above the independent hours'
    cv = 0.15
    labels = [f"damage_sn/{ln}" for ln in LINES]
    hours = lifecycle.sum_seed_cv(lc["damage_sn"].transpose("time", "line").values, cv)
    assert np.all(cv * rc.sel(output=labels).values > 3 * hours)
    seed = np.hypot(hours, cv * rc.sel(output=labels).values).max()
    assert lifecycle.band_sigma(lc, "sn", {"sn": cv}) == pytest.approx(
        np.hypot(seed, lifecycle.validation_sum_term(lc, "sn")), rel=1e-12
    )
    # replicates divide a record's term by the square root of its records
    sims4 = sims.assign(n_records=("case", np.full(sims.sizes["case"], 4)))
    f4 = lifecycle.fit_reconstruction(cases, sims4, settings=settings)
    pred = lifecycle.predict_outputs(f4.model, hp)
    np.testing.assert_allclose(lifecycle.records_term(f4, hp, pred), expect / 2, rtol=1e-12)


def test_gp_records_term_matches_its_kernel_and_skips_a_linear_mean():
    from moorlife import gp

    hc, cases, sims = _stores(n_hours=400, n_train=40, n_val=5)
    hp = lifecycle._points(hc, "time")
    settings = _settings(method="gp", gp={"restarts": 0})
    fitted = lifecycle.fit_reconstruction(cases, sims, settings=settings)
    pred = lifecycle.predict_outputs(fitted.model, hp)
    rc = lifecycle.records_term(fitted, hp, pred)
    j = fitted.cols.index(("damage_sn", "M1"))
    m, cols = fitted.model.models[0], fitted.model.columns[0]
    jj = int(np.flatnonzero(cols == j)[0])
    g = gp.training_weights(m, hp, np.clip(pred[:, j], 0, None), outputs=[jj])[:, 0]
    assert rc[j] == pytest.approx(np.linalg.norm(g) / np.clip(pred[:, j], 0, None).sum(), rel=1e-12)
    linear = lifecycle.fit_reconstruction(
        cases, sims, settings=_settings(method="gp", gp={"restarts": 0, "mean": "linear"})
    )
    assert np.all(np.isnan(lifecycle.records_term(linear, hp, lifecycle.predict_outputs(linear.model, hp))))


def test_window_records_refit_checks_the_store_and_takes_the_windows_hours():
    from moorlife.stages.truth import window_records

    hc, cases, sims = _stores()
    settings = _settings()
    lc = lifecycle.reconstruct_lifecycle(hc, cases, sims, settings=settings, n_suggest=2)
    fitted = lifecycle.fit_reconstruction(cases, sims, settings=settings)
    hours = np.arange(200, 500)
    got = window_records(fitted, lc, hours, source="lc.zarr")
    hp = lifecycle._points(hc.isel(time=hours), "time")
    expect = lifecycle.records_term(fitted, hp, lifecycle.predict_outputs(fitted.model, hp))
    assert got == {
        f"damage_sn/{ln}": pytest.approx(expect[fitted.cols.index(("damage_sn", ln))], rel=1e-12) for ln in LINES
    }
    # a window of 300 hours rests on fewer records than 1,500: its term is larger
    assert all(got[k] > lc["records_sum_cv"].sel(output=k) for k in got)
    # a store built from other simulations is refused, naming it and the hour
    other = sims.copy(deep=True)
    other["damage_sn"] = other["damage_sn"] * 1.01
    with pytest.raises(ValueError, match=r"lc.zarr: damage_sn/M1 at hindcast hour 200 .* other simulations"):
        window_records(lifecycle.fit_reconstruction(cases, other, settings=settings), lc, hours, source="lc.zarr")
