"""The normalised sea-state space (moorlife.space), shared by the selection and the RBF."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

from moorlife import names, rbf, selection, space
from moorlife.conventions import circular_difference

ROOT = Path(__file__).resolve().parents[1]
MASK = space.direction_mask()

# (wind_speed, wind_dir, hs, tp, wave_dir): wind 0..10 m/s, hs 1..3 m, tp constant
POINTS = np.array(
    [
        [0.0, 350.0, 1.0, 8.0, 10.0],
        [10.0, 10.0, 3.0, 8.0, 190.0],
        [5.0, 270.0, 2.0, 8.0, 360.0],
    ]
)


def _old_pairwise(a: np.ndarray, b: np.ndarray, mask: np.ndarray) -> np.ndarray:
    """The numpy implementation that selection.pairwise_distance had before moorlife.space."""
    sq = np.zeros((a.shape[0], b.shape[0]))
    for k in range(a.shape[1]):
        d = np.abs(a[:, k, None] - b[None, :, k])
        if mask[k]:
            d = np.minimum(d, 2.0 - d)
        sq += d * d
    return np.sqrt(sq)


def test_direction_mask_follows_names():
    assert names.METOCEAN_VARS == ("wind_speed", "wind_dir", "hs", "tp", "wave_dir")
    np.testing.assert_array_equal(MASK, [False, True, False, False, True])
    np.testing.assert_array_equal(space.direction_mask(["hs", "wave_dir"]), [False, True])


def test_scaling_and_normalise_on_known_values():
    lo, span = space.scaling_from(POINTS, MASK)
    np.testing.assert_array_equal(lo, [0.0, 0.0, 1.0, 8.0, 0.0])
    np.testing.assert_array_equal(span, [10.0, 180.0, 2.0, 1.0, 180.0])  # constant tp: span 1
    z = space.normalise(POINTS, MASK, lo, span)
    expected = np.array(
        [
            [0.0, 350.0 / 180.0, 0.0, 0.0, 10.0 / 180.0],
            [1.0, 10.0 / 180.0, 1.0, 0.0, 190.0 / 180.0],
            [0.5, 1.5, 0.5, 0.0, 0.0],  # 360 deg is north: 0
        ]
    )
    np.testing.assert_array_equal(z, expected)
    # any turn: -90 deg is 270 deg; a tiny negative direction folds to 0, not to 2
    w = space.normalise([[0.0, -90.0, 1.0, 8.0, -1e-20]], MASK, lo, span)
    np.testing.assert_array_equal(w[0, [1, 4]], [1.5, 0.0])
    assert space.normalise(POINTS, MASK, lo, span, dtype=np.float32).dtype == np.float32
    with pytest.raises(ValueError, match="span must be finite and > 0"):
        space.normalise(POINTS, MASK, lo, [0.0, 180.0, 2.0, 1.0, 180.0])
    bad = POINTS.copy()
    bad[1, 2] = np.nan
    with pytest.raises(ValueError, match="column 2, row 1"):
        space.scaling_from(bad, MASK)


def test_distances_on_known_values():
    z = space.normalise(POINTS, MASK)
    d = space.pairwise_distance(z, z, MASK)
    # rows 0 and 1: wind 1, wind_dir 350 vs 10 -> 20 deg, hs 1, tp 0, wave_dir 10 vs 190 -> 180 deg
    expected01 = np.sqrt(1.0 + (20.0 / 180.0) ** 2 + 1.0 + 0.0 + 1.0)
    assert d[0, 1] == pytest.approx(expected01, rel=1e-14)
    np.testing.assert_array_equal(np.diag(d), 0.0)
    np.testing.assert_array_equal(d, d.T)
    np.testing.assert_array_equal(np.sqrt(space.squared_distances(z, z, MASK)), d)
    # the circle: folded difference / 180 of conventions.circular_difference
    a = np.array([[0.0], [359.0], [90.0], [180.0]])
    b = np.array([[1.0], [181.0], [270.0]])
    za, zb = space.normalise(a, [True]), space.normalise(b, [True])
    np.testing.assert_allclose(
        space.pairwise_distance(za, zb, [True]), circular_difference(a, b.T) / 180.0, rtol=0, atol=1e-15
    )
    np.testing.assert_array_equal(space.nearest_distance(z, z, MASK, exclude_same_index=True), np.sort(d, axis=1)[:, 1])


def test_compiled_distances_are_bitwise_the_former_numpy_ones():
    rng = np.random.default_rng(3)
    for t in range(6):
        a = rng.uniform(0, 1, (int(rng.integers(1, 90)), 5))
        b = rng.uniform(0, 1, (int(rng.integers(1, 90)), 5))
        a[:, MASK] *= 2.0
        b[:, MASK] *= 2.0
        if t % 2:  # exact ties, halves and folded differences of exactly 1
            a, b = np.round(a * 4) / 4, np.round(b * 4) / 4
        old = _old_pairwise(a, b, MASK)
        new = space.pairwise_distance(a, b, MASK)
        np.testing.assert_array_equal(new.view(np.int64), old.view(np.int64))
        dmin, imin = np.empty(a.shape[0]), np.empty(a.shape[0], dtype=np.int64)
        space.nearest_block(np.ascontiguousarray(a), np.ascontiguousarray(b.T), MASK, dmin, imin)
        np.testing.assert_array_equal(dmin, old.min(axis=1))
        np.testing.assert_array_equal(imin, old.argmin(axis=1))


def test_fit_space_and_embed_are_the_selection_normalisation():
    lo, span = space.scaling_from(POINTS, MASK)
    sp = space.fit_space(POINTS, MASK)
    np.testing.assert_array_equal(sp.lower, lo)
    np.testing.assert_array_equal(sp.scale, span)
    np.testing.assert_array_equal(sp.is_direction, MASK)
    z = space.embed(POINTS, sp)
    assert z.flags.c_contiguous and z.dtype == np.float64
    np.testing.assert_array_equal(z, space.normalise(POINTS, MASK, lo, span))
    # given ranges: directions keep 0 / 180 whatever is passed
    sp2 = space.fit_space(POINTS, MASK, lo=[1, 5, 0, 0, 7], span=[20, 1, 4, 2, 9])
    np.testing.assert_array_equal(sp2.lower, [1, 0, 0, 0, 0])
    np.testing.assert_array_equal(sp2.scale, [20, 180, 4, 2, 180])
    with pytest.raises(ValueError, match="points have 4 columns"):
        space.embed(POINTS[:, :4], sp)
    with pytest.raises(ValueError, match="input column 0 has span"):
        space.fit_space(POINTS, MASK, span=[0, 1, 1, 1, 1])
    np.testing.assert_array_equal(space.as_points([1.0, 2.0]), [[1.0], [2.0]])


def test_selection_and_rbf_use_the_shared_space():
    from moorlife.lifecycle import fit as lc_fit
    from moorlife.lifecycle import spaces as lc_spaces
    from moorlife.rbf import fit as rbf_fit
    from moorlife.rbf import predict as rbf_predict
    from moorlife.selection import adapters as sel_adapters
    from moorlife.selection import dissimilarity as sel_mda

    assert selection.scaling_from is space.scaling_from
    assert selection.normalise is space.normalise
    assert selection.pairwise_distance is space.pairwise_distance
    assert selection.nearest_distance is space.nearest_distance
    assert rbf.Space is space.Space
    assert rbf.fit_space is space.fit_space
    assert rbf.normalise is space.embed
    assert rbf.squared_distances is space.squared_distances
    assert sel_mda.normalise is space.normalise
    assert sel_adapters.direction_mask is space.direction_mask
    assert sel_adapters.nearest_distance is space.nearest_distance
    assert rbf_fit.fit_space is space.fit_space and rbf_fit.embed is space.embed
    assert rbf_predict.sq_dist_block is space.sq_dist_block
    assert rbf_predict.nearest_block is space.nearest_block
    assert lc_fit.fit_space is space.fit_space and lc_fit.embed is space.embed
    assert lc_spaces.direction_mask is space.direction_mask and lc_spaces.scaling_from is space.scaling_from
    # no second implementation of the embedding or the distance anywhere else in the package
    defs = re.compile(r"^def (normalise|scaling_from|fit_space|embed|pairwise_distance|squared_distances)\(", re.M)
    others = [
        p.relative_to(ROOT)
        for p in (ROOT / "src" / "moorlife").rglob("*.py")
        if p.name != "space.py" and defs.search(p.read_text())
    ]
    assert others == []


def test_rbf_and_selection_measure_the_same_distance():
    rng = np.random.default_rng(5)
    pts = np.column_stack(
        [
            rng.uniform(0, 25, 300),
            rng.uniform(0, 360, 300),
            rng.gamma(2, 1, 300),
            rng.uniform(3, 18, 300),
            rng.uniform(0, 360, 300),
        ]
    )
    lo, span = selection.scaling_from(pts, MASK)
    train = selection.mda(pts, 40, is_direction=MASK, lo=lo, span=span, dtype=np.float64)
    model = rbf.fit_rbf(pts[train], pts[train, 2], is_direction=MASK, shape=0.3, lo=lo, span=span)
    np.testing.assert_array_equal(model.centres, selection.normalise(pts[train], MASK, lo, span))
    dist, _ = rbf.nearest_centre(model, pts)
    z = selection.normalise(pts, MASK, lo, span)
    np.testing.assert_array_equal(dist, selection.nearest_distance(z, z[train], MASK))
