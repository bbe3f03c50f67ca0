"""Tests of moorlife.metocean: generator kernels (closed forms), the synthetic BiMEP-like climate
(bands of issue 3), determinism, the contract Dataset and build_hindcast."""

from __future__ import annotations

import dataclasses
import logging
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from scipy import stats

from moorlife import metocean as mo
from moorlife.io import open_zarr, read_yaml, write_zarr
from moorlife.names import METOCEAN_ATTRS, METOCEAN_VARS
from moorlife.stages.metocean import build_hindcast

ROOT = Path(__file__).resolve().parents[1]
SEED = 20190601
N_PAPER = 271_728  # hourly sea states 1985-2015 (paper section 2)


@pytest.fixture(scope="module")
def config(study_config_factory) -> dict:
    return study_config_factory()


@pytest.fixture(scope="module")
def full(config):
    """The default 31-year synthetic hindcast (the study's, with the study's seed)."""
    h = config["hindcast"]
    time = mo.hourly_time(h["start"], h["end"])
    params = mo.SyntheticParams.from_config(h["synthetic"])
    return time, mo.generate_synthetic(time, params, config["seed"], h["hub_height"], h["shear_exponent"])


# ------------------------------------------------------------------------------ kernels
def test_power_law_lift_closed_form():
    assert mo.power_law_lift(10.0, 10.0, 90.0, 0.14) == pytest.approx(10.0 * 9.0**0.14, rel=1e-15)
    assert mo.power_law_lift(10.0, 10.0, 90.0, 0.14) == pytest.approx(13.6017, abs=1e-4)  # 9 ** 0.14 = 1.360172
    np.testing.assert_allclose(mo.power_law_lift([5.0, 8.0], 100.0, 90.0, 0.14), np.array([5.0, 8.0]) * 0.9**0.14)
    with pytest.raises(ValueError):
        mo.power_law_lift(1.0, 0.0, 90.0, 0.14)


def test_wind_from_uv_nautical_coming_from():
    speed, direction = mo.wind_from_uv([1.0, 0.0, -1.0, 0.0, 3.0], [0.0, 1.0, 0.0, -1.0, 4.0])
    np.testing.assert_allclose(speed, [1, 1, 1, 1, 5])
    # blowing east comes from the west (270), blowing north comes from the south (180), ...
    np.testing.assert_allclose(direction, [270.0, 180.0, 90.0, 0.0, (np.degrees(np.arctan2(-3, -4))) % 360], atol=1e-12)
    assert direction[4] == pytest.approx(216.8699, abs=1e-4)


def test_wind_from_uv_roundtrip():
    rng = np.random.default_rng(5)
    speed, direction = rng.uniform(0.1, 40, 1000), rng.uniform(0, 360, 1000)
    u, v = -speed * np.sin(np.radians(direction)), -speed * np.cos(np.radians(direction))
    s2, d2 = mo.wind_from_uv(u, v)
    np.testing.assert_allclose(s2, speed, rtol=1e-12)
    np.testing.assert_allclose(d2, direction, atol=1e-9)


def test_regime_series_frequencies_follow_seasonal_probabilities():
    p = mo.WindParams.from_config({"veer_hours": 0.0})
    t = pd.date_range("1985-01-01", "2014-12-31T23:00", freq="h").values
    season = mo.annual_cycle(t, 15.0)
    direction, spread, factor = mo.regime_series(np.random.default_rng(2), season, p)
    label = np.argmin(np.abs(direction[:, None] - np.asarray(p.regime_directions)[None, :]), axis=1)
    probs, amps = np.asarray(p.regime_probabilities), np.asarray(p.regime_seasonal_amplitudes)
    for sel, c in ((season > 0.9, 1.0), (season < -0.9, -1.0)):
        expected = probs * (1 + amps * c)
        expected /= expected.sum()
        observed = np.bincount(label[sel], minlength=3) / sel.sum()
        np.testing.assert_allclose(observed, expected, atol=0.05)
    # persistence: mean run length of a regime is about regime_hours (consecutive equal draws merge)
    changes = np.count_nonzero(np.diff(label))
    q = np.sum(probs**2)  # chance a new segment repeats the regime
    assert label.size / changes == pytest.approx(p.regime_hours / (1 - q), rel=0.1)
    np.testing.assert_array_equal(spread, np.asarray(p.regime_spreads)[label])
    np.testing.assert_array_equal(factor, np.asarray(p.regime_speed_factors)[label])


def test_smooth_noise_variance_and_lag1():
    rng = np.random.default_rng(1)
    tau = 20.0
    z = mo.smooth_noise(rng, 400_000, tau)
    a = np.exp(-1.0 / tau)
    assert z.std() == pytest.approx(1.0, abs=0.05)
    assert abs(z.mean()) < 0.05
    assert np.corrcoef(z[:-1], z[1:])[0, 1] == pytest.approx(2 * a / (1 + a * a), abs=2e-4)


def test_relax_step_response():
    x = np.r_[0.0, np.ones(20)]
    y = mo.relax(x, 4.0)
    k = np.arange(21)
    np.testing.assert_allclose(y, np.where(k == 0, 0.0, 1.0 - 0.75**k), atol=1e-12)
    np.testing.assert_array_equal(mo.relax(x, 1.0), x)


def test_weibull_from_gaussian_matches_scipy():
    z = np.linspace(-5, 6, 101)
    expected = stats.weibull_min.ppf(stats.norm.cdf(z[:80]), 2.1, scale=6.6)
    np.testing.assert_allclose(mo.weibull_from_gaussian(z[:80], 6.6, 2.1), expected, rtol=1e-9)
    # upper tail stays finite and exact where 1 - Phi(z) underflows in double precision
    tail = mo.weibull_from_gaussian(z[-1], 6.6, 2.1)
    assert tail == pytest.approx(6.6 * (-stats.norm.logsf(6.0)) ** (1 / 2.1), rel=1e-12)


def test_fetch_limited_sea_closed_forms():
    g = 9.80665
    # short fetch: JONSWAP growth
    u, x = 10.0, 20_000.0
    hs, tp = mo.fetch_limited_sea(u, x)
    xs = g * x / u**2
    assert hs == pytest.approx(0.0016 * np.sqrt(xs) * u**2 / g, rel=1e-12)
    assert tp == pytest.approx(0.2857 * np.cbrt(xs) * u / g, rel=1e-12)
    # infinite fetch: Pierson-Moskowitz fully developed sea (Hs about 0.0248 U^2, Tp about 0.83 U)
    hs, tp = mo.fetch_limited_sea(20.0, 1e9)
    assert hs == pytest.approx(0.2433 * 400 / g, rel=1e-12)
    assert tp == pytest.approx(8.134 * 20 / g, rel=1e-12)


def test_steepness_limited_tp():
    tp = mo.steepness_limited_tp([1.0, 6.0], [2.0, 14.0], 1.0 / 15.0)
    assert tp[0] == pytest.approx(np.sqrt(1.0 / (9.80665 / (2 * np.pi) / 15.0)), rel=1e-12)
    assert tp[1] == 14.0


def test_annual_cycle_peak_day():
    t = pd.date_range("2001-01-01", "2001-12-31T23:00", freq="h").values
    c = mo.annual_cycle(t, 15.0)
    assert c.max() == pytest.approx(1.0, abs=1e-6)
    assert pd.Timestamp(t[np.argmax(c)]).dayofyear == 15
    assert c.min() == pytest.approx(-1.0, abs=1e-3)


def test_hourly_time_paper_period_and_errors():
    t = mo.hourly_time("1985-01-01T00:00", "2015-12-31T23:00")
    assert t.size == N_PAPER and t.dtype == np.dtype("datetime64[ns]")
    assert np.all(np.diff(t) == np.timedelta64(1, "h"))
    with pytest.raises(mo.HindcastError, match="before"):
        mo.hourly_time("2000-01-02", "2000-01-01")
    with pytest.raises(mo.HindcastError, match="whole hour"):
        mo.hourly_time("2000-01-01T00:30", "2000-01-02")


# -------------------------------------------------------------------------- configuration
def test_config_equals_dataclass_defaults(config):
    h = config["hindcast"]
    assert mo.SyntheticParams.from_config(h["synthetic"]) == mo.SyntheticParams.from_config({})
    assert mo.CleaningPolicy.from_config(h["cleaning"]) == mo.CleaningPolicy.from_config({})


def test_schema_defaults_equal_config():
    raw = read_yaml(ROOT / "config/config.yaml")["hindcast"]
    schema = read_yaml(ROOT / "workflow/schemas/config.schema.yaml")["properties"]["hindcast"]

    def walk(cfg, sch, key):
        for k, v in cfg.items():
            sub = sch["properties"][k]
            if isinstance(v, dict) and "properties" in sub:
                walk(v, sub, f"{key}.{k}")
            else:
                assert sub["default"] == v, f"{key}.{k}"

    walk(raw, schema, "hindcast")


def test_from_config_rejects_unknown_keys():
    with pytest.raises(ValueError, match="tp_bse"):
        mo.SyntheticParams.from_config({"swell": {"tp_bse": 1.0}})
    with pytest.raises(ValueError, match="stroms"):
        mo.SyntheticParams.from_config({"stroms": {}})


# ---------------------------------------------------------------------- synthetic climate
def test_generation_is_seeded_and_bit_identical():
    t = mo.hourly_time("1990-01-01", "1992-12-31T23:00")
    p = mo.SyntheticParams.from_config({})
    a = mo.generate_synthetic(t, p, 7, 90.0, 0.14)
    b = mo.generate_synthetic(t, p, 7, 90.0, 0.14)
    c = mo.generate_synthetic(t, p, 8, 90.0, 0.14)
    for v in METOCEAN_VARS:
        assert np.array_equal(a[v], b[v]), v
        assert not np.allclose(a[v], c[v]), v


def test_hub_height_lift_exact():
    t = mo.hourly_time("1990-01-01", "1990-03-31T23:00")
    p = mo.SyntheticParams.from_config({})
    at_ref = mo.generate_synthetic(t, p, 3, p.reference_height, 0.14)
    at_hub = mo.generate_synthetic(t, p, 3, 90.0, 0.14)
    np.testing.assert_allclose(at_hub["wind_speed"], at_ref["wind_speed"] * (90.0 / 10.0) ** 0.14, rtol=1e-13)
    np.testing.assert_array_equal(at_hub["hs"], at_ref["hs"])


def test_paper_length_and_physical_ranges(full):
    time, o = full
    assert time.size == N_PAPER
    for v in METOCEAN_VARS:
        assert o[v].shape == (N_PAPER,) and np.isfinite(o[v]).all(), v
    assert o["hs"].min() > 0
    assert o["tp"].min() >= 3.0 and o["tp"].max() <= 22.0
    for v in ("wave_dir", "wind_dir"):
        assert o[v].min() >= 0.0 and o[v].max() < 360.0


def test_hs_marginal_and_extremes(full):
    _, o = full
    hs = o["hs"]
    decades = hs.size / (24 * 365.25 * 10)
    assert 1.5 <= hs.mean() <= 2.0
    # issue 3: a maximum of about 10-11 m over 31 years, a few hours per decade above 8 m
    # (a storm that peaks at 10 m spends 8-20 h above 8 m, so "a few storms" is the bound)
    assert 10.0 <= hs.max() <= 11.5
    assert 1.0 <= np.sum(hs > 8.0) / decades <= 15.0
    above = np.diff(np.r_[0, (hs > 8.0).astype(int), 0])
    assert 1 <= np.sum(above == 1) <= 5  # distinct storms above 8 m in 31 years
    assert np.sum(hs > 6.0) / hs.size < 0.005


def test_hs_persistence_and_storm_shape(full):
    _, o = full
    hs = o["hs"]
    assert np.corrcoef(hs[:-1], hs[1:])[0, 1] > 0.98
    assert np.quantile(np.abs(np.diff(hs)), 0.999) < 0.5  # m per hour
    i = int(np.argmax(hs))
    # the largest storm builds up and decays over a day or more
    assert hs[i - 24] < 0.8 * hs[i] and hs[i + 48] < 0.8 * hs[i]
    assert hs[i - 6] > 0.6 * hs[i] and hs[i + 6] > 0.6 * hs[i]


def test_hs_seasonal_cycle(full):
    time, o = full
    month = pd.DatetimeIndex(time).month
    winter = o["hs"][np.isin(month, [12, 1, 2])].mean()
    summer = o["hs"][np.isin(month, [6, 7, 8])].mean()
    assert winter > 1.5 * summer


def test_tp_steepness_swell_and_growth(full, config):
    _, o = full
    hs, tp = o["hs"], o["tp"]
    s_max = config["hindcast"]["synthetic"]["max_steepness"]
    steep = hs / (9.80665 / (2 * np.pi) * tp**2)
    assert steep.max() <= s_max * (1 + 1e-9)
    assert tp[hs < 1.0].mean() > 8.5  # long swell periods in calm states
    assert tp[hs > 5.0].mean() > tp[(hs > 1.0) & (hs < 2.0)].mean() + 1.0
    assert np.mean(tp < 6.0) > 0.005  # some short-period wind seas exist


def test_wave_direction_mainly_north_west(full):
    _, o = full
    h, edges = np.histogram(o["wave_dir"], bins=36, range=(0, 360))
    mode = edges[np.argmax(h)] + 5.0
    assert 295.0 <= mode <= 335.0
    share_nw = np.mean((o["wave_dir"] >= 270.0) & (o["wave_dir"] < 360.0))
    assert 0.7 < share_nw < 0.99  # dominant, with spread


def test_wind_three_prevailing_directions(full):
    _, o = full
    h, _ = np.histogram(o["wind_dir"], bins=12, range=(0, 360))
    peaks = [k for k in range(12) if h[k] > h[k - 1] and h[k] > h[(k + 1) % 12]]
    centres = sorted(15.0 + 30.0 * k for k in peaks)
    assert len(centres) == 3, h
    east, south, west = centres
    assert 45 <= east <= 135 and 150 <= south <= 225 and 240 <= west <= 315


def test_wind_speed_weibull_mean_max(full):
    _, o = full
    w = o["wind_speed"]
    assert 8.0 <= w.mean() <= 9.0
    assert 33.0 <= w.max() <= 42.0
    shape, _, _ = stats.weibull_min.fit(w[::10], floc=0.0)
    assert 1.6 <= shape <= 2.6


def test_storms_bring_wind_and_waves_from_west(full):
    _, o = full
    hs, w = o["hs"], o["wind_speed"]
    top = hs >= np.quantile(hs, 0.999)
    assert 250.0 <= np.median(o["wind_dir"][top]) <= 330.0
    assert np.median(w[top]) > 20.0
    assert np.corrcoef(hs, w)[0, 1] > 0.35
    assert np.median(o["wave_dir"][top]) == pytest.approx(300.0, abs=30.0)


@pytest.mark.parametrize("seed", [1, 2])
def test_other_seeds_stay_in_wider_bands(seed):
    t = mo.hourly_time("1985-01-01", "2015-12-31T23:00")
    o = mo.generate_synthetic(t, mo.SyntheticParams.from_config({}), seed, 90.0, 0.14)
    assert 1.5 <= o["hs"].mean() <= 2.0
    assert 8.5 <= o["hs"].max() <= 13.0
    assert 8.0 <= o["wind_speed"].mean() <= 9.0
    assert 30.0 <= o["wind_speed"].max() <= 45.0


# ----------------------------------------------------------------------- contract Dataset
def test_build_hindcast_contract_roundtrip(config, tmp_path, caplog):
    h = dict(config["hindcast"], start="1985-01-01T00:00", end="1987-12-31T23:00")
    with caplog.at_level(logging.INFO, logger="moorlife"):
        ds = build_hindcast(h, SEED)
    assert "synthetic hindcast" in caplog.text
    assert ds.sizes == {"time": 26_280}
    assert ds["time"].dtype == np.dtype("datetime64[ns]")
    assert list(ds.data_vars) == list(METOCEAN_VARS)
    for v in METOCEAN_VARS:
        assert ds[v].dtype == np.float64
        for k, val in METOCEAN_ATTRS[v].items():
            assert ds[v].attrs[k] == val
    for k in ("source", "site", "lon", "lat", "hub_height", "Conventions", "direction_convention"):
        assert k in ds.attrs, k
    assert ds.attrs["site"] == "BiMEP" and ds.attrs["lon"] == -2.894 and ds.attrs["hub_height"] == 90.0
    assert "coming from" in ds.attrs["direction_convention"] or "come from" in ds.attrs["direction_convention"]
    write_zarr(ds, tmp_path / "hindcast.zarr")
    back = open_zarr(tmp_path / "hindcast.zarr")
    for v in METOCEAN_VARS:
        np.testing.assert_array_equal(back[v].values, ds[v].values)
    # whole study config accepted too, and the same seed gives the same numbers
    again = build_hindcast(dict(config, hindcast=h), SEED)
    np.testing.assert_array_equal(again["hs"].values, ds["hs"].values)


def test_build_hindcast_file_source_dispatch(config, tmp_path):
    t = pd.date_range("2001-01-01", periods=48, freq="h")
    df = pd.DataFrame(
        {
            "time": t.strftime("%Y-%m-%d %H:%M:%S"),
            "hs": 1.0 + 0.01 * np.arange(48),
            "tp": 9.0 + 0.01 * np.arange(48),
            "mwd": 300.0,
            "u10": -5.0 - 0.01 * np.arange(48),
            "v10": 0.0,
        }
    )  # varying Hs, Tp and wind speed: a constant coordinate is refused
    (tmp_path / "h.csv").write_text("#ERA5,LONGITUDE:-2.9,LATITUDE:43.6,\n" + df.to_csv(index=False))
    h = dict(config["hindcast"], source="file", path="h.csv", start="2001-01-01T06:00", end="2001-01-01T23:00")
    ds = build_hindcast(h, SEED, base_dir=str(tmp_path))
    assert ds.sizes["time"] == 18
    np.testing.assert_allclose(ds["wind_dir"], 90.0)  # u = -5: blowing west, from the east
    np.testing.assert_allclose(ds["wind_speed"], (5.0 + 0.01 * np.arange(6, 24)) * 9.0**0.14)
    with pytest.raises(mo.HindcastError, match="hindcast.path"):
        build_hindcast(dict(h, path=None), SEED)


def test_validate_hindcast_on_dataset_and_frame(config):
    ds = build_hindcast(dict(config["hindcast"], start="1990-01-01", end="1990-01-10T23:00"), SEED)
    clean = mo.validate_hindcast(ds, source="synthetic")
    np.testing.assert_array_equal(clean["hs"].to_numpy(), ds["hs"].values)
    bad = ds.copy(deep=True)
    bad["tp"][5] = -1.0
    with pytest.raises(
        mo.HindcastError, match=r"mem: column 'tp', row 5 \(time 1990-01-01T05:00:00\): value -1 is not > 0"
    ):
        mo.validate_hindcast(bad, source="mem")
    frame = ds.to_dataframe().reset_index().drop(columns=["wind_dir"])
    with pytest.raises(mo.HindcastError, match=r"mem: missing column\(s\) for wind_dir"):
        mo.validate_hindcast(frame, source="mem")


def test_hindcast_dataset_requires_waves():
    with pytest.raises(KeyError, match="tp"):
        mo.hindcast_dataset(
            np.array(["2000-01-01"], dtype="datetime64[ns]"),
            {"hs": [1.0], "wave_dir": [1.0]},
            source="x",
            site="s",
            lon=0.0,
            lat=0.0,
            hub_height=90.0,
        )


def test_params_are_frozen():
    with pytest.raises(dataclasses.FrozenInstanceError):
        mo.SyntheticParams.from_config({}).tp_min = 1.0  # type: ignore[misc]


# ------------------------------------------------------------------------------- figures
def test_rose_frequencies_closed_form():
    from moorlife.plots.metocean import rose_frequencies

    # 16 sectors of 22.5 deg centred on north: 11 deg -> N, 12 deg -> NNE, 355 -> N, 270 -> W
    f = rose_frequencies([11.0, 12.0, 355.0, 270.0], [1.0, 5.0, 30.0, 9.0], 16, [0.0, 4.0, 8.0])
    assert f.shape == (16, 3) and f.sum() == pytest.approx(100.0)
    assert f[0, 0] == 25.0 and f[0, 2] == 25.0 and f[1, 1] == 25.0 and f[12, 2] == 25.0


def test_figures_are_built(config):
    from matplotlib.figure import Figure

    from moorlife.plots.metocean import plot_hs_tp, plot_wave_rose, plot_wind_rose

    ds = build_hindcast(dict(config["hindcast"], start="1985-01-01", end="1985-12-31T23:00"), SEED)
    for fn in (plot_wind_rose, plot_wave_rose):
        fig = fn(ds)
        assert isinstance(fig, Figure) and fig.axes[0].name == "polar"
    fig = plot_hs_tp(ds)
    ax = fig.axes[0]
    assert ax.get_xlabel() == "Tp [s]" and ax.get_ylabel() == "Hs [m]"
    assert ax.get_ylim()[1] >= float(ds["hs"].max())
