"""Tests of moorlife.lifecycle on small synthetic hindcasts and simulation stores with known answers."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
import xarray as xr

from moorlife import fatigue, gp, lifecycle, names
from moorlife.config import ConfigError

LINES = list(names.LINES)


def _hindcast(n: int = 3000, seed: int = 0) -> xr.Dataset:
    rng = np.random.default_rng(seed)
    data = {
        "wind_speed": rng.uniform(0, 25, n),
        "wind_dir": rng.uniform(0, 360, n),
        "hs": rng.uniform(0.3, 6, n),
        "tp": rng.uniform(4, 18, n),
        "wave_dir": rng.uniform(0, 360, n),
    }
    t = np.arange(n).astype("timedelta64[h]") + np.datetime64("2000-01-01T00")
    return xr.Dataset({k: ("time", v, names.attrs_for(k)) for k, v in data.items()}, coords={"time": t})


def _cases(hc: xr.Dataset, n_train: int = 90, n_val: int = 25, seed: int = 1) -> xr.Dataset:
    idx = np.random.default_rng(seed).choice(hc.sizes["time"], n_train + n_val, replace=False)
    ds = xr.Dataset({v: ("case", hc[v].values[idx]) for v in names.METOCEAN_VARS}, coords={"case": np.arange(idx.size)})
    ds["hindcast_index"] = ("case", idx)
    ds["role"] = ("case", np.array(["train"] * n_train + ["validate"] * n_val))
    return ds


def _sims(cases: xr.Dataset, damage=(2e-6, 5e-6, 1e-6)) -> xr.Dataset:
    """Outputs with known closed forms: linear offsets, constant damage per line."""
    hs, tp, w = cases["hs"].values, cases["tp"].values, cases["wind_speed"].values
    n = hs.size
    ds = xr.Dataset(coords={"case": cases["case"].values, "line": LINES})
    ds["surge_mpm"] = ("case", 2.0 + 0.5 * hs + 0.1 * tp)
    ds["sway_mpm"] = ("case", 1.0 + 0.2 * w)
    ds["tension_mpm"] = (("case", "line"), np.outer(1e6 + 1e5 * hs, [1.0, 1.2, 0.9]))
    ds["damage_sn"] = (("case", "line"), np.tile(np.asarray(damage), (n, 1)))
    ds["damage_tn"] = (("case", "line"), 0.5 * np.tile(np.asarray(damage), (n, 1)))
    ds.attrs["mooring_system"] = "MS2"
    return ds


SETTINGS = lifecycle.RBFSettings.from_config({"shape": "fixed", "outputs": list(lifecycle.DEFAULT_OUTPUTS)})


@pytest.fixture(scope="module")
def rebuilt():
    hc = _hindcast()
    cases = _cases(hc)
    sims = _sims(cases)
    ds = lifecycle.reconstruct_lifecycle(hc, cases, sims, settings=SETTINGS, n_suggest=5)
    return hc, cases, sims, ds


def test_constant_hourly_damage_gives_n_hours_times_value(rebuilt):
    hc, _, _, ds = rebuilt
    n = hc.sizes["time"]
    expect = np.array([[2e-6, 5e-6, 1e-6], [1e-6, 2.5e-6, 0.5e-6]]) * n
    np.testing.assert_allclose(ds["lifecycle_damage"].sel(curve=["sn", "tn"]).values, expect, rtol=1e-9)
    np.testing.assert_allclose(ds["damage_per_year"].values, expect / n * 8766.0, rtol=1e-9)
    np.testing.assert_allclose(ds["fatigue_life_years"].values, 1.0 / (expect / n * 8766.0), rtol=1e-9)
    assert ds["damage_sn"].dims == ("time", "line") and ds.sizes["time"] == n


def test_linear_outputs_rebuilt_exactly_everywhere(rebuilt):
    hc, _, _, ds = rebuilt
    np.testing.assert_allclose(ds["surge_mpm"].values, 2.0 + 0.5 * hc["hs"].values + 0.1 * hc["tp"].values, atol=1e-8)
    np.testing.assert_allclose(ds["tension_mpm"].sel(line="M2").values, 1.2 * (1e6 + 1e5 * hc["hs"].values), rtol=1e-10)
    np.testing.assert_allclose(
        ds["validation_r"].sel(output=["surge_mpm", "sway_mpm", "tension_mpm/M1"]).values, 1.0, atol=1e-10
    )
    assert ds["tension_mpm"].attrs["units"] == "N"


def test_design_check_uses_fatigue_rules(rebuilt):
    _, _, _, ds = rebuilt
    fs = fatigue.fatigue_settings({})
    # S-N: DNV rule, dF = 2e-6 / 5e-6 = 0.4 -> DFF 5; T-N: API -> 3
    assert float(ds["damage_ratio"].sel(curve="sn")) == pytest.approx(0.4)
    assert float(ds["design_fatigue_factor"].sel(curve="sn")) == 5.0
    assert float(ds["design_fatigue_factor"].sel(curve="tn")) == 3.0
    util = ds["utilisation"].sel(curve="sn", line="M2")
    assert float(util) == pytest.approx(5.0 * 5e-6 * 8766.0 * fs.design_life, rel=1e-9)
    assert int(ds["passes"].sel(curve="sn", line="M2")) == int(float(util) <= 1)


def test_design_check_dnv_factor_rises_with_adjacent_damage():
    fs = fatigue.fatigue_settings({})
    out = lifecycle.design_check(np.array([1e-2, 0.9e-2, 0.1e-2]), 25.0, "sn", fs)
    assert float(out["damage_ratio"]) == pytest.approx(0.9)
    assert float(out["design_fatigue_factor"]) == pytest.approx(5 + 3 * 0.1 / 0.2)
    np.testing.assert_allclose(out["utilisation"], 6.5 * 25 * np.array([1e-2, 0.9e-2, 0.1e-2]))
    np.testing.assert_array_equal(out["passes"], [False, False, True])


def test_validation_metrics_closed_form():
    sim = np.array([[1.0, 2.0], [2.0, 4.0], [3.0, 6.0], [4.0, 8.0]])
    pred = np.column_stack([2 * sim[:, 0] + 1, sim[:, 1]])
    m = lifecycle.validation_metrics(pred, sim)
    np.testing.assert_allclose(m["r"], [1.0, 1.0])
    np.testing.assert_allclose(m["slope"], [2.0, 1.0])
    np.testing.assert_allclose(m["intercept"], [1.0, 0.0], atol=1e-12)
    np.testing.assert_allclose(m["bias"], [3.5, 0.0])
    np.testing.assert_allclose(m["rmse"][0], np.sqrt(np.mean((sim[:, 0] + 1) ** 2)))
    np.testing.assert_allclose(m["sum_error"], [24 / 10 - 1, 0.0], atol=1e-12)
    noisy = lifecycle.validation_metrics(sim[:, 0] + np.array([0.1, -0.1, 0.1, -0.1]), sim[:, 0])
    assert 0.99 < noisy["r"][0] < 1.0


def test_discrete_baseline_arithmetic_and_difference_sign():
    p = np.array([0.5, 0.3, 0.2])
    hourly = np.array([[1.0, 2.0], [3.0, 4.0], [5.0, 6.0]]) * 1e-6
    got = lifecycle.discrete_damage(p, hourly, 1000.0)
    np.testing.assert_allclose(got, [(0.5 + 0.9 + 1.0) * 1e-3, (1.0 + 1.2 + 1.2) * 1e-3])
    assert lifecycle.difference_pct(10.0, 8.0) == pytest.approx(20.0)  # discrete underestimates -> positive
    assert lifecycle.difference_pct(10.0, 12.0) == pytest.approx(-20.0)
    with pytest.raises(ValueError, match="sum to 1"):
        lifecycle.discrete_damage([0.5, 0.3], hourly[:2], 10.0)
    bad = hourly.copy()
    bad[1, 0] = -1e-6
    with pytest.raises(ValueError, match=r"index \(1, 0\)"):
        lifecycle.discrete_damage(p, bad, 10.0)


def test_discrete_table_and_summary(rebuilt):
    hc, _, _, ds = rebuilt
    states = xr.Dataset({"probability": ("bin", [0.25, 0.75])}, coords={"bin": [0, 1]})
    dsims = xr.Dataset(
        {
            "damage_sn": (("bin", "line"), [[1e-6, 4e-6, 1e-6], [2e-6, 4e-6, 1e-6]]),
            "damage_tn": (("bin", "line"), [[1e-6, 2e-6, 1e-6], [1e-6, 2e-6, 1e-6]]),
        },
        coords={"bin": [0, 1], "line": LINES},
    )
    n = hc.sizes["time"]
    dd = lifecycle.discrete_damage_table(states, dsims, n)
    assert float(dd["discrete_damage"].sel(curve="sn", line="M1")) == pytest.approx(1.75e-6 * n)
    mooring = pd.DataFrame({"mass_kg_per_m": [125.6], "link_diameter_mm": [79.0]}, index=["MS2"])
    table = lifecycle.summary_table({"MS2": ds}, {"MS2": dd}, mooring)
    assert len(table) == 6
    r = table[(table.line == "M1") & (table.curve == "sn")].iloc[0]
    assert r.difference_pct == pytest.approx(100 * (2e-6 - 1.75e-6) / 2e-6, rel=1e-9)
    assert r.fatigue_life_low <= r.fatigue_life_years <= r.fatigue_life_high
    for col in (
        "mooring_system",
        "line",
        "curve",
        "lifecycle_damage",
        "discrete_damage",
        "difference_pct",
        "fatigue_life_years",
        "design_fatigue_factor",
        "passes",
    ):
        assert col in table.columns


def test_recommend_picks_the_lightest_passing_system():
    rows = []
    for ms, mass, ok_sn, ok_tn in (
        ("MS1", 92, False, True),
        ("MS2", 125.6, True, True),
        ("MS3", 200, True, True),
        ("MS0", 50, True, False),
    ):
        for line in LINES:
            rows += [
                {"mooring_system": ms, "line": line, "curve": "sn", "passes": ok_sn, "mass_kg_per_m": mass},
                {"mooring_system": ms, "line": line, "curve": "tn", "passes": ok_tn, "mass_kg_per_m": mass},
            ]
    t = pd.DataFrame(rows)
    assert lifecycle.recommend(t) == "MS2"
    assert lifecycle.recommend(t, curves=["sn"]) == "MS0"
    assert lifecycle.recommend(t, curves=["tn"]) == "MS1"
    t.loc[t.mooring_system.isin(["MS2", "MS3"]) & (t.line == "M2"), "passes"] = False
    assert lifecycle.recommend(t) is None


def test_seed_lives_and_band():
    lives = lifecycle.seed_lives([1e-5, 2e-5])
    np.testing.assert_allclose(lives, [1 / (1e-5 * 8766), 1 / (2e-5 * 8766)])
    lo, hi = lifecycle.life_band(10.0, 0.25)
    assert lo == pytest.approx(8.0) and hi == pytest.approx(10 / 0.75)
    assert lifecycle.life_band(10.0, 1.5)[1] == np.inf


def test_seed_scatter_of_a_sum_matches_independent_seeds():
    """sum_seed_cv against the sd of sums of hours each drawn with its own seed error."""
    rng = np.random.default_rng(3)
    hours = rng.lognormal(-10, 1.5, 500)  # a few hours dominate, as storms do
    cv = 0.17
    draws = hours * (1 + cv * rng.standard_normal((20000, hours.size)))
    measured = draws.sum(axis=1).std() / hours.sum()
    predicted = lifecycle.sum_seed_cv(hours, cv)
    assert predicted == pytest.approx(measured, rel=0.02)
    assert cv / np.sqrt(hours.size) < predicted < cv
    # the two limits: one hour keeps its CV, n equal hours divide it by sqrt(n)
    assert lifecycle.sum_seed_cv([0, 0, 3.0], cv) == pytest.approx(cv)
    assert lifecycle.sum_seed_cv(np.ones(400), cv) == pytest.approx(cv / 20)
    np.testing.assert_allclose(lifecycle.sum_seed_cv(np.zeros((5, 2)), cv), 0.0)


def test_band_sigma_takes_the_seed_scatter_of_the_sum():
    n = 10_000
    hourly = np.full((n, 3), 1e-6)
    hourly[0, 1] = 1e-3  # one storm hour holds most of M2's sum
    lc = xr.Dataset(
        {
            "damage_sn": (("time", "line"), hourly),
            "validation_sum_error": ("output", [0.04, -0.06, 0.02, 0.9]),
        },
        coords={
            "time": np.arange(n),
            "line": list(names.LINES),
            "output": [*(f"damage_sn/{x}" for x in names.LINES), "x"],
        },
    )
    seed = lifecycle.sum_seed_cv(hourly, 0.2).max()  # M2's, set by its storm hour
    assert lifecycle.band_sigma(lc, "sn", {"sn": 0.2}) == pytest.approx(np.hypot(seed, 0.06))
    assert lifecycle.band_sigma(lc, "sn") == pytest.approx(0.06)
    # without hourly damage the one-hour CV stands for the sum: an upper bound
    assert lifecycle.band_sigma(lc.drop_vars("damage_sn"), "sn", {"sn": 0.2}) == pytest.approx(np.hypot(0.2, 0.06))


def test_coverage_needed_and_its_calibration():
    k = lifecycle.coverage_needed([15.7, -3.6, 0.0], [12.18, 13.89, 12.0])
    np.testing.assert_allclose(k, [15.7 / 12.18, 3.6 / 13.89, 0.0])
    assert lifecycle.coverage_needed(1.0, 0.0) == np.inf and lifecycle.coverage_needed(0.0, 0.0) == 0.0
    assert lifecycle.calibrate_coverage([*k, np.nan]) == pytest.approx(1.30)
    assert lifecycle.calibrate_coverage([0.5, 1.0]) == pytest.approx(1.0)  # a multiple of the step stays
    with pytest.raises(ValueError, match="no measured case"):
        lifecycle.calibrate_coverage([np.nan, np.inf])


def test_mean_stress_table_reproduces_paper_table8_static_rows():
    # Barrera et al. (2019) Table 8 (static position), from Table 4 pretension and link diameter.
    mooring = pd.DataFrame(
        {"pretension_kN": [811.0, 1770.0, 5675.0], "link_diameter_mm": [68.0, 100.0, 178.0]},
        index=["MS1", "MS3", "MS6"],
    )
    t = lifecycle.mean_stress_table(mooring)
    expect = {
        "MS1": (111.6563, 0.8837, 0.8405, 0.9865),
        "MS3": (112.6817, 0.8826, 0.8390, 0.9862),
        "MS6": (114.0265, 0.8812, 0.8371, 0.9859),
    }
    for ms, (s, g, so, ge) in expect.items():
        r = t[(t.mooring_system == ms) & (t.block == "static")].iloc[0]
        assert round(r.mean_stress_mpa, 4) == s
        assert (round(r.goodman, 4), round(r.soderberg, 4), round(r.gerber, 4)) == (g, so, ge)
    t2 = lifecycle.mean_stress_table(mooring, {"MS1": 1.0e6})
    assert set(t2.block) == {"static", "lifecycle mean"}
    assert np.isnan(t2[(t2.block == "lifecycle mean") & (t2.mooring_system == "MS3")].goodman.iloc[0])


def test_corrosion_evolution():
    fs = fatigue.fatigue_settings({})
    out = lifecycle.corrosion_evolution(0.02, 0.079, 25.0, curve="sn", settings=fs)
    np.testing.assert_allclose(out["years"], [0, 5, 10, 15, 20, 25])
    np.testing.assert_allclose(out["intact"], 0.02 * out["years"])
    # first step at the new diameter, second at d0 - 1 mm: factor (d0 / d)^(2 m)
    np.testing.assert_allclose(out["corroded"][1], 0.1)
    np.testing.assert_allclose(out["corroded"][2] - out["corroded"][1], 0.1 * (0.079 / 0.078) ** 6)
    assert np.all(np.diff(out["factor"]) > 0)
    none = lifecycle.corrosion_evolution(
        0.02, 0.079, 25.0, curve="tn", settings=fatigue.fatigue_settings({"corrosion": {"rate": 0.0}})
    )
    np.testing.assert_allclose(none["corroded"], none["intact"])


def test_suggestions_target_uncertain_sparse_regions(rebuilt):
    hc, cases, sims, ds = rebuilt
    picks = ds["suggested_hour"].values
    assert picks.size == 5 and np.unique(picks).size == 5
    assert picks[0] == int(np.argmax(ds["error_indicator"].values))
    train_idx = cases["hindcast_index"].values[cases["role"].values == "train"]
    assert not np.isin(picks, train_idx).any()  # training hours have zero distance -> never suggested


def test_rippa_mode_and_other_transform_are_reported():
    hc = _hindcast(800, seed=5)
    cases = _cases(hc, 60, 15, seed=6)
    sims = _sims(cases)
    rng = np.random.default_rng(7)
    dmg = 1e-6 * (cases["hs"].values[:, None] ** 3) * np.array([1.0, 2.0, 0.5]) * (1 + 0.05 * rng.random((75, 3)))
    sims["damage_sn"] = (("case", "line"), dmg)
    settings = lifecycle.RBFSettings.from_config({"grid": {"n": 8}, "outputs": list(lifecycle.DEFAULT_OUTPUTS)})
    ds = lifecycle.reconstruct_lifecycle(hc, cases, sims, settings=settings, n_suggest=0)
    assert np.all(ds["validation_r"].sel(output="damage_sn/M2") > 0.95)
    assert np.isfinite(ds["validation_r_other_transform"].sel(output="damage_sn/M2"))
    assert np.isnan(ds["validation_r_other_transform"].sel(output="surge_mpm"))
    assert ds.attrs["rbf_shape_mode"] == "rippa"
    assert np.all(np.isin(ds["shape_parameter"].values, np.geomspace(settings.grid_min, settings.grid_max, 8)))
    assert np.all(np.isin(ds["smoothing"].values, settings.smoothing))


def test_bad_simulation_values_are_named():
    hc = _hindcast(300)
    cases = _cases(hc, 40, 5)
    sims = _sims(cases)
    sims["surge_mpm"][7] = np.nan
    with pytest.raises(ValueError, match="surge_mpm is not finite for case 7"):
        lifecycle.reconstruct_lifecycle(hc, cases, sims, settings=SETTINGS, n_suggest=0)
    with pytest.raises(ValueError, match="index"):
        lifecycle.life_damage(np.array([[1.0, -1.0]]))
    with pytest.raises(ValueError, match="lifecycle.rbf.shape"):
        lifecycle.rbf_settings({"shape": "magic"})


@pytest.mark.slow
def test_stores_comparison_and_sensitivity_end_to_end(tmp_path):
    """The io layer on tiny synthetic stores: lifecycle.zarr, summary.csv, recommendation, figures."""
    import yaml

    from moorlife.io import open_zarr, write_zarr
    from moorlife.stages import compare as st_compare
    from moorlife.stages import lifecycle as st_lifecycle
    from moorlife.stages import sensitivity as st_sensitivity

    hc = _hindcast(1500, seed=8)
    cases = _cases(hc, 50, 10, seed=9)
    write_zarr(hc, tmp_path / "hindcast.zarr")
    write_zarr(cases, tmp_path / "cases.zarr")
    systems = ["MS1", "MS2"]
    pd.DataFrame(
        {
            "mooring_system": systems,
            "mass_kg_per_m": [92.0, 125.6],
            "pretension_kN": [811.0, 1112.0],
            "link_diameter_mm": [68.0, 79.0],
            "equivalent_diameter_m": [0.1199, 0.1398],
            "EA_N": [5.43e8, 7.45e8],
            "MBS_N": [5420364.0, 7200284.0],
            "chain": ["studless", "studless"],
        }
    ).to_csv(tmp_path / "ms.tsv", sep="\t", index=False)
    write_zarr(xr.Dataset({"probability": ("bin", [0.4, 0.6])}, coords={"bin": [0, 1]}), tmp_path / "bins.zarr")
    cfg = {"rbf": {"shape": "fixed"}, "adaptive": {"n_suggest": 3}, "recommendation": {"curves": ["sn", "tn"]}}
    for k, ms in enumerate(systems):
        s = _sims(cases, damage=np.array([2e-6, 5e-6, 1e-6]) / 10 ** (2 * k))
        s["tension_mean"] = (("case", "line"), np.full((60, 3), 1e6 * (k + 1)))
        write_zarr(s, tmp_path / f"{ms}_sims.zarr")
        d = xr.Dataset(
            {v: (("bin", "line"), np.full((2, 3), 1e-6 / 10 ** (2 * k))) for v in ("damage_sn", "damage_tn")},
            coords={"bin": [0, 1], "line": LINES},
        )
        write_zarr(d, tmp_path / f"{ms}_disc.zarr")
        st_lifecycle.run(
            hindcast=tmp_path / "hindcast.zarr",
            cases=tmp_path / "cases.zarr",
            simulations=tmp_path / f"{ms}_sims.zarr",
            store=tmp_path / f"{ms}_lc.zarr",
            lifecycle=cfg,
            fatigue={},
            threads=1,
        )
    lc = open_zarr(tmp_path / "MS1_lc.zarr")
    assert lc["damage_sn"].dims == ("time", "line") and lc.sizes["time"] == 1500
    np.testing.assert_allclose(lc["lifecycle_damage"].sel(curve="sn").values, np.array([2e-6, 5e-6, 1e-6]) * 1500)
    st_lifecycle.figures(
        lifecycle=tmp_path / "MS1_lc.zarr",
        **{k: tmp_path / f"{k}.png" for k in ("validation", "loo_map", "damage_metocean")},
        ms="MS1",
    )
    lcs = [tmp_path / f"{ms}_lc.zarr" for ms in systems]
    stores = dict(
        lifecycles=lcs,
        discretes=[tmp_path / f"{ms}_disc.zarr" for ms in systems],
        bins=tmp_path / "bins.zarr",
        mooring_systems=tmp_path / "ms.tsv",
        systems=systems,
    )
    table = st_compare.run(
        **stores, summary=tmp_path / "summary.csv", recommendation=tmp_path / "rec.yaml", lifecycle=cfg
    )
    csv = pd.read_csv(tmp_path / "summary.csv")
    assert len(csv) == len(table) == 12
    # MS1 damages 2e-6..5e-6 per hour -> ~0.04 per year x 25 y x DFF fails; MS2 is 100x lower and passes
    rec = yaml.safe_load((tmp_path / "rec.yaml").read_text())
    assert rec["recommended"] == "MS2"
    r = csv[(csv.mooring_system == "MS1") & (csv.line == "M2") & (csv.curve == "sn")].iloc[0]
    assert r.difference_pct == pytest.approx(100 * (5e-6 - 1e-6) / 5e-6)
    # judged on the corroding chain, the verdict can only get stricter
    corr = lifecycle.summary_table(
        {ms: open_zarr(p) for ms, p in zip(systems, lcs)},
        {
            ms: lifecycle.discrete_damage_table(
                open_zarr(tmp_path / "bins.zarr"), open_zarr(tmp_path / f"{ms}_disc.zarr"), 1500
            )
            for ms in systems
        },
        pd.read_csv(tmp_path / "ms.tsv", sep="\t").set_index("mooring_system"),
        corrosion=fatigue.fatigue_settings({}),
    )
    assert np.all(corr["utilisation_corroded"] > corr["utilisation"])
    assert not np.any(corr["passes"] & ~table["passes"])
    st_compare.figures(
        summary=tmp_path / "summary.csv",
        recommendation=tmp_path / "rec.yaml",
        lifecycles=lcs,
        **{k: tmp_path / f"{k}.png" for k in ("damage_mass", "difference", "offsets")},
        recommendation_fig=tmp_path / "recommendation.png",
        systems=systems,
    )
    seeds = xr.Dataset(
        {
            v: (("case", "line"), np.full((4, 3), 1e-5) * np.array([[1], [1.1], [0.9], [1.2]]))
            for v in ("damage_sn", "damage_tn")
        },
        coords={"case": np.arange(4) + 10**6, "line": LINES},
    )
    write_zarr(seeds, tmp_path / "seeds.zarr")
    # the summary's band takes the seed scatter of the life-cycle sum, from the hourly damage
    banded = st_compare.run(
        **stores,
        summary=tmp_path / "summary_band.csv",
        recommendation=tmp_path / "rec_band.yaml",
        lifecycle={**cfg, "uncertainty": {"coverage": 1.0}},
        seeds=tmp_path / "seeds.zarr",
    )
    cv = st_compare._seed_cv(tmp_path / "seeds.zarr")
    sigma = lifecycle.band_sigma(open_zarr(tmp_path / "MS1_lc.zarr"), "sn", cv)
    assert sigma < 0.5 * cv["sn"]  # 1,500 hours average one hour's seed error out
    r = banded[(banded.mooring_system == "MS1") & (banded.curve == "sn")].iloc[0]
    assert r.fatigue_life_low == pytest.approx(r.fatigue_life_years / (1 + sigma), rel=1e-12)
    outs = {
        k: tmp_path / "sens" / f"{k}.{'csv' if k.endswith('csv') else 'png'}"
        for k in ("seeds_csv", "seeds_fig", "corrosion_csv", "corrosion_fig", "mean_stress_csv", "mean_stress_fig")
    }
    st_sensitivity.run(
        seeds=tmp_path / "seeds.zarr",
        lifecycle=lcs[1],
        lifecycles=lcs,
        mooring_systems=tmp_path / "ms.tsv",
        **outs,
        systems=systems,
        ms="MS2",
        line="M1",
        fatigue={},
    )
    lives = pd.read_csv(outs["seeds_csv"])
    assert lives[(lives.curve == "sn") & (lives.line == "M1")]["life_years"].max() == pytest.approx(
        1 / (0.9e-5 * 8766), rel=1e-5
    )
    ms_tab = pd.read_csv(outs["mean_stress_csv"])
    assert ms_tab[(ms_tab.block == "lifecycle mean") & (ms_tab.mooring_system == "MS2")]["mean_tension_kN"].iloc[
        0
    ] == pytest.approx(2000.0)
    for p in [*outs.values(), *(tmp_path / f"{k}.png" for k in ("validation", "damage_mass", "recommendation"))]:
        assert p.stat().st_size > (200 if p.suffix == ".csv" else 5000), p


def test_selection_normalisation_is_used_in_any_attribute_order():
    hc = _hindcast(600, seed=11)
    cases = _cases(hc, 40, 8, seed=12)
    sims = _sims(cases)
    order = ["hs", "tp", "wave_dir", "wind_speed", "wind_dir"]
    lo = {"wind_speed": -5.0, "wind_dir": 0.0, "hs": 0.0, "tp": 2.0, "wave_dir": 0.0}
    span = {"wind_speed": 40.0, "wind_dir": 180.0, "hs": 10.0, "tp": 20.0, "wave_dir": 180.0}
    cases.attrs.update(norm_variables=order, norm_lo=[lo[v] for v in order], norm_span=[span[v] for v in order])
    settings = lifecycle.RBFSettings.from_config({"shape": "fixed", "outputs": ["surge_mpm"]})
    a = lifecycle.reconstruct_lifecycle(hc, cases, sims, settings=settings, n_suggest=0)
    # the same space given in METOCEAN_VARS order gives identical numbers
    cases.attrs.update(
        norm_variables=list(names.METOCEAN_VARS),
        norm_lo=[lo[v] for v in names.METOCEAN_VARS],
        norm_span=[span[v] for v in names.METOCEAN_VARS],
    )
    b = lifecycle.reconstruct_lifecycle(hc, cases, sims, settings=settings, n_suggest=0)
    np.testing.assert_array_equal(a["nearest_distance"].values, b["nearest_distance"].values)
    # and differs from the training-range normalisation
    del cases.attrs["norm_lo"]
    c = lifecycle.reconstruct_lifecycle(hc, cases, sims, settings=settings, n_suggest=0)
    assert not np.allclose(a["nearest_distance"].values, c["nearest_distance"].values)
    cases.attrs.update(norm_lo=[0.0] * 4)
    with pytest.raises(ValueError, match="inconsistent"):
        lifecycle.reconstruct_lifecycle(hc, cases, sims, settings=settings, n_suggest=0)


# ------------------------------------------------------------------ per-output space and transform
def _thrust_curve() -> lifecycle.ThrustCurve:
    from pathlib import Path

    from moorlife.io import read_yaml

    return lifecycle.thrust_curve(read_yaml(Path(__file__).resolve().parents[1] / "config/platform.yaml"))


PER_OUTPUT = {"choose": "per_output", "grid": {"n": 8}, "outputs": list(lifecycle.DEFAULT_OUTPUTS)}


def test_thrust_coordinate_is_t_of_w_scaled_by_its_range_over_the_wind_range():
    curve = _thrust_curve()
    x = np.array([[11.3, 0.0, 1.0, 8.0, 0.0], [5.0, 90.0, 2.0, 9.0, 180.0], [30.0, 0.0, 1.0, 8.0, 0.0]])
    lo, span = [0.0, 0.0, 0.0, 2.0, 0.0], [30.0, 180.0, 10.0, 20.0, 180.0]
    x6, mask, lo6, span6 = lifecycle.space_inputs("thrust", x, lo, span, curve)
    np.testing.assert_array_equal(x6[:, :5], x)
    np.testing.assert_array_equal(x6[:, 5], lifecycle.thrust_at(curve, x[:, 0]))
    np.testing.assert_array_equal(mask, [False, True, False, False, True, False])
    assert x6[2, 5] == 0.0 and x6[0, 5] == pytest.approx(819e3, rel=0.01)  # above cut-out; the rated peak
    assert lo6[5] == 0.0 and span6[5] == pytest.approx(x6[0, 5], rel=1e-3)  # 0 .. the peak over W in [0, 30]
    np.testing.assert_array_equal(lo6[:5], lo)
    # above rated only: from T(25 m/s) to T(15 m/s)
    _, _, lo_b, span_b = lifecycle.space_inputs("thrust", x, [15.0, 0, 0, 2, 0], [10.0, 180, 10, 20, 180], curve)
    t15, t25 = lifecycle.thrust_at(curve, [15.0, 25.0])
    assert lo_b[5] == pytest.approx(t25) and span_b[5] == pytest.approx(t15 - t25)
    assert lifecycle.space_inputs("paper", x, lo, span)[0] is not None
    with pytest.raises(ValueError, match="thrust curve"):
        lifecycle.space_inputs("thrust", x, lo, span)
    with pytest.raises(ValueError, match="unknown RBF input space"):
        lifecycle.space_inputs("6d", x, lo, span, curve)


def _ridge_outputs(cases: xr.Dataset, curve: lifecycle.ThrustCurve) -> np.ndarray:
    """A damage sharp in W around rated (a power of T(W)) and a motion smooth in the 5-D space."""
    w, _, hs, tp, alpha = lifecycle._points(cases, "case").T
    t = lifecycle.thrust_at(curve, w) / 819e3
    ridge = 1e-6 * t**8 * (1 + 0.1 * hs) + 1e-9
    smooth = 1.0 + 0.3 * hs**2 + 0.004 * w**2 + 0.2 * np.cos(np.deg2rad(alpha)) + 0.05 * tp
    return np.column_stack([ridge, smooth])


def _ridge_stores(n_hours: int, n_train: int, n_val: int, *, seed: int, smooth: str = "heave_mpm"):
    """Stores of :func:`_ridge_outputs`: the ridge as the S-N damage of every line (1, 0.5 and 2
    times it) and the smooth output as ``smooth``; the hindcast drawn with ``seed``, the cases with
    ``seed + 1``. Returns the thrust curve, the hindcast, the cases and the simulations."""
    curve = _thrust_curve()
    hc = _hindcast(n_hours, seed=seed)
    cases = _cases(hc, n_train, n_val, seed=seed + 1)
    sims = _sims(cases)
    y = _ridge_outputs(cases, curve)
    sims["damage_sn"] = (("case", "line"), np.outer(y[:, 0], [1.0, 0.5, 2.0]))
    sims[smooth] = ("case", y[:, 1])
    return curve, hc, cases, sims


def _ridge_training():
    """150 training and 30 validation states of :func:`_ridge_outputs`: curve, points, values, train mask, columns."""
    curve = _thrust_curve()
    cases = _cases(_hindcast(3000, seed=21), 150, 30, seed=22)
    tr = cases["role"].values == "train"
    return (
        curve,
        lifecycle._points(cases, "case"),
        _ridge_outputs(cases, curve),
        tr,
        [("damage_sn", "M1"), ("surge_mpm", None)],
    )


def test_per_output_choice_takes_the_thrust_space_for_a_thrust_ridge_only():
    curve, x, y, tr, cols = _ridge_training()
    settings = lifecycle.RBFSettings.from_config(PER_OUTPUT)
    model = lifecycle.fit_outputs(x[tr], y[tr], cols, settings, thrust=curve)
    np.testing.assert_array_equal(model.input_space, ["thrust", "paper"])
    assert model.spaces == ("paper", "thrust") and model.models[1].centres.shape == (150, 6)
    paper = lifecycle.fit_outputs(
        x[tr], y[tr], cols, lifecycle.RBFSettings.from_config({**PER_OUTPUT, "spaces": ["paper"]})
    )
    assert model.loo_rmse_units[0] < 0.5 * paper.loo_rmse_units[0]
    r = lifecycle.validation_metrics(lifecycle.predict_outputs(model, x[~tr]), y[~tr])["r"]
    r_paper = lifecycle.validation_metrics(lifecycle.predict_outputs(paper, x[~tr]), y[~tr])["r"]
    assert r[0] > 0.99 and r[0] > r_paper[0] + 0.2  # the ridge: the paper space smooths it out
    assert r[1] == r_paper[1]  # the smooth output: the same choice, the same model
    with pytest.raises(ValueError, match="thrust curve"):
        lifecycle.fit_outputs(x[tr], y[tr], cols, settings)


def test_weighted_space_divides_each_scalar_span_by_its_weight():
    x = np.array([[5.0, 10.0, 1.0, 6.0, 350.0], [25.0, 200.0, 7.0, 16.0, 20.0], [12.0, 90.0, 3.0, 9.0, 180.0]])
    w = [2.0, 1.0, 0.5, 4.0, 3.0]  # the direction weights (1.0, 3.0) are ignored
    x_w, mask, lo, span = lifecycle.space_inputs("weighted", x, None, None, weights=w)
    np.testing.assert_array_equal(x_w, x)
    np.testing.assert_array_equal(lo, [5.0, 0.0, 1.0, 6.0, 0.0])
    np.testing.assert_array_equal(span, [10.0, 180.0, 12.0, 2.5, 180.0])  # training range / weight
    _, _, lo_b, span_b = lifecycle.space_inputs("weighted", x, [0.0, 0, 0, 2, 0], [30.0, 180, 10, 20, 180], weights=w)
    np.testing.assert_array_equal(lo_b, [0.0, 0, 0, 2, 0])
    np.testing.assert_array_equal(span_b, [15.0, 180, 20, 5, 180])
    np.testing.assert_array_equal(lifecycle.space_points("weighted", x), x)
    with pytest.raises(ValueError, match="weights of lifecycle.rbf.weights"):
        lifecycle.space_inputs("weighted", x, None, None)
    with pytest.raises(ValueError, match="positive weights"):
        lifecycle.space_inputs("weighted", x, None, None, weights=[1.0, 1.0, 0.0, 1.0, 1.0])


def test_global_weighted_space_with_unit_weights_is_the_paper_fit():
    hc = _hindcast(400, seed=32)
    cases = _cases(hc, 60, 10, seed=33)
    sims = _sims(cases)
    cols = lifecycle.output_columns(sims, "case", lifecycle.DEFAULT_OUTPUTS)
    x, y = lifecycle._points(cases, "case"), lifecycle.stack_outputs(sims, "case", cols)
    lo, span = x.min(axis=0) - 1.0, np.ptp(x, axis=0) + 2.0
    base = {"grid": {"n": 6}, "outputs": list(lifecycle.DEFAULT_OUTPUTS)}
    paper = lifecycle.fit_outputs(x, y, cols, lifecycle.RBFSettings.from_config(base), lo=lo, span=span)
    unit = {**base, "space": "weighted", "weights": {"wind_speed": 1.0, "hs": 1.0, "tp": 1.0}}
    same = lifecycle.fit_outputs(x, y, cols, lifecycle.RBFSettings.from_config(unit), lo=lo, span=span)
    at = x + 0.1
    np.testing.assert_array_equal(lifecycle.predict_outputs(same, at), lifecycle.predict_outputs(paper, at))
    assert same.spaces == ("weighted",) and set(same.input_space) == {"weighted"}
    np.testing.assert_array_equal(same.centres, paper.centres)  # the error indicator's paper space
    weighted = lifecycle.RBFSettings.from_config({**base, "space": "weighted"})
    assert weighted.weights == (1.5, 1.0, 1.0, 0.7, 1.0)  # the schema's defaults, directions 1
    other = lifecycle.fit_outputs(x, y, cols, weighted, lo=lo, span=span)
    assert not np.array_equal(lifecycle.predict_outputs(other, at), lifecycle.predict_outputs(paper, at))
    with pytest.raises(ValueError, match="space = 'weighted' with method 'gp'"):
        lifecycle.RBFSettings.from_config({"method": "gp", "space": "weighted"})


def test_per_output_choice_takes_the_weighted_space_for_a_wind_ridge_only():
    """A damage sharp in the wind speed takes the space that weights it; one sharp in Hs does not."""
    hc = _hindcast(3000, seed=34)
    cases = _cases(hc, 150, 40, seed=35)
    x = lifecycle._points(cases, "case")
    w, _, hs, tp, _ = x.T
    wind_ridge = 1e-6 * np.exp(-(((w - 12.0) / 1.5) ** 2)) * (1 + 0.05 * hs) + 1e-9
    hs_ridge = 1e-6 * np.exp(-(((hs - 3.0) / 0.6) ** 2)) * (1 + 0.01 * w) + 1e-9
    y = np.column_stack([wind_ridge, hs_ridge])
    tr = cases["role"].values == "train"
    cols = [("damage_sn", "M1"), ("damage_sn", "M2")]
    cfg = {**PER_OUTPUT, "spaces": ["paper", "weighted"], "weights": {"wind_speed": 3.0, "hs": 1.0, "tp": 1.0}}
    model = lifecycle.fit_outputs(x[tr], y[tr], cols, lifecycle.RBFSettings.from_config(cfg))
    np.testing.assert_array_equal(model.input_space, ["weighted", "paper"])
    paper = lifecycle.fit_outputs(x[tr], y[tr], cols, lifecycle.RBFSettings.from_config({**cfg, "spaces": ["paper"]}))
    r = lifecycle.validation_metrics(lifecycle.predict_outputs(model, x[~tr]), y[~tr])["r"]
    r_paper = lifecycle.validation_metrics(lifecycle.predict_outputs(paper, x[~tr]), y[~tr])["r"]
    assert r[0] > r_paper[0] + 0.02 and r[1] == r_paper[1]


def test_per_output_choice_takes_the_wind_trend_for_a_wind_band_only():
    """A damage peaked in a band of wind speed takes the space with the wind-speed trend; a smooth one does not."""
    hc = _hindcast(3000, seed=36)
    cases = _cases(hc, 150, 40, seed=37)
    x = lifecycle._points(cases, "case")
    w, _, hs, tp, _ = x.T
    band = 1e-6 * np.exp(-(((w - 12.0) / 1.0) ** 2)) * (1 + 0.05 * hs) + 1e-9
    smooth = 1e-7 * (1 + hs) ** 2 * (1 + 0.01 * w)
    y = np.column_stack([band, smooth])
    tr = cases["role"].values == "train"
    cols = [("damage_sn", "M1"), ("damage_sn", "M2")]
    cfg = {**PER_OUTPUT, "spaces": ["paper", "wind_trend"], "wind_trend": {"knots": [8, 10, 11, 12, 13, 14, 16]}}
    settings = lifecycle.RBFSettings.from_config(cfg)
    assert settings.trend_knots == (8.0, 10.0, 11.0, 12.0, 13.0, 14.0, 16.0) and settings.trend_harmonics == 1
    model = lifecycle.fit_outputs(x[tr], y[tr], cols, settings)
    np.testing.assert_array_equal(model.input_space, ["wind_trend", "paper"])
    assert model.models[list(model.spaces).index("wind_trend")].trend.knots  # the fit carries its trend
    paper = lifecycle.fit_outputs(x[tr], y[tr], cols, lifecycle.RBFSettings.from_config({**cfg, "spaces": ["paper"]}))
    r = lifecycle.validation_metrics(lifecycle.predict_outputs(model, x[~tr]), y[~tr])["r"]
    r_paper = lifecycle.validation_metrics(lifecycle.predict_outputs(paper, x[~tr]), y[~tr])["r"]
    assert r[0] > r_paper[0] + 0.05 and r[1] == r_paper[1], (r, r_paper)
    glob = lifecycle.fit_outputs(x[tr], y[tr], cols, lifecycle.RBFSettings.from_config({"space": "wind_trend"}))
    assert glob.spaces == ("wind_trend",)
    np.testing.assert_array_equal(glob.centres, paper.centres)  # the error indicator's paper space
    with pytest.raises(ValueError, match=r"wind_trend.knots = \[12.0, 11.0\]; expected strictly increasing"):
        lifecycle.RBFSettings.from_config({"wind_trend": {"knots": [12, 11]}}, source="c.yaml")


def test_lifecycle_with_the_wind_trend_records_it_and_ignores_the_validation_states():
    """The whole reconstruction in the wind_trend space: recorded per output, steered by training states only."""
    hc = _hindcast(1500, seed=38)
    cases = _cases(hc, 90, 25, seed=39)
    sims = _sims(cases)
    w = cases["wind_speed"].values
    band = 1e-6 * np.exp(-(((w - 12.0) / 1.0) ** 2)) + 1e-8
    sims["damage_sn"] = (("case", "line"), np.outer(band, [1.0, 0.5, 2.0]))
    settings = lifecycle.RBFSettings.from_config(
        {"space": "wind_trend", "grid": {"n": 8}, "wind_trend": {"knots": [6, 10, 12, 14, 18]}}
    )
    a = lifecycle.reconstruct_lifecycle(hc, cases, sims, settings=settings, n_suggest=5)
    assert set(a["input_space"].values) == {"wind_trend"}
    val = cases["role"].values == "validate"
    sims["damage_sn"][val] = sims["damage_sn"].values[val] * 3.0
    b = lifecycle.reconstruct_lifecycle(hc, cases, sims, settings=settings, n_suggest=5)
    changed = [v for v in a.data_vars if not a[v].equals(b[v])]
    assert changed and all(v.startswith("validation_") for v in changed), changed
    np.testing.assert_array_equal(a["damage_sn"].values, b["damage_sn"].values)


def test_per_output_fit_does_not_depend_on_the_validation_states():
    """Perturbing the validation outputs changes the validation metrics and nothing else."""
    curve, hc, cases, sims = _ridge_stores(1500, 90, 25, seed=23)
    settings = lifecycle.RBFSettings.from_config({**PER_OUTPUT, "retransform": "smearing", "smoothing": [0.0, 0.01]})
    a = lifecycle.reconstruct_lifecycle(hc, cases, sims, settings=settings, n_suggest=5, thrust=curve)
    val = cases["role"].values == "validate"
    rng = np.random.default_rng(25)
    for v in ("damage_sn", "heave_mpm", "surge_mpm", "tension_mpm"):
        scale = rng.uniform(0.2, 5.0, (int(val.sum()),) + sims[v].shape[1:])
        sims[v][val] = sims[v].values[val] * scale
    b = lifecycle.reconstruct_lifecycle(hc, cases, sims, settings=settings, n_suggest=5, thrust=curve)
    assert set(a["input_space"].values) == {"paper", "thrust"} and a.attrs["rbf_choose"] == "per_output"
    assert np.any(a["retransform_factor"].values != 1.0)
    changed = [v for v in a.data_vars if not a[v].equals(b[v])]
    assert changed and all(v.startswith("validation_") for v in changed), changed
    assert "validation_simulated" in changed
    for v in ("shape_parameter", "smoothing", "input_space", "transform", "retransform_factor", "loo_error"):
        np.testing.assert_array_equal(a[v].values, b[v].values)
    np.testing.assert_array_equal(a["damage_sn"].values, b["damage_sn"].values)


def test_stage_reads_the_thrust_curve_for_per_output(tmp_path):
    from pathlib import Path

    from moorlife.io import open_zarr, write_zarr
    from moorlife.stages import lifecycle as st_lifecycle

    hc = _hindcast(400, seed=26)
    cases = _cases(hc, 40, 8, seed=27)
    for name, ds in (("hindcast", hc), ("cases", cases), ("sims", _sims(cases))):
        write_zarr(ds, tmp_path / f"{name}.zarr")
    paths = dict(hindcast=tmp_path / "hindcast.zarr", cases=tmp_path / "cases.zarr", simulations=tmp_path / "sims.zarr")
    cfg = {"rbf": {"choose": "per_output", "shape": "fixed", "retransform": "ratio"}, "adaptive": {"n_suggest": 0}}
    platform = Path(__file__).resolve().parents[1] / "config/platform.yaml"
    st_lifecycle.run(**paths, store=tmp_path / "lc.zarr", lifecycle=cfg, fatigue={}, platform_cfg=platform, threads=1)
    lc = open_zarr(tmp_path / "lc.zarr")
    assert lc.attrs["rbf_choose"] == "per_output" and lc.attrs["rbf_retransform"] == "ratio"
    assert set(lc["input_space"].values) <= {"paper", "thrust"}
    assert set(lc["transform"].values) <= {"linear", "log10"} and lc["loo_rmse_units"].sizes["output"] == 11
    np.testing.assert_allclose(lc["lifecycle_damage"].sel(curve="sn").values, np.array([2e-6, 5e-6, 1e-6]) * 400)
    with pytest.raises(ValueError, match="needs platform_cfg"):
        st_lifecycle.run(**paths, store=tmp_path / "lc2.zarr", lifecycle=cfg, fatigue={}, threads=1)


def test_per_output_transform_candidates_per_output_kind():
    hc = _hindcast(300, seed=28)
    cases = _cases(hc, 50, 5, seed=29)
    sims = _sims(cases)
    cols = lifecycle.output_columns(sims, "case", lifecycle.DEFAULT_OUTPUTS)
    x, y = lifecycle._points(cases, "case"), lifecycle.stack_outputs(sims, "case", cols)
    is_dmg = np.array([c[0].startswith("damage") for c in cols])
    y[:, is_dmg] *= np.exp(0.3 * x[:, 2:3])  # positive, rising with Hs
    cfg = {**PER_OUTPUT, "spaces": ["paper"], "transforms": ["linear"], "damage_transforms": ["log10"]}
    model = lifecycle.fit_outputs(x, y, cols, lifecycle.RBFSettings.from_config(cfg))
    np.testing.assert_array_equal(model.log_output, is_dmg)
    np.testing.assert_array_equal(model.input_space, ["paper"] * len(cols))
    flipped = {**cfg, "transforms": ["log10"], "damage_transforms": ["linear"]}
    model = lifecycle.fit_outputs(x, y, cols, lifecycle.RBFSettings.from_config(flipped))
    np.testing.assert_array_equal(model.log_output, ~is_dmg)  # every other output is positive here
    forced = lifecycle.fit_outputs(x, y, cols, lifecycle.RBFSettings.from_config(flipped), log_damage=True)
    np.testing.assert_array_equal(forced.log_output, np.ones(len(cols), bool))


GP = {"method": "gp", "outputs": list(lifecycle.DEFAULT_OUTPUTS), "gp": {"subsample": 40}}


@pytest.mark.parametrize(
    ("share", "mean", "indicator", "covariance", "wind"),
    [
        ("none", "constant", "sd", "gaussian", "none"),
        ("variable", "constant", "sd", "matern52", "none"),
        ("all", "linear", "loo", "matern32", "none"),
        ("variable", "constant", "sd", "matern52", "damage"),
    ],
)
def test_gp_fit_does_not_depend_on_the_validation_states(share, mean, indicator, covariance, wind):
    """method: gp: perturbing the validation outputs changes the validation metrics and nothing else
    (``wind``: ``gp.wind_term``, the damage with an additive term of the wind)."""
    curve, hc, cases, sims = _ridge_stores(1500, 90, 25, seed=30)
    gp_cfg = {"subsample": 40, "thrust": True, "indicator": indicator, "share": share, "mean": mean}
    settings = lifecycle.RBFSettings.from_config({**GP, "gp": {**gp_cfg, "covariance": covariance, "wind_term": wind}})
    a = lifecycle.reconstruct_lifecycle(hc, cases, sims, settings=settings, n_suggest=5, thrust=curve)
    if wind == "none":
        assert "gp_wind_sd" not in a and "gp_wind_term" not in a.attrs
    else:  # the damage has the wind term, seeing the wind speed and direction only; the rest has none
        assert a.attrs["gp_wind_term"] == wind and a.attrs["gp_wind_subsample"] == 0
        assert a.attrs["gp_wind_start"] == "joint"
        is_dmg = np.char.startswith(a["output"].values.astype(str), "damage")
        sd, wls = a["gp_wind_sd"].values, a["gp_wind_length_scale"]
        assert (sd[is_dmg] > 0).all() and (sd[~is_dmg] == 0).all()
        seen = ["wind_speed", "cos_wind_dir", "sin_wind_dir"]
        assert np.isfinite(wls.sel(gp_input=seen).values[is_dmg]).all()
        assert np.isinf(wls.drop_sel(gp_input=seen).values[is_dmg]).all()
        gate = a["gp_wind_gate"].values  # the sea gate's scale, fitted within wind_gate's bounds
        assert ((gate[is_dmg] >= 0.02) & (gate[is_dmg] <= 2.0)).all() and np.isinf(gate[~is_dmg]).all()
    assert a.attrs["gp_share"] == share and a.attrs["gp_mean"] == mean and a.attrs["gp_covariance"] == covariance
    dmg = [o for o in a["output"].values.astype(object) if o.startswith("damage")]
    same = [
        np.array_equal(a["gp_length_scale"].sel(output=o).values, a["gp_length_scale"].sel(output=dmg[0]).values)
        for o in dmg
    ]
    assert all(same) == (share != "none")  # one set of hyperparameters for the damage of every line
    val = cases["role"].values == "validate"
    rng = np.random.default_rng(32)
    for v in ("damage_sn", "heave_mpm", "surge_mpm", "tension_mpm"):
        scale = rng.uniform(0.2, 5.0, (int(val.sum()),) + sims[v].shape[1:])
        sims[v][val] = sims[v].values[val] * scale
    b = lifecycle.reconstruct_lifecycle(hc, cases, sims, settings=settings, n_suggest=5, thrust=curve)
    assert a.attrs["rbf_method"] == "gp" and set(a["input_space"].values) == {"thrust"}
    assert a.sizes["gp_input"] == 8 and np.all(np.isnan(a["shape_parameter"].values))
    changed = [v for v in a.data_vars if not a[v].equals(b[v])]
    assert changed and all(v.startswith("validation_") for v in changed), changed
    kept = ("gp_length_scale", "gp_noise_sd", "smoothing", "retransform_factor", "loo_error", "error_indicator")
    for v in kept + (("gp_wind_sd", "gp_wind_length_scale", "gp_wind_gate") if wind != "none" else ()):
        np.testing.assert_array_equal(a[v].values, b[v].values)
    np.testing.assert_array_equal(a["damage_sn"].values, b["damage_sn"].values)


def test_gp_sd_indicator_is_the_largest_latent_sd_over_the_scale():
    hc = _hindcast(600, seed=33)
    cases = _cases(hc, 60, 0, seed=34)
    sims = _sims(cases)
    sims["surge_mpm"] = sims["surge_mpm"] * np.exp(0.01 * np.random.default_rng(35).standard_normal(60))
    cols = lifecycle.output_columns(sims, "case", ("surge_mpm", "damage_sn"))
    x, y = lifecycle._points(cases, "case"), lifecycle.stack_outputs(sims, "case", cols)
    y[:, 1:] *= np.exp(0.2 * x[:, 2:3])
    settings = lifecycle.RBFSettings.from_config({**GP, "gp": {"indicator": "sd", "subsample": 0}})
    model = lifecycle.fit_outputs(x, y, cols, settings)
    hp = lifecycle._points(hc, "time")
    scale = np.where(model.log_output, 1.0, y.std(axis=0))
    ind, dist = lifecycle.error_indicator(model, hp, scale)
    _, var = gp.predict_latent(model.models[0], hp, variance_of=np.ones(len(cols), bool))
    np.testing.assert_allclose(ind, np.max(np.sqrt(var) / scale, axis=1), rtol=1e-12)
    assert ind[dist == 0].mean() < ind[dist > np.quantile(dist, 0.9)].mean()  # surest at the training states
    loo = lifecycle.fit_outputs(x, y, cols, lifecycle.RBFSettings.from_config({**GP, "gp": {"subsample": 0}}))
    ind_loo, _ = lifecycle.error_indicator(loo, hp, scale)
    assert np.all(ind_loo[dist == 0] == 0) and not np.allclose(ind_loo, ind)
    picks = lifecycle.suggest_states(model, hp, ind, 4, distance=dist)
    assert picks[0] == int(np.argmax(ind)) and np.unique(picks).size == 4


def test_gp_per_output_choice_takes_the_thrust_space_for_a_thrust_ridge():
    """method: gp, choose: per_output: one GP per space, each output keeps the smaller leave-one-out."""
    curve, x, y, tr, cols = _ridge_training()
    gp_cfg = {"subsample": 0, "covariance": "matern52", "indicator": "sd"}
    per = lifecycle.RBFSettings.from_config({**GP, "choose": "per_output", "gp": gp_cfg})
    model = lifecycle.fit_outputs(x[tr], y[tr], cols, per, thrust=curve)
    fits = {
        sp: lifecycle.fit_outputs(
            x[tr],
            y[tr],
            cols,
            lifecycle.RBFSettings.from_config({**GP, "gp": {**gp_cfg, "thrust": sp == "thrust"}}),
            thrust=curve,
        )
        for sp in ("paper", "thrust")
    }
    rmse = np.array([fits["paper"].loo_rmse_units, fits["thrust"].loo_rmse_units])
    assert model.input_space[0] == "thrust" and rmse[1, 0] < 0.5 * rmse[0, 0]  # the ridge: the thrust space
    np.testing.assert_array_equal(model.input_space, np.array(["paper", "thrust"])[np.argmin(rmse, axis=0)])
    np.testing.assert_array_equal(model.loo_rmse_units, rmse.min(axis=0))
    at = x[~tr]
    got = lifecycle.predict_outputs(model, at)
    for j, sp in enumerate(model.input_space):  # each output is its space's GP, bit for bit
        np.testing.assert_array_equal(got[:, j], lifecycle.predict_outputs(fits[sp], at)[:, j])
        np.testing.assert_array_equal(model.loo_error[:, j], fits[sp].loo_error[:, j])
        scale = np.where(np.arange(2) == j, 1.0, np.inf)
        own, _ = lifecycle.error_indicator(fits[sp], at, scale)
        assert np.all(lifecycle.error_indicator(model, at, [1.0, 1.0])[0] >= own)  # the sd indicator: the max
    rmse_val = lifecycle.validation_metrics(got, y[~tr])["rmse"]
    assert (
        rmse_val[0]
        < 0.5 * lifecycle.validation_metrics(lifecycle.predict_outputs(fits["paper"], at), y[~tr])["rmse"][0]
    )


def test_gp_per_output_choice_never_picks_a_nan_leave_one_out(monkeypatch):
    """A candidate whose leave-one-out RMS is NaN loses to a finite one; no finite RMS stops the fit, named."""
    curve, x, y, tr, cols = _ridge_training()
    per = lifecycle.RBFSettings.from_config({**GP, "choose": "per_output", "gp": {"subsample": 0}})
    fit_in, fitted = lifecycle.fit._gp_in, {}

    def real(name, *a, **k):  # each space fitted once: the four fits below share the data and GP settings
        key = (name, repr(a[3].gp))
        if key not in fitted:
            fitted[key] = fit_in(name, *a, **k)
        return fitted[key]

    def nan_thrust_output_0(name, *a, **k):
        model, e = real(name, *a, **k)
        return model, np.where((np.arange(e.shape[1]) == 0) & (name == "thrust"), np.nan, e)

    monkeypatch.setattr(lifecycle.fit, "_gp_in", nan_thrust_output_0)  # the thrust space wins output 0 when finite
    model = lifecycle.fit_outputs(x[tr], y[tr], cols, per, thrust=curve)
    assert model.input_space[0] == "paper" and np.isfinite(model.loo_rmse_units).all()
    stack = lifecycle.RBFSettings.from_config({**GP, "choose": "stack", "gp": {"subsample": 0}})
    model = lifecycle.fit_outputs(x[tr], y[tr], cols, stack, thrust=curve)  # no blend with a NaN part
    assert model.input_space[0] == "paper" and np.isfinite(model.loo_rmse_units).all()

    def all_nan(name, *a, **k):
        model, e = real(name, *a, **k)
        return model, np.full_like(e, np.nan)

    monkeypatch.setattr(lifecycle.fit, "_gp_in", all_nan)
    with pytest.raises(ValueError, match=r"output damage_sn/M1 has no finite leave-one-out RMS .*paper.*thrust"):
        lifecycle.fit_outputs(x[tr], y[tr], cols, per, thrust=curve)
    with pytest.raises(ValueError, match=r"'stack': output damage_sn/M1 has no finite leave-one-out RMS .*paper"):
        lifecycle.fit_outputs(x[tr], y[tr], cols, stack, thrust=curve)


def test_validation_r_interval_matches_the_sampling_law_and_widens_on_one_dominant_state():
    """The bootstrap interval of r: the normal theory's standard error (1 - rho^2) / sqrt(n) on
    bivariate normal states, wider when one state carries the correlation, NaN on a constant
    output, deterministic and independent of the other outputs."""
    rng = np.random.default_rng(11)
    n, rho = 225, 0.98
    x = rng.standard_normal((n, 4))
    y = rho * x + np.sqrt(1 - rho**2) * rng.standard_normal((n, 4))
    y[:, 3] = 1.0  # a constant output: r undefined
    low, high, se = lifecycle.validation_r_interval(x, y)
    r = lifecycle.validation_metrics(x, y)["r"]
    law = (1 - rho**2) / np.sqrt(n)
    assert np.all(np.abs(se[:3] / law - 1) < 0.25), (se, law)
    assert np.all((low[:3] < r[:3]) & (r[:3] < high[:3]))
    assert np.all(np.abs((high - low)[:3] / (2 * 1.645 * law) - 1) < 0.3)
    assert np.isnan([low[3], high[3], se[3]]).all()
    exact = lifecycle.validation_r_interval(x[:, :1], 2 * x[:, :1] + 1)  # r = 1 on every resample
    assert exact[0][0] == pytest.approx(1.0) and exact[1][0] == pytest.approx(1.0) and exact[2][0] < 1e-12
    again = lifecycle.validation_r_interval(x[:, [2, 0]], y[:, [2, 0]])
    assert again[0][1] == low[0] and again[1][0] == high[2]  # the same draws for every output
    assert np.array_equal(np.stack(lifecycle.validation_r_interval(x, y)), np.stack((low, high, se)), equal_nan=True)
    # one state ten spreads out on both sides: r rises, and rests on that state
    xp, yp = x[:, :1].copy(), (0.6 * x[:, :1] + 0.8 * rng.standard_normal((n, 1)))
    xp[0], yp[0] = 10.0, 10.0
    lo1, hi1, se1 = lifecycle.validation_r_interval(xp, yp)
    r1 = lifecycle.validation_metrics(xp, yp)["r"][0]
    law1 = (1 - r1**2) / np.sqrt(n)
    assert r1 > 0.65 and se1[0] > 2.5 * law1 and hi1[0] - lo1[0] > 2 * (2 * 1.645 * law1) and lo1[0] < r1 < hi1[0]
    with pytest.raises(ValueError, match=r"predicted \(225, 4\) and simulated \(225, 3\)"):
        lifecycle.validation_r_interval(x, y[:, :3])


def test_stack_weights_blend_two_candidates_and_never_lose_to_either():
    """Stacking: the weight of the smallest leave-one-out RMS in units, arithmetic in the
    interpolated values (geometric for log10); 1 or 0 is one candidate's choice."""
    rng = np.random.default_rng(5)
    y = np.exp(rng.standard_normal((400, 3)))
    ea, eb = rng.standard_normal((2, 400, 3)) * 0.2
    a, b = y + ea, y + eb  # independent errors of equal size: the blend halves their variance
    b[:, 1] = y[:, 1] + 5 * eb[:, 1]  # a far worse second candidate
    a[:, 2], b[:, 2] = y[:, 2] * np.exp(ea[:, 2]), y[:, 2] * np.exp(eb[:, 2])  # a log10 output
    logs = np.array([False, False, True])
    w, rmse = lifecycle.stack_weights(y, a, b, logs)
    assert 0.35 <= w[0] <= 0.65 and w[1] >= 0.9 and 0.3 <= w[2] <= 0.7
    pure = [np.sqrt(np.mean((y - p) ** 2, axis=0)) for p in (a, b)]
    assert np.all(rmse <= np.minimum(*pure) * (1 + 1e-12)) and rmse[0] < 0.8 * min(pure[0][0], pure[1][0])
    for j, blend in enumerate((w[0] * a[:, 0] + (1 - w[0]) * b[:, 0], None, a[:, 2] ** w[2] * b[:, 2] ** (1 - w[2]))):
        if blend is not None:  # the brute-force blend at the chosen weight
            assert rmse[j] == pytest.approx(np.sqrt(np.mean((y[:, j] - blend) ** 2)), rel=1e-12)
    nan_b = b.copy()
    nan_b[0, 0] = np.nan  # a candidate with a non-finite error is never blended in
    assert lifecycle.stack_weights(y, a, nan_b, logs)[0][0] == 1.0
    with pytest.raises(ValueError, match=r"values \(400, 3\), loo_a \(400, 2\)"):
        lifecycle.stack_weights(y, a[:, :2], b, logs)


def test_stack_weights_resampled_stay_mixed_where_the_leave_one_out_cannot_tell():
    """stack.resamples: the mean weight over bootstrap resamples of the training states. Two
    candidates with almost the same errors: all states pick one whole, the resamples split, so
    the weight stays mixed; a far better candidate keeps its weight; seeded and bit-stable."""
    rng = np.random.default_rng(1)
    y = np.exp(rng.standard_normal((300, 2)))
    e = rng.standard_normal((300, 2)) * 0.3
    a = y + e
    b = y + e * (1 + 0.05 * rng.choice([-1.0, 1.0], (300, 2)))  # 5 % larger or smaller, state by state
    b[:, 1] = y[:, 1] + 4 * e[:, 1]  # a far worse second candidate
    logs = np.zeros(2, dtype=bool)
    w0, r0 = lifecycle.stack_weights(y, a, b, logs)
    w, r = lifecycle.stack_weights(y, a, b, logs, resamples=200, seed=3)
    assert w0[0] in (0.0, 1.0) and 0.1 < w[0] < 0.9 and w[1] >= 0.95
    assert np.all(r >= r0) and r[0] < 1.01 * r0[0]  # all states' optimum, and barely above it
    blend = w[0] * a[:, 0] + (1 - w[0]) * b[:, 0]
    assert r[0] == pytest.approx(np.sqrt(np.mean((y[:, 0] - blend) ** 2)), rel=1e-12)
    again = lifecycle.stack_weights(y, a, b, logs, resamples=200, seed=3)
    assert np.array_equal(again[0], w) and np.array_equal(again[1], r)
    nan_b = b.copy()
    nan_b[0, 0] = np.nan  # not finite on all states: the choice on all states, never a mean
    assert lifecycle.stack_weights(y, a, nan_b, logs, resamples=50)[0][0] == 1.0
    with pytest.raises(ValueError, match="stack.resamples = 20 with choose = 'per_output'"):
        lifecycle.RBFSettings.from_config({**GP, "choose": "per_output", "stack": {"resamples": 20}})


def test_gp_stack_blends_the_paper_and_thrust_gps_from_the_training_states():
    """choose: stack: each output the blend of the two spaces' GPs at its leave-one-out weight;
    the prediction, the leave-one-out residuals, the records' term and the fit's independence
    from the validation states."""
    curve, hc, cases, sims = _ridge_stores(600, 90, 15, seed=41, smooth="surge_mpm")
    gp_cfg = {"subsample": 0, "covariance": "matern52", "restarts": 0}
    settings = lifecycle.RBFSettings.from_config({**GP, "choose": "stack", "gp": gp_cfg})
    fitted = lifecycle.fit_reconstruction(cases, sims, settings=settings, thrust=curve)
    model, x, y, cols = fitted.model, fitted.points[fitted.train], fitted.values[fitted.train], fitted.cols
    parts = {
        sp: lifecycle.fit_outputs(
            x,
            y,
            cols,
            lifecycle.RBFSettings.from_config({**GP, "gp": {**gp_cfg, "thrust": sp == "thrust"}}),
            lo=fitted.lo,
            span=fitted.span,
            thrust=curve,
        )
        for sp in ("paper", "thrust")
    }
    w = np.zeros(len(cols))
    for c, wk, sp in zip(model.columns, model.weights, model.spaces):
        if sp == "paper":
            w[c] = wk
    blended = ((w > 0) & (w < 1)).any()
    assert model.choose == "stack" and blended and set(model.spaces) == {"paper", "thrust"}
    j_dmg = cols.index(("damage_sn", "M1"))
    assert w[j_dmg] < 0.5  # the thrust ridge leans on the thrust space
    best = np.minimum(parts["paper"].loo_rmse_units, parts["thrust"].loo_rmse_units)  # choose: per_output
    assert np.all(model.loo_rmse_units <= best * (1 + 1e-9))  # the blend never loses to the choice
    at = lifecycle._points(hc, "time")[:200]
    pa, pb = (lifecycle.predict_outputs(parts[sp], at) for sp in ("paper", "thrust"))
    expect = w * pa + (1 - w) * pb
    logs = model.log_output
    expect[:, logs] = pa[:, logs] ** w[logs] * pb[:, logs] ** (1 - w[logs])
    np.testing.assert_allclose(lifecycle.predict_outputs(model, at), expect, rtol=1e-10)
    np.testing.assert_allclose(
        model.loo_error, w * parts["paper"].loo_error + (1 - w) * parts["thrust"].loo_error, rtol=1e-12
    )
    # the records' term of a blend: the weighted sum of its parts' shares, at the blend's hours
    from moorlife.lifecycle.records import carried_shares

    dmg = [j for j, c in enumerate(cols) if c[0] == "damage_sn"]
    pred = lifecycle.predict_outputs(model, at)
    g = carried_shares(model, at, pred, y, x, dmg)
    ga, gb = (carried_shares(parts[sp], at, pred, y, x, dmg) for sp in ("paper", "thrust"))
    np.testing.assert_allclose(g, w[dmg] * ga + (1 - w[dmg]) * gb, rtol=1e-10)
    kw = {"settings": settings, "n_suggest": 3, "thrust": curve, "compare_transforms": False}
    a = lifecycle.reconstruct_lifecycle(hc, cases, sims, **kw)
    assert a.attrs["rbf_choose"] == "stack" and any("+" in v for v in a["input_space"].values.astype(object))
    assert np.isfinite(a["gp_length_scale"].sel(gp_input="wind_speed").values).all()
    val = cases["role"].values == "validate"
    sims["damage_sn"][val] = sims["damage_sn"].values[val] * 3.0
    sims["surge_mpm"][val] = sims["surge_mpm"].values[val] + 1.0
    b = lifecycle.reconstruct_lifecycle(hc, cases, sims, **kw)
    changed = [v for v in a.data_vars if not a[v].equals(b[v])]
    assert changed and all(v.startswith("validation_") for v in changed), changed
    with pytest.raises(ValueError, match=r"choose = 'stack' with method 'rbf'; the blend is the GP's"):
        lifecycle.RBFSettings.from_config({"choose": "stack"})
    with pytest.raises(ValueError, match=r"gp.thrust = true with choose = 'stack'"):
        lifecycle.RBFSettings.from_config({**GP, "choose": "stack", "gp": {"thrust": True}})


def test_gp_per_output_choice_with_outputs_in_both_spaces():
    """Outputs split between the spaces: the prediction, the records and the sd indicator per model."""
    curve = _thrust_curve()
    hc = _hindcast(800, seed=23)
    cases = _cases(hc, 60, 15, seed=24)
    x, y = lifecycle._points(cases, "case"), _ridge_outputs(cases, curve)
    cols = [("damage_sn", "M1"), ("surge_mpm", None)]
    settings = lifecycle.RBFSettings.from_config({**GP, "choose": "per_output", "gp": {"subsample": 0}})
    paper = lifecycle.fit_outputs(x, y, cols, lifecycle.RBFSettings.from_config({**GP, "gp": {"subsample": 0}}))
    thrust = lifecycle.fit_outputs(
        x, y, cols, lifecycle.RBFSettings.from_config({**GP, "gp": {"subsample": 0, "thrust": True}}), thrust=curve
    )
    # force a split whichever way the leave-one-out falls: damage from the thrust GP, surge from the paper GP
    mixed = lifecycle.fit.Reconstruction(
        **{
            **{f: getattr(paper, f) for f in paper.__dataclass_fields__},
            "models": (gp.select_outputs(paper.models[0], [1]), gp.select_outputs(thrust.models[0], [0])),
            "columns": (np.array([1]), np.array([0])),
            "spaces": ("paper", "thrust"),
            "thrust": curve,
            "input_space": np.array(["thrust", "paper"]),
        }
    )
    at = lifecycle._points(hc, "time")[:50]
    got = lifecycle.predict_outputs(mixed, at)
    np.testing.assert_array_equal(got[:, 0], lifecycle.predict_outputs(thrust, at)[:, 0])
    np.testing.assert_array_equal(got[:, 1], lifecycle.predict_outputs(paper, at)[:, 1])
    inputs, ls, _, noise = lifecycle.adapters._gp_records(mixed)
    k = inputs.index("thrust")
    assert np.isnan(ls[1, k]) and ls[0, k] > 0 and not np.isnan(np.delete(ls, k, axis=1)).any()
    assert lifecycle.adapters._gp_wind_records(mixed) is None  # lifecycle.rbf.gp.wind_term: none
    np.testing.assert_array_equal(
        noise, [np.sqrt(thrust.models[0].noise_var[0]), np.sqrt(paper.models[0].noise_var[1])]
    )
    with pytest.raises(ValueError, match="out of the model's 2 outputs"):
        gp.select_outputs(paper.models[0], [2])
    ds = lifecycle.reconstruct_lifecycle(hc, cases, _sims(cases), settings=settings, n_suggest=3, thrust=curve)
    assert ds.attrs["rbf_choose"] == "per_output" and "rbf_thrust_statistic" not in ds.attrs
    assert set(ds["input_space"].values.astype(object)) <= {"paper", "thrust"}


def test_turbulent_thrust_rises_below_rated_dips_at_rated_and_has_no_cut_out_spike():
    curve = _thrust_curve()
    wind = {"spectrum": "npd", "height": 90.0}
    tt = lifecycle.turbulent_thrust(curve, wind, 3600.0)
    at = lambda w: float(lifecycle.thrust_at(tt, w))  # noqa: E731
    assert at(6.0) < at(8.0) < at(10.0)  # below rated: the slope of T(W) and sigma_u both grow
    assert at(11.0) < 0.8 * at(10.0) and at(11.0) < 0.8 * at(12.0)  # the dip at rated: the slope changes sign
    assert at(12.0) > at(14.0) > at(17.0)  # above rated: pitch control flattens T(W)
    assert abs(at(25.05) - at(24.95)) < 2e3  # N: no shutdown spike at cut-out (the ramp would give 1.7e5)
    assert max(at(w) for w in np.arange(3.0, 35.0, 0.05)) < 1e5
    x = np.array([[11.4, 0.0, 1.0, 8.0, 0.0], [9.0, 90.0, 2.0, 9.0, 180.0]])
    x6, _, lo6, span6 = lifecycle.space_inputs("thrust", x, [0.0] * 5, [30.0, 180.0, 10.0, 20.0, 180.0], tt)
    np.testing.assert_array_equal(x6[:, 5], lifecycle.thrust_at(tt, x[:, 0]))
    assert lo6[5] >= 0 and span6[5] == pytest.approx(max(at(w) for w in np.arange(0.0, 30.0, 0.01)) - lo6[5], rel=1e-9)


def test_turbulence_kernels_against_closed_forms():
    from moorlife.lifecycle import turbulence

    u = np.array([8.0, 12.0])
    kaimal = {"spectrum": "kaimal", "turbulence_intensity": 0.12, "length_scale": 340.2}
    np.testing.assert_allclose(turbulence.wind_sd(u, kaimal, 0.0, 10.0), 0.12 * u, rtol=5e-3)  # the whole variance
    assert np.all(turbulence.wind_sd(u, kaimal, 1.0 / 600.0, 10.0) < 0.12 * u)  # an hour's mean keeps the slow part
    sd = turbulence.thrust_sd(lambda v: 3.0 * v + 1.0, [5.0, 6.0], [0.5, 1.0])
    np.testing.assert_allclose(sd, [1.5, 3.0], rtol=2e-3)  # linear T: slope x sigma_u (quadrature over +-4 sd)
    capped = turbulence.thrust_sd(lambda v: v**2, [20.0, 30.0], [1.0, 2.0], cap=25.0)
    np.testing.assert_allclose(capped[1], turbulence.thrust_sd(lambda v: v**2, [25.0], [2.0])[0])
    with pytest.raises(ValueError, match="0 <= f_min < f_max"):
        turbulence.wind_sd(u, kaimal, 1.0, 0.5)
    with pytest.raises(ValueError, match="2 speeds and 1 sigma_u"):
        turbulence.thrust_sd(np.abs, [1.0, 2.0], [1.0])


def test_thrust_for_builds_the_turbulent_thrust_from_the_wind_section():
    from pathlib import Path

    from moorlife.stages import thrust_for

    platform = Path(__file__).resolve().parents[1] / "config/platform.yaml"
    cfg = {**GP, "gp": {"thrust": True}, "thrust": {"statistic": "turbulent_sd"}}
    settings = lifecycle.RBFSettings.from_config(cfg)
    assert settings.thrust_statistic == "turbulent_sd" and settings.thrust_averaging_time == 3600.0
    with pytest.raises(ValueError, match="thrust.statistic = 'turbulent_sd': the stage needs simulation.wind"):
        thrust_for(settings, platform)
    tt = thrust_for(settings, platform, {"spectrum": "npd"})
    ref = lifecycle.turbulent_thrust(_thrust_curve(), {"spectrum": "npd", "height": 90.0}, 3600.0)
    np.testing.assert_array_equal(tt.sd, ref.sd)
    steady = thrust_for(lifecycle.RBFSettings.from_config({**GP, "gp": {"thrust": True}}), platform)
    assert isinstance(steady, lifecycle.ThrustCurve)
    with pytest.raises(ConfigError, match="statistic"):
        lifecycle.RBFSettings.from_config({"thrust": {"statistic": "mean"}})


def test_turbulent_thrust_settings_are_checked_before_any_job(tiny_config):
    from moorlife.config import check_cross_keys

    cfg = tiny_config
    cfg["lifecycle"]["rbf"]["thrust"] = {"statistic": "turbulent_sd", "averaging_time": 3600.0}
    check_cross_keys(cfg, "tiny.yaml")
    cfg["simulation"]["wind"]["spectrum"] = "none"
    with pytest.raises(ConfigError, match="tiny.yaml: .*'turbulent_sd' needs a turbulent wind.*'none'"):
        check_cross_keys(cfg, "tiny.yaml")
    cfg["simulation"]["wind"]["spectrum"] = "npd"
    cfg["lifecycle"]["rbf"]["thrust"]["averaging_time"] = 0.5
    with pytest.raises(ConfigError, match=r"'lifecycle.rbf.thrust.averaging_time' = 0.5 s .*f_max' = 1.0 Hz"):
        check_cross_keys(cfg, "tiny.yaml")
