"""Tests of moorlife.selection: MDA (fast vs strict reference vs bluemath-tk), validation
states, the discrete scatter matrix, and the xarray adapters of the output contract."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
import xarray as xr
from hypothesis import given, settings
from hypothesis import strategies as st

from moorlife import names
from moorlife.conventions import circular_difference
from moorlife.io import open_zarr, write_zarr
from moorlife.selection import (
    VALIDATION_STREAM_KEY,
    class_labels,
    discrete_states,
    mda,
    mda_bruteforce,
    modal_direction,
    nearest_distance,
    normalise,
    pairwise_distance,
    scaling_from,
    scatter_matrix,
    select_cases,
    select_validation,
)

# columns in names.METOCEAN_VARS order: wind_speed, wind_dir, hs, tp, wave_dir
MASK = np.array([v in names.DIRECTION_VARS for v in names.METOCEAN_VARS])


def random_states(n: int, seed: int) -> np.ndarray:
    """Realistic-ish (W, beta, Hs, Tp, alpha) points, shape (n, 5)."""
    rng = np.random.default_rng(seed)
    hs = rng.gamma(2.0, 0.8, n)
    return np.column_stack(
        [
            rng.weibull(2.0, n) * 9.0,
            rng.uniform(0.0, 360.0, n),
            hs,
            6.0 + 2.5 * np.sqrt(hs) + rng.normal(0.0, 1.0, n),
            (315.0 + rng.vonmises(0.0, 3.0, n) * 57.3) % 360.0,
        ]
    )


def make_hindcast(n: int, seed: int = 0) -> xr.Dataset:
    pts = random_states(n, seed)
    time = pd.date_range("1985-01-01", periods=n, freq="h").values
    ds = xr.Dataset(
        {v: (names.TIME, pts[:, k], names.attrs_for(v)) for k, v in enumerate(names.METOCEAN_VARS)},
        coords={names.TIME: time},
    )
    ds.attrs.update(source="synthetic test", site="test")
    return ds


# --------------------------------------------------------------------------- the distance
def test_normalised_distance_matches_conventions_circular_difference():
    rng = np.random.default_rng(3)
    a = rng.uniform(-720.0, 720.0, 500)
    b = rng.uniform(0.0, 360.0, 500)
    mask = np.array([True])
    xa = normalise(a[:, None], mask)
    xb = normalise(b[:, None], mask)
    d = np.array([pairwise_distance(xa[i], xb[i], mask)[0, 0] for i in range(a.size)])
    np.testing.assert_allclose(d, circular_difference(a, b) / 180.0, rtol=0, atol=1e-12)
    # 350 and 10 degrees are 20 degrees apart, not 340
    x = normalise(np.array([[350.0], [10.0]]), mask)
    assert pairwise_distance(x[:1], x[1:], mask)[0, 0] == pytest.approx(20.0 / 180.0)


def test_scaling_and_normalise_range():
    pts = np.array([[2.0, 10.0, 5.0], [4.0, 350.0, 5.0], [3.0, 180.0, 5.0]])
    mask = np.array([False, True, False])
    lo, span = scaling_from(pts, mask)
    np.testing.assert_array_equal(lo, [2.0, 0.0, 5.0])
    np.testing.assert_array_equal(span, [2.0, 180.0, 1.0])  # constant column -> span 1
    x = normalise(pts, mask)
    np.testing.assert_allclose(x[:, 0], [0.0, 1.0, 0.5])
    np.testing.assert_allclose(x[:, 1], [10 / 180, 350 / 180, 1.0])
    np.testing.assert_array_equal(x[:, 2], 0.0)
    # 3-4-5 triangle in the normalised space
    p = np.array([[0.0, 0.0], [3.0, 4.0]])
    assert pairwise_distance(p[:1], p[1:], [False, False])[0, 0] == pytest.approx(5.0)


def test_nearest_distance_leave_one_out():
    x = normalise(random_states(300, 8), MASK)
    full = pairwise_distance(x, x, MASK)
    np.fill_diagonal(full, np.inf)
    np.testing.assert_allclose(nearest_distance(x, x, MASK, exclude_same_index=True), full.min(axis=1))


def test_nonfinite_points_are_rejected_with_row_and_column():
    pts = random_states(20, 1)
    pts[7, 3] = np.nan
    with pytest.raises(ValueError, match="column 3, row 7"):
        mda(pts, 5, is_direction=MASK)


# --------------------------------------------------------------------------- MDA
@pytest.mark.parametrize("dtype", [np.float32, np.float64])
@pytest.mark.parametrize("seed", [0, 1, 2])
def test_fast_mda_equals_bruteforce_on_random_data(dtype, seed):
    pts = random_states(500, seed)
    start = int(np.argmax(pts[:, 2]))
    fast = mda(pts, 70, is_direction=MASK, start=start, dtype=dtype)
    ref = mda_bruteforce(pts, 70, is_direction=MASK, start=start, dtype=dtype)
    np.testing.assert_array_equal(fast, ref)
    assert fast[0] == start
    assert np.unique(fast).size == fast.size


@settings(max_examples=60, deadline=None)
@given(
    data=st.lists(st.tuples(*(st.integers(0, 4) for _ in range(5))), min_size=1, max_size=40),
    frac=st.floats(0.0, 1.0),
    dtype=st.sampled_from([np.float32, np.float64]),
)
def test_fast_mda_equals_bruteforce_property(data, frac, dtype):
    """Any small data set (coarse values: ties, duplicates, constant columns), any n."""
    pts = np.array(data, dtype=float) * np.array([3.0, 90.0, 1.5, 4.0, 45.0])
    n = max(1, round(frac * len(data)))
    fast = mda(pts, n, is_direction=MASK, dtype=dtype)
    np.testing.assert_array_equal(fast, mda_bruteforce(pts, n, is_direction=MASK, dtype=dtype))
    assert np.unique(fast).size == n


def test_fast_mda_equals_bruteforce_with_planted_ties():
    # coarse grid values: a flood of exactly equal distances, plus exact duplicate rows
    rng = np.random.default_rng(5)
    pts = np.column_stack(
        [
            rng.integers(0, 3, 300) * 5.0,
            rng.integers(0, 4, 300) * 90.0,
            rng.integers(0, 3, 300) * 2.0,
            rng.integers(0, 2, 300) * 10.0,
            rng.integers(0, 8, 300) * 45.0,
        ]
    )
    n_distinct = np.unique(pts, axis=0).shape[0]
    n = min(n_distinct + 5, 300)  # also runs past the distinct points into duplicates
    for dtype in (np.float32, np.float64):
        fast = mda(pts, n, is_direction=MASK, dtype=dtype)
        np.testing.assert_array_equal(fast, mda_bruteforce(pts, n, is_direction=MASK, dtype=dtype))
    # every distinct state comes before any duplicate of an already selected one
    first = pts[fast[:n_distinct]]
    assert np.unique(first, axis=0).shape[0] == n_distinct


def test_mda_hand_built_order_and_lowest_index_tie_break():
    # 1-D, range 0..1: start at max (1.0), then 0.0, then 0.5, then the two 0.25-away
    # candidates tie: the lower row index wins whichever value it holds
    for values, expected in (
        ([0.0, 1.0, 0.5, 0.25, 0.75], [1, 0, 2, 3, 4]),
        ([0.0, 1.0, 0.5, 0.75, 0.25], [1, 0, 2, 3, 4]),
        ([0.75, 0.25, 0.0, 1.0, 0.5], [3, 2, 4, 0, 1]),
    ):
        pts = np.array(values)[:, None]
        got = mda(pts, 5, is_direction=[False])  # default start: largest normalised value
        np.testing.assert_array_equal(got, expected)
        np.testing.assert_array_equal(mda_bruteforce(pts, 5, is_direction=[False]), expected)


def test_mda_directions_are_compared_on_the_circle():
    # directions only: start at 0 deg; the farthest state is 180, not 350
    pts = np.array([[0.0], [350.0], [180.0], [90.0], [270.0]])
    got = mda(pts, 3, is_direction=[True], start=0)
    np.testing.assert_array_equal(got[:2], [0, 2])
    assert set(got[2:]) <= {3}  # 90 and 270 tie at 90 deg: lowest index (3)


def test_mda_greedy_property_against_float64_distances():
    """Independent of the kernel's arithmetic: each pick maximises the nearest distance."""
    pts = random_states(800, 11)
    picks = mda(pts, 60, is_direction=MASK, start=int(np.argmax(pts[:, 2])))
    x = normalise(pts, MASK)
    radii = []
    for j in range(1, picks.size):
        near = nearest_distance(x, x[picks[:j]], MASK)
        near[picks[:j]] = -1.0
        assert near[picks[j]] == pytest.approx(near.max(), rel=1e-6)
        radii.append(near[picks[j]])
    assert np.all(np.diff(radii) <= 1e-7)  # the coverage radius never grows


def test_mda_continuation_equals_longer_run():
    pts = random_states(400, 4)
    long = mda(pts, 50, is_direction=MASK)
    cont = mda(pts, 50, is_direction=MASK, start=long[:30])
    np.testing.assert_array_equal(cont, long)
    tail = select_validation(pts, 20, exclude=long[:30], is_direction=MASK, rule="mda")
    np.testing.assert_array_equal(tail, long[30:])


def test_mda_bad_arguments():
    pts = random_states(10, 0)
    with pytest.raises(ValueError, match="cannot select n = 11"):
        mda(pts, 11, is_direction=MASK)
    with pytest.raises(ValueError, match="outside"):
        mda(pts, 3, is_direction=MASK, start=10)
    with pytest.raises(ValueError, match="is_direction has 4 entries"):
        mda(pts, 3, is_direction=MASK[:4])


@pytest.mark.slow  # importing bluemath-tk takes a few seconds
def test_mda_agrees_with_bluemath_tk_under_one_metric():
    """Peer library: bluemath-tk's MDA on the three scalar variables, min-max normalised."""
    bm = pytest.importorskip("bluemath_tk.datamining.mda")
    pts = random_states(600, 21)[:, [0, 2, 3]]
    start = int(np.argmax(pts[:, 1]))
    df = pd.DataFrame(pts, columns=["W", "Hs", "Tp"])
    peer = bm.MDA(num_centers=30)
    peer.logger.disabled = True
    peer.fit(data=df, first_centroid_seed=start, normalize_data=True)
    ours = mda(pts, 30, is_direction=[False] * 3, start=start, dtype=np.float64)
    np.testing.assert_array_equal(np.asarray(peer.centroid_real_indices), ours)


# --------------------------------------------------------------------------- validation
def test_random_validation_is_disjoint_seeded_and_skips_duplicates():
    pts = random_states(600, 9)
    train = mda(pts, 50, is_direction=MASK)
    others = np.setdiff1d(np.arange(600), train)[-40:]
    pts[others] = pts[train[:40]]  # plant exact copies of training states
    a = select_validation(pts, 100, exclude=train, is_direction=MASK, seed=7)
    b = select_validation(pts, 100, exclude=train, is_direction=MASK, seed=7)
    c = select_validation(pts, 100, exclude=train, is_direction=MASK, seed=8)
    np.testing.assert_array_equal(a, b)
    assert not np.array_equal(a, c)
    assert np.unique(a).size == 100 and np.all(np.diff(a) > 0)
    assert not set(a) & set(train)
    train_rows = {tuple(r) for r in pts[train]}
    assert not any(tuple(r) in train_rows for r in pts[a])
    with pytest.raises(ValueError, match="only 510 states differ"):
        select_validation(pts, 600, exclude=train, is_direction=MASK)
    with pytest.raises(ValueError, match="not one of"):
        select_validation(pts, 5, exclude=train, is_direction=MASK, rule="kmeans")


# --------------------------------------------------------------------------- scatter matrix
def test_scatter_matrix_hand_built():
    # three occupied bins (Hs-major order) with known members
    rows = [
        # hs, W, tp, wave_dir, wind_dir      -> bin (hs 0, W 0, tp 1)
        (1.0, 3.0, 7.0, 312.0, 355.0),
        (0.5, 5.0, 8.0, 308.0, 4.0),
        (1.2, 6.9, 6.0, 314.0, 2.0),
        (0.3, 1.0, 8.9, 45.0, 90.0),
        # -> bin (hs 1, W 1, tp 2): 1.5 and 7.0 and 9.0 are lower-closed edges
        (1.5, 7.0, 9.0, 95.0, 180.0),
        (2.5, 10.0, 11.0, 85.0, 200.0),
        (2.0, 13.0, 10.0, 270.0, 200.0),
        # -> bin (hs 3, W 2, tp 3): open top classes
        (6.0, 20.0, 14.0, 300.0, 270.0),
        (9.0, 30.0, 16.0, 296.0, 275.0),
        (4.5, 25.0, 12.0, 304.0, 266.0),
    ]
    hs, w, tp, wdir, bdir = (np.array(c) for c in zip(*rows, strict=True))
    sm = scatter_matrix(hs, w, tp, wdir, bdir, sector=10.0)
    np.testing.assert_array_equal(sm.hs_class, [0, 1, 3])
    np.testing.assert_array_equal(sm.wind_class, [0, 1, 2])
    np.testing.assert_array_equal(sm.tp_class, [1, 2, 3])
    np.testing.assert_array_equal(sm.hours, [4, 3, 3])
    np.testing.assert_allclose(sm.probability, [0.4, 0.3, 0.3])
    assert sm.probability.sum() == pytest.approx(1.0)
    np.testing.assert_allclose(sm.hs, [0.75, 2.0, 6.5])
    np.testing.assert_allclose(sm.wind_speed, [15.9 / 4, 10.0, 25.0])
    np.testing.assert_allclose(sm.tp, [29.9 / 4, 10.0, 14.0])
    # 355, 4 and 2 deg all fall in the sector centred on north
    np.testing.assert_array_equal(sm.wind_dir, [0.0, 200.0, 270.0])
    # bin 2: 95 -> 100 sector, 85 -> 90 sector, 270 -> 270: a three-way tie, lowest centre
    np.testing.assert_array_equal(sm.wave_dir, [310.0, 90.0, 300.0])
    # a 30-degree sector regroups them
    sm30 = scatter_matrix(hs, w, tp, wdir, bdir, sector=30.0)
    np.testing.assert_array_equal(sm30.wave_dir, [300.0, 90.0, 300.0])


def test_modal_direction_and_labels():
    assert modal_direction([359.0, 1.0, 3.0, 180.0], 10.0) == 0.0
    assert modal_direction([14.9, 15.0, 16.0], 10.0) == 20.0  # [15, 25) is centred on 20
    assert modal_direction([100.0, 200.0], 10.0) == 100.0  # tie -> lowest centre
    assert class_labels([0, 1.5, 3, 4.5]) == ["0-1.5", "1.5-3", "3-4.5", ">=4.5"]
    with pytest.raises(ValueError, match="must divide 360"):
        modal_direction([1.0], 7.0)


def test_scatter_matrix_default_edges_give_at_most_48_bins_and_all_hours():
    pts = random_states(20_000, 13)
    col = dict(zip(names.METOCEAN_VARS, pts.T, strict=True))
    sm = scatter_matrix(col["hs"], col["wind_speed"], col["tp"], col["wave_dir"], col["wind_dir"])
    assert sm.hours.size <= 48 and sm.hours.sum() == 20_000
    assert np.all(sm.hours > 0)
    key = sm.hs_class * 100 + sm.wind_class * 10 + sm.tp_class
    assert np.all(np.diff(key) > 0)  # Hs-major, then W, then Tp


def test_scatter_matrix_rejects_bad_input():
    ok = np.ones(3)
    with pytest.raises(ValueError, match="tp: value -1.0 at row 2"):
        scatter_matrix(ok, ok, np.array([5.0, 5.0, -1.0]), ok, ok)
    with pytest.raises(ValueError, match="increase strictly"):
        scatter_matrix(ok, ok, ok, ok, ok, hs_edges=[0.0, 3.0, 1.5])
    with pytest.raises(ValueError, match="wave_dir: value nan at row 0"):
        scatter_matrix(ok, ok, ok, np.array([np.nan, 1.0, 1.0]), ok)


# --------------------------------------------------------------------------- adapters
def test_select_cases_contract(tmp_path):
    hc = make_hindcast(3000, seed=2)
    ds = select_cases(hc, n_train=40, n_validate=12, rule="random", seed=5)
    assert ds.sizes == {names.CASE: 52}
    np.testing.assert_array_equal(ds[names.CASE].values, np.arange(52))
    assert ds["hindcast_index"].dtype == np.int64
    assert list(ds["role"].values) == ["train"] * 40 + ["validate"] * 12
    for var in names.METOCEAN_VARS:
        assert ds[var].attrs["units"] == names.METOCEAN_ATTRS[var]["units"]
        np.testing.assert_array_equal(ds[var].values, hc[var].values[ds["hindcast_index"].values])
    np.testing.assert_array_equal(ds[names.TIME].values, hc[names.TIME].values[ds["hindcast_index"].values])
    assert ds["hindcast_index"].values[0] == int(np.argmax(hc["hs"].values))
    assert ds.attrs["validation_rule"] == "random"
    assert ds.attrs["norm_variables"] == list(names.METOCEAN_VARS)
    assert ds.attrs["norm_span"][1] == 180.0
    assert ds["hs"].attrs["norm_lo"] == pytest.approx(float(hc["hs"].min()))
    assert np.all(ds["nearest_train_distance"].values > 0)
    # the documented validation rule: seeded uniform sample from a labelled stream
    pts = np.column_stack([hc[v].values for v in names.METOCEAN_VARS])
    idx = ds["hindcast_index"].values
    stream = np.random.SeedSequence([5, VALIDATION_STREAM_KEY])
    expected = select_validation(pts, 12, exclude=idx[:40], is_direction=MASK, seed=stream)
    np.testing.assert_array_equal(idx[40:], expected)
    # the store round-trips through the atomic writer
    write_zarr(ds, tmp_path / "cases.zarr")
    back = open_zarr(tmp_path / "cases.zarr")
    np.testing.assert_array_equal(back["hindcast_index"].values, ds["hindcast_index"].values)
    assert [str(r) for r in back["role"].values] == list(ds["role"].values)


def test_select_cases_deterministic_and_chunk_independent():
    hc = make_hindcast(2000, seed=3)
    a = select_cases(hc, n_train=30, n_validate=10, rule="random", seed=1)
    b = select_cases(hc.chunk({names.TIME: 333}), n_train=30, n_validate=10, rule="random", seed=1)
    xr.testing.assert_identical(a, b)
    m = select_cases(hc, n_train=30, n_validate=10, rule="mda", seed=1)
    np.testing.assert_array_equal(m["hindcast_index"].values[:30], a["hindcast_index"].values[:30])
    full = mda(
        np.column_stack([hc[v].values for v in names.METOCEAN_VARS]),
        40,
        is_direction=MASK,
        start=int(np.argmax(hc["hs"].values)),
    )
    np.testing.assert_array_equal(m["hindcast_index"].values, full)


def test_select_cases_reports_bad_hindcast_values():
    hc = make_hindcast(100)
    hc["wave_dir"][17] = 400.0
    with pytest.raises(ValueError, match=r"my\.zarr: variable 'wave_dir' row 17 \(time 1985-01-01T17"):
        select_cases(hc, n_train=5, n_validate=2, source="my.zarr")
    with pytest.raises(ValueError, match="variable 'hs' is missing"):
        select_cases(make_hindcast(50).drop_vars("hs"), n_train=5, n_validate=2)
    with pytest.raises(ValueError, match="exceeds the 50 hours"):
        select_cases(make_hindcast(50), n_train=45, n_validate=6)


def test_discrete_states_contract(tmp_path):
    hc = make_hindcast(5000, seed=4)
    ds = discrete_states(hc, hs_edges=[0, 1.5, 3, 4.5], wind_edges=[0, 7, 14], tp_edges=[0, 6, 9, 12], sector=10)
    k = ds.sizes[names.BIN]
    assert 1 <= k <= 48
    np.testing.assert_array_equal(ds[names.BIN].values, np.arange(k))
    assert float(ds["probability"].sum()) == pytest.approx(1.0)
    assert int(ds["hours"].sum()) == 5000
    for var in names.METOCEAN_VARS:
        assert ds[var].attrs["units"] == names.METOCEAN_ATTRS[var]["units"]
    assert set(ds["hs_bin"].values) <= {"0-1.5", "1.5-3", "3-4.5", ">=4.5"}
    # each bin's mean Hs lies inside its class
    lo = np.array([0, 1.5, 3, 4.5])[ds["hs_class"].values]
    assert np.all(ds["hs"].values >= lo)
    assert np.all(np.mod(ds["wave_dir"].values, 10.0) == 0.0)
    write_zarr(ds, tmp_path / "discrete.zarr")
    back = open_zarr(tmp_path / "discrete.zarr")
    np.testing.assert_allclose(back["probability"].values, ds["probability"].values)
    assert back.attrs["hs_edges"] == [0.0, 1.5, 3.0, 4.5]


@pytest.mark.slow  # renders two full figures
def test_figures_render_from_round_tripped_stores(tmp_path):
    from moorlife.plots.selection import plot_discrete_states, plot_selection_cloud

    hc = make_hindcast(3000, seed=6)
    write_zarr(select_cases(hc, n_train=25, n_validate=8, seed=1), tmp_path / "cases.zarr")
    write_zarr(discrete_states(hc), tmp_path / "discrete.zarr")
    cases, disc = open_zarr(tmp_path / "cases.zarr"), open_zarr(tmp_path / "discrete.zarr")
    fig = plot_selection_cloud(hc, cases)
    panels = [ax for ax in fig.axes if ax.axison and ax.collections and ax.get_label() != "<colorbar>"]
    assert len(panels) == 10  # every pair of the five variables
    sizes = [len(c.get_offsets()) for c in panels[0].collections if type(c).__name__ == "PathCollection"]
    assert 25 in sizes and 8 in sizes  # training and validation points drawn
    fig.savefig(tmp_path / "cloud.png", dpi=40)
    fig = plot_discrete_states(hc, disc)
    bars = fig.axes[2].patches
    assert len(bars) == disc.sizes[names.BIN]
    np.testing.assert_allclose([b.get_height() for b in bars], 100.0 * disc["probability"].values)
    fig.savefig(tmp_path / "discrete.png", dpi=40)
    assert (tmp_path / "cloud.png").stat().st_size > 0


def _run_script(name: str, smk) -> None:
    """Run a workflow script's main(smk) as Snakemake would (the adapter layer)."""
    import importlib.util
    from pathlib import Path

    path = Path(__file__).resolve().parents[1] / "workflow" / "scripts" / f"{name}.py"
    spec = importlib.util.spec_from_file_location(f"_script_{name}", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    module.main(smk)


def test_workflow_scripts_write_contract_stores(tmp_path):
    from types import SimpleNamespace as NS

    from snakemake.iocontainers import Namedlist

    def nl(**kw):  # Snakemake's input/output/params containers (mappings by name)
        return Namedlist(fromdict=kw)

    hc = make_hindcast(1500, seed=12)
    write_zarr(hc, tmp_path / "hindcast.zarr")
    src = nl(hindcast=str(tmp_path / "hindcast.zarr"))
    params = nl(n_train=20, n_validate=5, rule="mda", seed=3)
    _run_script(
        "selection",
        NS(
            input=src,
            output=nl(store=str(tmp_path / "cases.zarr")),
            params=params,
            log=[str(tmp_path / "selection.log")],
        ),
    )
    params = nl(hs_edges=[0.0, 1.5, 3.0], wind_edges=[0.0, 7.0, 14.0], tp_edges=[0.0, 6.0, 9.0, 12.0], sector=15.0)
    _run_script(
        "discrete",
        NS(
            input=src,
            output=nl(store=str(tmp_path / "discrete.zarr")),
            params=params,
            log=[str(tmp_path / "discrete.log")],
        ),
    )
    cases, disc = open_zarr(tmp_path / "cases.zarr"), open_zarr(tmp_path / "discrete.zarr")
    assert cases.sizes[names.CASE] == 25 and cases.attrs["validation_rule"] == "mda"
    assert disc.attrs["direction_sector"] == 15.0 and float(disc["probability"].sum()) == pytest.approx(1.0)
    assert "MDA picked 20 of 1500" in (tmp_path / "selection.log").read_text()
    # a bad hindcast fails with the file named, and the log keeps the reason
    bad = hc.copy(deep=True)
    bad["tp"][3] = np.nan
    write_zarr(bad, tmp_path / "bad.zarr")
    with pytest.raises(ValueError, match=r"bad\.zarr: variable 'tp' row 3"):
        _run_script(
            "selection",
            NS(
                input=nl(hindcast=str(tmp_path / "bad.zarr")),
                output=nl(store=str(tmp_path / "x.zarr")),
                params=nl(n_train=5, n_validate=2, rule="random", seed=0),
                log=[str(tmp_path / "bad.log")],
            ),
        )
    assert "variable 'tp' row 3" in (tmp_path / "bad.log").read_text()
    assert not (tmp_path / "x.zarr").exists()
