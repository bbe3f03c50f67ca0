"""The truth target (every hour of a window simulated) and its comparison with the life-cycle method.

Pure arithmetic on constructed data with known answers first; then the workflow on the tiny
configuration: one session-scoped run builds the MS1 chain and a truth window of 32 hours around
a training state, and the other tests read or copy it.
"""

from __future__ import annotations

import re
import shutil
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import xarray as xr
from test_workflow import OVERLAYS, SNAKEMAKE, clone_study, copy_repo, kill_during_fanout, smk

from moorlife import io as mio
from moorlife import lifecycle, names, selection
from moorlife import truth as T

# --------------------------------------------------------------------------- window and subset

HC0, HC1 = "1985-01-01T00:00", "1985-12-31T23:00"


def test_window_indices_inclusive_and_strided():
    t = np.datetime64("1985-01-01T00:00") + np.arange(48) * np.timedelta64(1, "h")
    idx = T.window_indices(t, np.datetime64("1985-01-01T05:00"), np.datetime64("1985-01-01T14:00"))
    assert idx.tolist() == list(range(5, 15))
    idx3 = T.window_indices(t, np.datetime64("1985-01-01T05:00"), np.datetime64("1985-01-01T14:00"), 3)
    assert idx3.tolist() == [5, 8, 11, 14]
    with pytest.raises(ValueError, match="no hour of the hindcast"):
        T.window_indices(t, np.datetime64("1985-01-01T05:30"), np.datetime64("1985-01-01T05:40"))


def test_check_window_counts_hours():
    assert T.check_window("1985-03-01T00:00", "1985-03-01T23:00", 1, 2, hindcast_start=HC0, hindcast_end=HC1) == 24
    assert T.check_window("1985-03-01T00:00", "1985-03-01T23:00", 5, 2, hindcast_start=HC0, hindcast_end=HC1) == 5
    assert T.check_window(HC0, HC1, 1, 200, hindcast_start=HC0, hindcast_end=HC1) == 8760
    kw = dict(hindcast_start=HC0, hindcast_end=HC1, source="bad.yaml")
    assert T.check_window(HC0, HC1, 1, 200, second_seed_storm=100, **kw) == 8760
    with pytest.raises(ValueError, match=r"bad\.yaml: config key 'truth\.second_seed_storm' = 200 is invalid"):
        T.check_window(HC0, HC1, 1, 200, second_seed_storm=200, **kw)
    # the default stratum with a small second seed: the message says what to change
    with pytest.raises(
        ValueError, match=r"= 100 is invalid: .*truth\.n_second_seed - 1 = 49 \(the default, 100, needs"
    ):
        T.check_window(HC0, HC1, 1, 50, second_seed_storm=100, **kw)


@pytest.mark.parametrize(
    ("start", "end", "stride", "n2", "pattern"),
    [
        (
            "1984-12-31T00:00",
            "1985-01-02T00:00",
            1,
            2,
            r"'truth\.window\.start' = '1984-12-31T00:00' is outside the hindcast",
        ),
        (
            "1985-12-31T00:00",
            "1986-01-02T00:00",
            1,
            2,
            r"'truth\.window\.end' = '1986-01-02T00:00' is outside the hindcast",
        ),
        ("1986-02-01T00:00", "1986-03-01T00:00", 1, 2, r"'truth\.window\.start' = '1986-02-01T00:00' is outside"),
        ("1985-03-02T00:00", "1985-03-01T00:00", 1, 2, r"'truth\.window\.end' = '1985-03-01T00:00' is before .* empty"),
        ("1985-03-01T00:10", "1985-03-01T00:50", 1, 2, r"no hour of the hindcast lies in the truth window"),
        ("1985-03-01T00:00", "1985-03-02T00:00", 0, 2, r"'truth\.stride' = 0 is invalid"),
        ("1985-03-01T00:00", "1985-03-01T09:00", 1, 11, r"'truth\.n_second_seed' = 11 is larger than the 10 hours"),
        ("1985-03-01T00:00", "1985-03-01T09:00", 5, 3, r"'truth\.n_second_seed' = 3 is larger than the 2 hours"),
        (
            "1985-13-01T00:00",
            "1985-03-01T09:00",
            1,
            2,
            r"'truth\.window\.start' = '1985-13-01T00:00' is not an ISO 8601",
        ),
    ],
)
def test_check_window_names_key_and_value(start, end, stride, n2, pattern):
    with pytest.raises(ValueError, match=pattern):
        T.check_window(start, end, stride, n2, hindcast_start=HC0, hindcast_end=HC1, source="bad.yaml")


def test_second_seed_subset_even_deterministic():
    assert T.second_seed_subset(10, 4).tolist() == [0, 3, 6, 9]
    assert T.second_seed_subset(5, 5).tolist() == [0, 1, 2, 3, 4]
    assert T.second_seed_subset(7, 1).tolist() == [0]
    s = T.second_seed_subset(8760, 200)
    assert s[0] == 0 and s[-1] == 8759 and np.all(np.diff(s) >= 43) and np.all(np.diff(s) <= 45)
    assert np.array_equal(s, T.second_seed_subset(8760, 200))
    for n, k in ((11, 10), (100, 37), (3, 2)):
        s = T.second_seed_subset(n, k)
        assert s.size == k and np.all(np.diff(s) > 0) and s[-1] == n - 1
    with pytest.raises(ValueError, match="n_second_seed"):
        T.second_seed_subset(5, 6)


# --------------------------------------------------------------------------- arithmetic, known answers


def test_second_seed_subset_storm_stratum():
    hs = np.array([1.0, 5.0, 2.0, 7.0, 1.5, 7.0, 0.5, 3.0, 1.0, 2.5])
    # the two largest Hs (7.0 at 3 and 5), then 3 evenly spaced among the other 8 hours
    # (positions 0, 4, 7 of [0, 1, 2, 4, 6, 7, 8, 9])
    assert T.second_seed_subset(10, 5, hs=hs, storm=2).tolist() == [0, 3, 5, 6, 9]
    # ties at the stratum's edge go to the earlier hour; storm = 0 is the evenly spaced subset
    assert T.second_seed_subset(10, 5, hs=hs, storm=3).tolist() == [0, 1, 3, 5, 9]
    assert np.array_equal(T.second_seed_subset(10, 5, hs=hs, storm=0), T.second_seed_subset(10, 5))
    w = T.strata_weights(10, [0, 3, 5, 6, 9], hs=hs, storm=2)
    np.testing.assert_allclose(w, [8 / 3, 1.0, 1.0, 8 / 3, 8 / 3])
    assert w.sum() == pytest.approx(10.0)
    with pytest.raises(ValueError, match=r"'truth\.second_seed_storm' = 5 must be between 0 and"):
        T.second_seed_subset(10, 5, hs=hs, storm=5)
    with pytest.raises(ValueError, match="needs the Hs of the 10 truth hours"):
        T.second_seed_subset(10, 5, storm=2)
    with pytest.raises(ValueError, match=r"not the subset of truth\.n_second_seed = 5, truth\.second_seed_storm = 2"):
        T.strata_weights(10, T.second_seed_subset(10, 5), hs=hs, storm=2)


def test_stratified_noise_floor_finds_the_ceiling_an_even_subset_misses():
    """A window of calm hours and one 40-hour storm that holds the seed noise: the weighted
    storm stratum estimates the window's ceiling of the per-hour r; the evenly spaced subset,
    with two storm hours, does not."""
    err_even, err_strat = [], []
    for seed in range(8):
        rng = np.random.default_rng(seed)
        n = 4000
        hs = rng.uniform(0.5, 3.0, n)
        hs[1000:1040] = 8.0 + rng.uniform(0.0, 1.0, 40)
        s = np.where(hs > 5, 100 + 10 * (hs - 8), 1 + hs)
        sd = np.where(hs > 5, 15.0, 0.1)
        x1, x2 = s + sd * rng.normal(size=n), s + sd * rng.normal(size=n)
        expected = np.sqrt(1 - np.mean(sd**2) / x1.var())  # 1 - E var(e) / var(x)
        ev = T.second_seed_subset(n, 200)
        even = T.noise_floor(x1[ev, None], x2[ev, None], n_window=n, window=x1[:, None])
        st = T.second_seed_subset(n, 200, hs=hs, storm=40)
        w = T.strata_weights(n, st, hs=hs, storm=40)
        strat = T.noise_floor(x1[st, None], x2[st, None], n_window=n, window=x1[:, None], weights=w)
        err_even.append(abs(even["r_ceiling"][0] - expected))
        err_strat.append(abs(strat["r_ceiling"][0] - expected))
        assert strat["r"][0] == pytest.approx(strat["r_ceiling"][0] ** 2)
        # the one-hour CV c behind the sum's scatter: 100 c |x| / sum x
        assert strat["sum_std_pct"][0] == pytest.approx(100 * strat["hour_cv"][0] * np.linalg.norm(x1) / x1.sum())
    assert max(err_strat) < 0.004
    assert np.mean(err_even) > 2 * np.mean(err_strat)
    with pytest.raises(ValueError, match="needs the window"):
        T.noise_floor(x1[st, None], x2[st, None], weights=w)


def test_hourly_agreement_known_answers():
    t = np.array([[1.0, 1.0], [2.0, 0.0], [3.0, 1.0], [4.0, 0.0]])
    shifted = T.hourly_agreement(t, t + 0.5)
    np.testing.assert_allclose(shifted["r"], [1.0, 1.0])
    np.testing.assert_allclose(shifted["bias"], [0.5, 0.5])
    np.testing.assert_allclose(shifted["rmse"], [0.5, 0.5])
    np.testing.assert_allclose(shifted["sum_error"], [0.5 * 4 / 10, 0.5 * 4 / 2])
    flipped = T.hourly_agreement(t, -t)
    np.testing.assert_allclose(flipped["r"], [-1.0, -1.0])
    # rec = truth + e with e = [1, -1, 1, -1]: RMSE 1, bias 0; r from the covariance
    e = np.array([1.0, -1.0, 1.0, -1.0])
    out = T.hourly_agreement(t[:, :1], t[:, :1] + e[:, None])
    assert out["rmse"][0] == pytest.approx(1.0) and out["bias"][0] == pytest.approx(0.0)
    x, y = t[:, 0], t[:, 0] + e
    assert out["r"][0] == pytest.approx(np.corrcoef(x, y)[0, 1])


def test_signed_error_pct():
    np.testing.assert_allclose(T.signed_error_pct([1.1, 0.9, 2.0], [1.0, 1.0, 1.0]), [10.0, -10.0, 100.0])


def test_noise_floor_known_answers():
    a = np.array([[1.0], [2.0], [3.0], [4.0]])
    same = T.noise_floor(a, a)
    assert same["r"][0] == pytest.approx(1.0) and same["sum_std_pct"][0] == 0 and same["sum_difference_pct"][0] == 0
    b = a + np.array([[1.0], [-1.0], [1.0], [-1.0]])
    nf = T.noise_floor(a, b, n_window=100)
    # per-hour seed variance (x1 - x2)^2 / 2 = 0.5; window sum sd sqrt(100 x 0.5); mean 2.5 per hour
    assert nf["sum_std_pct"][0] == pytest.approx(100 * np.sqrt(50.0) / 250.0)
    assert nf["sum_difference_pct"][0] == pytest.approx(0.0)
    assert nf["r"][0] == pytest.approx(np.corrcoef(a[:, 0], b[:, 0])[0, 1])


def test_noise_ceiling_is_the_r_of_the_expected_value_against_one_seed():
    """Hours x = s + e with heteroscedastic seed noise (log-normal, like damage): the two seeds
    correlate at r, the expected value s correlates with one seed at sqrt(r), well above r."""
    rng = np.random.default_rng(11)
    s = 10.0 ** (0.5 * rng.normal(size=20_000))
    x1, x2 = (s * np.exp(rng.normal(scale=0.35, size=s.size) - 0.35**2 / 2) for _ in range(2))
    nf = T.noise_floor(x1[:, None], x2[:, None])
    perfect = np.corrcoef(s, x1)[0, 1]
    assert nf["r"][0] < 0.86 < 0.91 < perfect, "a perfect reconstruction beats the r of two seeds"
    assert nf["r_ceiling"][0] == pytest.approx(np.sqrt(nf["r"][0]))
    assert perfect == pytest.approx(nf["r_ceiling"][0], abs=0.01)
    assert T.noise_floor(x1[:, None], -x1[:, None])["r_ceiling"][0] == 0.0


def test_noise_floor_of_a_sum_follows_the_windows_own_values():
    """A relative seed scatter: every seed-2 value 10 % above seed 1. c^2 = sum(0.5 (0.1 x)^2) /
    sum((1.05 x)^2) = 0.005 / 1.1025; over a window whose damage sits in one hour of 100 the
    sum's scatter is c (the storm's own), not c / 10 as the subset's mean variance says."""
    a = np.array([[1.0], [2.0], [3.0], [4.0]])
    c = np.sqrt(0.005 / 1.1025)
    window = np.r_[np.full(99, 1e-6), [1.0]][:, None]
    nf = T.noise_floor(a, 1.1 * a, n_window=100, window=window)
    expect = 100 * c * np.sqrt(np.sum(window**2)) / np.sum(window)
    assert nf["sum_std_pct"][0] == pytest.approx(expect)
    assert nf["sum_std_pct"][0] == pytest.approx(100 * c, rel=1e-3)
    flat = T.noise_floor(a, 1.1 * a, n_window=100, window=np.ones((100, 1)))
    assert flat["sum_std_pct"][0] == pytest.approx(100 * c / 10)
    with pytest.raises(ValueError, match="differ in outputs"):
        T.noise_floor(a, a, window=np.ones((5, 2)))


def _random_hours(n, seed=3):
    rng = np.random.default_rng(seed)
    return {
        "hs": rng.gamma(2.0, 0.9, n),
        "wind_speed": rng.weibull(2.0, n) * 9.0,
        "tp": 4 + rng.gamma(3.0, 1.6, n),
        "wave_dir": rng.uniform(0, 360, n),
        "wind_dir": rng.uniform(0, 360, n),
    }


EDGES = dict(hs_edges=[0.0, 1.5, 3.0, 4.5], wind_edges=[0.0, 7.0, 14.0], tp_edges=[0.0, 6.0, 9.0, 12.0])


def _direct_class(v, edges):
    """The class of one value by explicit comparisons (the last class open)."""
    k = 0
    for j, e in enumerate(edges):
        if v >= e:
            k = j
    return k


def test_hour_bins_reuse_the_scatter_matrix_rule_and_window_sum_is_direct():
    h = _random_hours(3000)
    sm = selection.scatter_matrix(h["hs"], h["wind_speed"], h["tp"], h["wave_dir"], h["wind_dir"], **EDGES)
    classes = np.column_stack([sm.hs_class, sm.wind_class, sm.tp_class])
    bins = T.hour_bins(h["hs"], h["wind_speed"], h["tp"], bin_classes=classes, **EDGES)
    # the bins of every hour reproduce the scatter matrix's hours and means
    np.testing.assert_array_equal(np.bincount(bins, minlength=sm.hours.size), sm.hours)
    np.testing.assert_allclose(np.bincount(bins, weights=h["hs"]) / sm.hours, sm.hs)
    # the same classes as explicit comparisons
    for i in range(0, 3000, 97):
        c = (
            _direct_class(h["hs"][i], EDGES["hs_edges"]),
            _direct_class(h["wind_speed"][i], EDGES["wind_edges"]),
            _direct_class(h["tp"][i], EDGES["tp_edges"]),
        )
        assert tuple(classes[bins[i]]) == c
    # a window of the hours: the bin damage equals the direct sum over its hours
    rng = np.random.default_rng(1)
    d = rng.lognormal(-12, 1.5, (sm.hours.size, 3))
    w = slice(700, 1444)
    direct = np.zeros(3)
    for i in range(w.start, w.stop):
        direct += d[bins[i]]
    np.testing.assert_allclose(T.window_bin_damage(bins[w], d), direct, rtol=1e-13)
    np.testing.assert_allclose(T.bin_damage_per_hour(bins[w], d).sum(axis=0), direct, rtol=1e-13)
    # over the whole hindcast it is the conventional sum_b p_b d_b N
    from moorlife.lifecycle import discrete_damage

    np.testing.assert_allclose(T.window_bin_damage(bins, d), discrete_damage(sm.probability, d, 3000), rtol=1e-12)


def test_hour_bins_refuses_an_hour_of_no_bin():
    classes = np.array([[0, 0, 0]])
    with pytest.raises(ValueError, match="falls in a class with no bin"):
        T.hour_bins([2.0], [1.0], [1.0], bin_classes=classes, **EDGES)


def _constructed(n=40, k_bins=None):
    """truth, reconstruction, bins with known answers: rec = 1.1 x truth on damage, truth + 0.2 on surge."""
    h = _random_hours(n, seed=11)
    sm = selection.scatter_matrix(h["hs"], h["wind_speed"], h["tp"], h["wave_dir"], h["wind_dir"], **EDGES)
    rng = np.random.default_rng(5)
    idx = np.arange(100, 100 + n, dtype=np.int64)
    dmg = rng.lognormal(-10, 1.0, (n, 3))
    surge = rng.normal(10, 2, n)
    met = {v: ("case", h[v]) for v in names.METOCEAN_VARS}
    truth = xr.Dataset(
        {**met, "hindcast_index": ("case", idx), "surge_mpm": ("case", surge), "damage_sn": (("case", "line"), dmg)},
        coords={"case": idx, "line": list(names.LINES)},
    )
    n_time = 300
    rec_d = np.zeros((n_time, 3))
    rec_d[idx] = 1.1 * dmg
    rec_s = np.zeros(n_time)
    rec_s[idx] = surge + 0.2
    rmet = {v: ("time", np.zeros(n_time)) for v in names.METOCEAN_VARS}
    for v in names.METOCEAN_VARS:
        rmet[v][1][idx] = h[v]
    rec = xr.Dataset(
        {**rmet, "surge_mpm": ("time", rec_s), "damage_sn": (("time", "line"), rec_d)},
        coords={"time": np.arange(n_time), "line": list(names.LINES)},
    )
    classes = {
        f"{ax}_class": ("bin", c) for ax, c in (("hs", sm.hs_class), ("wind", sm.wind_class), ("tp", sm.tp_class))
    }
    states = xr.Dataset(classes, coords={"bin": np.arange(sm.hours.size)}, attrs={k: list(v) for k, v in EDGES.items()})
    bd = rng.lognormal(-10, 1.0, (sm.hours.size, 3))
    sims = xr.Dataset(
        {"damage_sn": (("bin", "line"), bd)}, coords={"bin": np.arange(sm.hours.size), "line": list(names.LINES)}
    )
    # the window's hours per bin are the scatter matrix's hours of the window itself
    expected_bins = np.tensordot(sm.hours.astype(float), bd, axes=(0, 0))
    return truth, rec, states, sims, dmg, expected_bins


def test_compare_window_known_answers():
    truth, rec, states, sims, dmg, expected_bins = _constructed()
    seed2 = truth.isel(case=[0, 13, 26, 39]).copy(deep=True)
    seed2["damage_sn"] = seed2["damage_sn"] * 1.0  # identical seeds: noise r = 1, no scatter
    cmp = T.compare_window(truth, rec, states, sims, outputs=["surge_mpm", "damage_sn"], seed2=seed2)
    assert list(cmp["output"].values) == ["surge_mpm", "damage_sn/M1", "damage_sn/M2", "damage_sn/M3"]
    np.testing.assert_allclose(cmp["bias"].sel(output="surge_mpm"), 0.2)
    np.testing.assert_allclose(cmp["rmse"].sel(output="surge_mpm"), 0.2)
    np.testing.assert_allclose(cmp["r"].values, 1.0)
    np.testing.assert_allclose(cmp["truth_damage"].sel(curve="sn").values, dmg.sum(axis=0))
    np.testing.assert_allclose(cmp["reconstruction_error_pct"].values, 10.0)
    np.testing.assert_allclose(cmp["bins_damage"].sel(curve="sn").values, expected_bins, rtol=1e-12)
    np.testing.assert_allclose(
        cmp["bins_error_pct"].sel(curve="sn").values,
        100 * (expected_bins - dmg.sum(axis=0)) / dmg.sum(axis=0),
        rtol=1e-12,
    )
    np.testing.assert_allclose(cmp["truth_cumulative"].isel(hour=-1).values, cmp["truth_damage"].values)
    np.testing.assert_allclose(cmp["bins_cumulative"].isel(hour=-1).values, cmp["bins_damage"].values)
    np.testing.assert_allclose(cmp["noise_r"].values, 1.0)
    np.testing.assert_allclose(cmp["ceiling_r"].values, 1.0)
    np.testing.assert_allclose(cmp["seed_sum_std_pct"].values, 0.0)
    # no validation term in this reconstruction and no seed scatter: a band of zero width,
    # which no finite coverage factor stretches over a 10 % error
    np.testing.assert_allclose(cmp["band_sigma_pct"].values, 0.0)
    assert np.isinf(cmp["coverage_needed"].values).all()
    from moorlife.stages.truth import comparison_table

    table = comparison_table(cmp)
    assert set(table["kind"]) == {"output", "damage"} and len(table) == 4 + 3
    assert {"band_sigma_pct", "coverage_needed"} <= set(table.columns)
    # a reconstruction from another hindcast is refused
    bad = rec.copy(deep=True)
    bad["hs"][:] = 99.0
    with pytest.raises(ValueError, match="disagree on hs"):
        T.compare_window(truth, bad, states, sims, outputs=["surge_mpm"])
    # a second seed with a storm stratum: weighted, named in the attributes; another subset is refused
    pick = T.second_seed_subset(40, 6, hs=truth["hs"].values, storm=2)
    st = T.compare_window(
        truth, rec, states, sims, outputs=["damage_sn"], seed2=truth.isel(case=pick), second_seed_storm=2
    )
    assert st.attrs["second_seed_storm"] == 2 and "2 storm hours" in st["noise_r"].attrs["long_name"]
    np.testing.assert_allclose(st["ceiling_r"].values, 1.0)
    with pytest.raises(ValueError, match=r"truth\.second_seed_storm = 2: rebuild it"):
        T.compare_window(truth, rec, states, sims, outputs=["damage_sn"], seed2=seed2, second_seed_storm=2)


# --------------------------------------------------------------------------- the workflow, tiny config


TARGET = "results/MS1/truth_comparison.zarr"
N_HOURS = 32


@pytest.fixture(scope="session")
def truth_study(study, tmp_path_factory) -> Path:
    """A copy of the tiny study (conftest.py), then a truth window of 32 hours around a training state."""
    work = clone_study(study, tmp_path_factory.mktemp("truth"))
    cases = mio.open_zarr(work / "results/selection/cases.zarr")
    hc = mio.open_zarr(work / "results/metocean/hindcast.zarr", load=False)
    n_time = hc.sizes["time"]
    train = [
        int(c)
        for c, r, h in zip(cases.case.values, cases.role.values, cases.hindcast_index.values)
        if str(r) == "train" and 20 <= int(h) < n_time - 20
    ]
    k = train[0]
    h = int(cases["hindcast_index"].sel(case=k))
    times = pd.DatetimeIndex(hc["time"].values)
    start, end = times[h - 12], times[h - 12 + N_HOURS - 1]
    (work / "truth.yaml").write_text(
        f'truth:\n  window: {{start: "{start:%Y-%m-%dT%H:%M}", end: "{end:%Y-%m-%dT%H:%M}"}}\n  n_second_seed: 8\n'
        "  second_seed_storm: 3\n"
    )
    (work / "train_case.txt").write_text(f"{k} {h}\n")
    smk(work, TARGET, overlays=[*OVERLAYS, "truth.yaml"])
    return work


def _ov(*extra):
    return [*OVERLAYS, "truth.yaml", *extra]


@pytest.mark.workflow
def test_truth_window_end_to_end(truth_study):
    w = truth_study
    tr = mio.open_zarr(w / "results/MS1/truth.zarr")
    assert tr.sizes["case"] == N_HOURS and tr.attrs["random_stream"] == "truth"
    np.testing.assert_array_equal(tr["case"].values, tr["hindcast_index"].values)
    assert np.all(np.diff(tr["hindcast_index"].values) == 1)
    s2 = mio.open_zarr(w / "results/MS1/truth_seed2.zarr")
    assert s2.sizes["case"] == 8 and s2.attrs["random_stream"] == "truth_seed2"
    # the default design: the 3 hours of largest Hs, and 5 evenly spaced over the others
    pick = T.second_seed_subset(N_HOURS, 8, hs=tr["hs"].values, storm=3)
    np.testing.assert_array_equal(s2["hindcast_index"].values, tr["hindcast_index"].values[pick])
    assert set(np.argsort(-tr["hs"].values, kind="stable")[:3]) <= set(pick.tolist())
    # same hours, other stream: the outputs differ
    assert not np.array_equal(s2["damage_sn"].values, tr["damage_sn"].sel(case=s2["case"].values).values)
    cmp = mio.open_zarr(w / TARGET)
    assert cmp.attrs["n_hours"] == N_HOURS and cmp.attrs["n_seed2"] == 8
    labels = list(cmp["output"].values)
    for v in (
        "surge_mpm",
        "sway_mpm",
        "heave_mpm",
        "accel_mpm",
        "accel_p90",
        "accel_p95",
        "accel_p99",
        "tension_mpm/M1",
        "damage_sn/M2",
        "damage_tn/M3",
        "tension_mean/M1",
        "surge_mean",
        "sway_mean",
    ):
        assert v in labels
    assert np.all(np.isfinite(cmp["r"].values)) and np.all(np.isfinite(cmp["noise_r"].values))
    assert np.all(cmp["truth_damage"].values > 0) and np.all(cmp["bins_damage"].values > 0)
    table = pd.read_csv(w / "results/MS1/truth_comparison.csv")
    assert len(table) == len(labels) + 6
    for fig in ("truth_scatter_MS1.png", "truth_damage_MS1.png"):
        assert (w / "results/figures" / fig).stat().st_size > 10_000
    # the reconstruction compared is lifecycle.zarr at the truth hours
    lc = mio.open_zarr(w / "results/MS1/lifecycle.zarr", load=False)
    np.testing.assert_array_equal(
        cmp["reconstruction"].sel(output="surge_mpm").values,
        lc["surge_mpm"].isel(time=tr["hindcast_index"].values).values,
    )
    np.testing.assert_array_equal(cmp["truth"].sel(output="damage_sn/M2").values, tr["damage_sn"].sel(line="M2").values)
    # the window's band holds the fit's validation term beside the two measured seed scatters:
    # the truth's hours and the reconstruction's training records (refitted, checked against lc)
    rec = cmp["records_sum_std_pct"].values
    assert np.all(np.isfinite(rec)) and np.all(rec > 0)
    for cv in ("sn", "tn"):
        val = 100 * lifecycle.validation_sum_term(lc, cv)
        assert val > 0
        seed, recs = (cmp[k].sel(curve=cv).values for k in ("seed_sum_std_pct", "records_sum_std_pct"))
        np.testing.assert_allclose(cmp["band_sigma_pct"].sel(curve=cv).values, np.sqrt(seed**2 + recs**2 + val**2))
        np.testing.assert_allclose(
            cmp["bias_z"].sel(curve=cv).values,
            cmp["reconstruction_error_pct"].sel(curve=cv).values / np.hypot(seed, recs),
        )
    # nothing left to do; the default target does not contain the truth
    dry = smk(w, TARGET, "-n", overlays=_ov())
    assert "Nothing to be done" in dry.stdout + dry.stderr
    dry_all = smk(w, "-n", overlays=_ov())
    assert "truth_" not in dry_all.stdout, "the truth target must stay outside rule all"


@pytest.mark.workflow
def test_truth_even_second_seed_end_to_end(truth_study, tmp_path):
    """truth.second_seed_storm: 0 is the evenly spaced design: its subset, an unweighted
    comparison that says so, and the hours it shares with the storm stratum keep their bits."""
    work = tmp_path / "s"
    shutil.copytree(truth_study, work, symlinks=True)
    (work / "even.yaml").write_text("truth:\n  second_seed_storm: 0\n")
    smk(work, TARGET, overlays=_ov("even.yaml"))
    tr = mio.open_zarr(work / "results/MS1/truth.zarr")
    s2 = mio.open_zarr(work / "results/MS1/truth_seed2.zarr")
    np.testing.assert_array_equal(
        s2["hindcast_index"].values, tr["hindcast_index"].values[T.second_seed_subset(N_HOURS, 8)]
    )
    cmp = mio.open_zarr(work / TARGET)
    strat = mio.open_zarr(truth_study / TARGET)
    assert cmp.attrs["second_seed_storm"] == 0 and "storm" not in cmp["noise_r"].attrs["long_name"]
    assert strat.attrs["second_seed_storm"] == 3 and "3 storm hours" in strat["noise_r"].attrs["long_name"]
    assert np.all(np.isfinite(cmp["ceiling_r"].values)) and np.all(np.isfinite(cmp["seed_sum_std_pct"].values))
    assert not np.array_equal(cmp["ceiling_r"].values, strat["ceiling_r"].values)
    # the reconstruction's own figures do not depend on the second seed
    np.testing.assert_array_equal(cmp["r"].values, strat["r"].values)
    storm = mio.open_zarr(truth_study / "results/MS1/truth_seed2.zarr")
    both = np.intersect1d(s2["hindcast_index"].values, storm["hindcast_index"].values)
    assert both.size > 0
    np.testing.assert_array_equal(s2["damage_sn"].sel(case=both).values, storm["damage_sn"].sel(case=both).values)


@pytest.mark.workflow
def test_truth_figures_in_the_report(truth_study, tmp_path):
    report = tmp_path / "report.html"
    smk(truth_study, "--report", str(report), TARGET, overlays=_ov())
    html = report.read_text(errors="replace")
    for fig in ("truth_scatter_MS1.png", "truth_damage_MS1.png"):
        assert fig in html, f"{fig} is not in the report"


@pytest.mark.workflow
def test_window_bin_damage_is_the_direct_sum(truth_study):
    w = truth_study
    tr = mio.open_zarr(w / "results/MS1/truth.zarr")
    states = mio.open_zarr(w / "results/selection/discrete.zarr")
    sims = mio.open_zarr(w / "results/MS1/discrete.zarr")
    cmp = mio.open_zarr(w / TARGET)
    a = states.attrs
    cls = {
        (int(states.hs_class[b]), int(states.wind_class[b]), int(states.tp_class[b])): int(states.bin[b])
        for b in range(states.sizes["bin"])
    }
    for curve, var in (("sn", "damage_sn"), ("tn", "damage_tn")):
        direct = np.zeros(3)
        for i in range(tr.sizes["case"]):
            key = (
                _direct_class(float(tr.hs[i]), a["hs_edges"]),
                _direct_class(float(tr.wind_speed[i]), a["wind_edges"]),
                _direct_class(float(tr.tp[i]), a["tp_edges"]),
            )
            direct += sims[var].sel(bin=cls[key]).transpose("line").values
        np.testing.assert_allclose(cmp["bins_damage"].sel(curve=curve).values, direct, rtol=1e-12)
        np.testing.assert_allclose(cmp["truth_damage"].sel(curve=curve).values, tr[var].sum("case").values, rtol=1e-12)
    # the same bin rule over the whole hindcast gives the bins' hours
    hc = mio.open_zarr(w / "results/metocean/hindcast.zarr")
    classes = np.column_stack([states[f"{ax}_class"].values for ax in ("hs", "wind", "tp")])
    bins = T.hour_bins(
        hc.hs.values,
        hc.wind_speed.values,
        hc.tp.values,
        hs_edges=a["hs_edges"],
        wind_edges=a["wind_edges"],
        tp_edges=a["tp_edges"],
        bin_classes=classes,
    )
    np.testing.assert_array_equal(np.bincount(bins, minlength=states.sizes["bin"]), states["hours"].values)


@pytest.mark.workflow
def test_truth_hour_equal_to_training_case_differs_only_in_stream(truth_study, tmp_path):
    """The training state's hour, simulated by the simulate stage itself: with the training
    stream and case id it gives simulations.zarr bit for bit, with the truth stream and the
    hour's id truth.zarr bit for bit, and the two realisations differ."""
    from moorlife.stages import simulate

    w = truth_study
    k, h = map(int, (w / "train_case.txt").read_text().split())
    cfg = mio.read_study_config(
        w / "config/config.yaml", tuple(w / o for o in _ov()), schema=w / "workflow/schemas/config.schema.yaml"
    )
    row = mio.read_mooring_systems(w / cfg["mooring_systems"]).loc["MS1"]
    row = {c: (v.item() if hasattr(v, "item") else v) for c, v in row.items()}
    cases = mio.open_zarr(w / "results/selection/cases.zarr")
    hours = mio.open_zarr(w / "results/truth/hours.zarr")
    one = cases.sel(case=[k])[list(names.METOCEAN_VARS) + ["hindcast_index"]]
    for v in names.METOCEAN_VARS:  # the same sea state
        assert float(one[v].values[0]) == float(hours[v].sel(case=h))
    sims = mio.open_zarr(w / "results/MS1/simulations.zarr")
    tr = mio.open_zarr(w / "results/MS1/truth.zarr")
    kw = dict(
        dim="case",
        ms="MS1",
        row=row,
        seed=cfg["seed"],
        simulation=cfg["simulation"],
        mooring=cfg["mooring"],
        fatigue=cfg["fatigue"],
        statistics=cfg["statistics"],
        threads=1,
        platform=w / "results/hydro/platform.nc",
        platform_cfg=w / cfg["platform"],
    )
    out = {}
    for name, store, stream in (("case", one, None), ("truth", one.assign_coords(case=[h]), "truth")):
        path = tmp_path / f"{name}_in.zarr"
        mio.write_zarr(store, path)
        out[name] = simulate.run(cases=path, store=tmp_path / "results" / f"{name}.zarr", stream=stream, **kw)
    outputs = [v for v in tr.data_vars if v in sims.data_vars and v not in hours.data_vars]
    assert {"damage_sn", "tension_mpm", "surge_mpm"} <= set(outputs)
    for v in outputs:
        np.testing.assert_array_equal(out["case"][v].values[0], sims[v].sel(case=k).values, err_msg=v)
        np.testing.assert_array_equal(out["truth"][v].values[0], tr[v].sel(case=h).values, err_msg=v)
    assert not np.array_equal(out["case"]["damage_sn"].values, out["truth"]["damage_sn"].values)


@pytest.mark.workflow
def test_truth_kill_and_resume_is_bit_identical(truth_study, tmp_path):
    """The truth rule killed during its fan-out, resumed with one worker: bit for bit.

    On a sub-window of 8 of the 32 hours: every hour draws its own random stream (seed, system,
    hour), whatever the window, so the 8 hours equal those of the 32-hour store of two workers
    and batches of 2; here batches of 1, SIGKILL after 3, the rest computed by one worker.
    """
    work = tmp_path / "k"
    shutil.copytree(truth_study, work, symlinks=True)
    target = "results/MS1/truth.zarr"
    shutil.rmtree(work / target)
    full = mio.open_zarr(truth_study / target)
    hours = full["case"].values[4:12]
    times = pd.DatetimeIndex(mio.open_zarr(work / "results/metocean/hindcast.zarr", load=False)["time"].values)
    t0, t1 = times[hours[0]], times[hours[-1]]
    (work / "sub.yaml").write_text(
        f'truth:\n  window: {{start: "{t0:%Y-%m-%dT%H:%M}", end: "{t1:%Y-%m-%dT%H:%M}"}}\n'
        "simulation:\n  batch_size: 1\n"
    )
    overlays = _ov("sub.yaml")
    part = mio.partial_path(work / target)
    cmd = [SNAKEMAKE, "--cores", "2", target, "--configfile", *overlays]
    n_before = kill_during_fanout(work, cmd, part, 3)
    assert not (work / target).exists(), "the run was not killed during the fan-out"
    assert 3 <= n_before < len(hours)
    smk(work, "--unlock", overlays=overlays)
    smk(work, target, overlays=overlays, cores=1)
    m = re.search(
        r"resuming .*: (\d+) of (\d+) batches already done", (work / "logs/MS1/truth_simulate.log").read_text()
    )
    assert m and n_before <= int(m.group(1)) < len(hours) and int(m.group(2)) == len(hours)
    xr.testing.assert_identical(mio.open_zarr(work / target).drop_attrs(), full.sel(case=hours).drop_attrs())


@pytest.mark.workflow
@pytest.mark.parametrize(
    ("yaml", "pattern"),
    [
        (
            'truth:\n  window: {start: "1984-12-01T00:00", end: "1985-01-02T00:00"}\n',
            r"config key 'truth\.window\.start' = '1984-12-01T00:00' is outside the hindcast",
        ),
    ],
    # the empty window, too many second-seed hours and stride 0 take the same path (the check of
    # common.smk): tests/test_bad_inputs.py runs them through the pre-flight command, and their
    # messages are tested on truth.check_window directly above
    ids=["outside"],
)
def test_bad_truth_config_stops_before_any_work(tmp_path, yaml, pattern):
    work = copy_repo(tmp_path)
    (work / "bad.yaml").write_text(yaml)
    res = smk(work, TARGET, check=False, overlays=[*OVERLAYS, "bad.yaml"])
    assert res.returncode != 0
    assert re.search(pattern, res.stdout + res.stderr), (res.stdout + res.stderr)[-3000:]
    assert not (work / "results").exists(), "no job may start with a bad truth config"


def test_compare_window_band_and_the_coverage_it_needs():
    """The window's band: hypot(measured seed scatter of the sum, max |validation sum error|)."""
    truth, rec, states, sims, dmg, _ = _constructed()
    rec = rec.assign_coords(output=["surge_mpm", "damage_sn/M1", "damage_sn/M2", "damage_sn/M3"])
    rec["validation_sum_error"] = ("output", [0.5, 0.03, -0.08, 0.05])  # surge_mpm is not a damage
    seed2 = truth.isel(case=[0, 13, 26, 39]).copy(deep=True)
    seed2["damage_sn"] = seed2["damage_sn"] * np.array([1.1, 0.9, 1.0])
    cmp = T.compare_window(truth, rec, states, sims, outputs=["surge_mpm", "damage_sn"], seed2=seed2)
    seed = cmp["seed_sum_std_pct"].values
    assert (seed[0, :2] > 0).all() and seed[0, 2] == 0.0
    expected = np.hypot(seed, 8.0)  # the largest |validation sum error| of the curve, in %
    np.testing.assert_allclose(cmp["band_sigma_pct"].values, expected, rtol=1e-12)
    np.testing.assert_allclose(cmp["coverage_needed"].values, 10.0 / expected, rtol=1e-12)
    assert "records_sum_std_pct" not in cmp  # not measured: not in the band
    with np.errstate(divide="ignore"):
        np.testing.assert_allclose(cmp["bias_z"].values, 10.0 / seed, rtol=1e-12)  # inf: no noise on M3
    # the records' term: the window's CV of one hour times the sum's sd per unit record CV
    records = {"damage_sn/M1": 0.5, "damage_sn/M2": 0.2, "damage_sn/M3": 0.1}
    cmp = T.compare_window(truth, rec, states, sims, outputs=["surge_mpm", "damage_sn"], seed2=seed2, records=records)
    x = truth["damage_sn"].transpose("case", "line").values
    c = T.noise_floor(x[[0, 13, 26, 39]], seed2["damage_sn"].transpose("case", "line").values, window=x)["hour_cv"]
    recs = 100 * c * np.array([0.5, 0.2, 0.1])
    np.testing.assert_allclose(cmp["records_sum_std_pct"].values[0], recs, rtol=1e-12)
    both = np.hypot(seed, recs)
    np.testing.assert_allclose(cmp["band_sigma_pct"].values, np.hypot(both, 8.0), rtol=1e-12)
    with np.errstate(divide="ignore"):
        np.testing.assert_allclose(cmp["bias_z"].values, 10.0 / both, rtol=1e-12)
    with pytest.raises(ValueError, match="records' term: no value for .*damage_sn/M3"):
        T.compare_window(
            truth, rec, states, sims, outputs=["damage_sn"], seed2=seed2, records={"damage_sn/M1": 1, "damage_sn/M2": 1}
        )
