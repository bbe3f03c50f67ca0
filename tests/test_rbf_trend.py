"""The piecewise-linear trend beside the RBF's polynomial (moorlife.rbf.trend): basis, support,
exact interpolation, Rippa's leave-one-out with the larger basis, and a ridge it must resolve."""

from __future__ import annotations

import numpy as np
import pytest

from moorlife import rbf

DIRS3 = np.array([False, True, False])


def _states(n: int, seed: int) -> np.ndarray:
    """Wind speed 0-30 m/s, wind direction 0-360 deg, Hs 0-5 m."""
    rng = np.random.default_rng(seed)
    return np.column_stack([rng.uniform(0, 30, n), rng.uniform(0, 360, n), rng.uniform(0, 5, n)])


def _ridge(x: np.ndarray) -> np.ndarray:
    """A band 2 m/s wide at 12 m/s whose height turns with the direction, on a smooth slope in Hs."""
    return np.exp(-(((x[:, 0] - 12.0) / 1.0) ** 2)) * (1 + 0.5 * np.cos(np.deg2rad(x[:, 1]))) + 0.1 * x[:, 2]


TREND = rbf.Trend(column=0, knots=tuple(np.arange(3.0, 26.0, 1.0)), direction=1, harmonics=1)


def test_trend_basis_columns_hinges_and_harmonics():
    x = np.array([[10.0, 0.0, 1.0], [14.0, 90.0, 2.0]])
    t = rbf.Trend(column=0, knots=(11.0, 13.0), direction=1, harmonics=2)
    b = rbf.trend_basis(x, t)
    assert b.shape == (2, t.n_columns) and t.n_columns == 2 * 5 + 4 + 2
    scale = 13.0 - 11.0
    # first knot: hinge, then times cos, sin, cos 2, sin 2 of the direction
    np.testing.assert_allclose(b[:, 0], [0.0, 3.0 / scale])
    np.testing.assert_allclose(b[1, 1:5], 3.0 / scale * np.array([0.0, 1.0, -1.0, 0.0]), atol=1e-15)
    np.testing.assert_allclose(b[1, 5], 1.0 / scale)  # second knot's hinge
    np.testing.assert_allclose(b[0, 10:14], 10.0 / scale * np.array([1.0, 0.0, 1.0, 0.0]))  # W times each harmonic
    np.testing.assert_allclose(b[:, 14:], [[1.0, 0.0], [-1.0, 0.0]], atol=1e-15)  # the second harmonic alone
    assert rbf.trend_basis(x, rbf.Trend(column=0, knots=(11.0,))).shape == (2, 1)


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"knots": (12.0, 11.0)}, "strictly increasing"),
        ({"knots": (11.0, float("nan"))}, "strictly increasing"),
        ({"knots": (11.0,), "harmonics": 1}, "needs a direction"),
    ],
)
def test_bad_trends_are_refused(kwargs, match):
    with pytest.raises(ValueError, match=match):
        rbf.Trend(column=0, **kwargs)


def test_knots_without_training_states_on_both_sides_are_dropped():
    x = _states(200, seed=1)
    t = rbf.supported_trend(rbf.Trend(column=0, knots=(-1.0, 0.5, 12.0, 29.9, 40.0)), x)
    w = x[:, 0]
    assert t.knots == tuple(k for k in (0.5, 12.0, 29.9) if (w < k).sum() >= 10 and (w > k).sum() >= 10)
    assert 12.0 in t.knots and -1.0 not in t.knots and 40.0 not in t.knots
    model = rbf.fit_rbf(x, _ridge(x), is_direction=DIRS3, shape=0.3, trend=rbf.Trend(column=0, knots=(12.0, 40.0)))
    assert model.trend.knots == (12.0,)  # the model records what it fitted


def test_trend_fit_interpolates_and_its_rippa_residuals_are_brute_force_leave_one_out():
    x = _states(120, seed=2)
    y = np.column_stack([_ridge(x), x[:, 2] ** 2])
    trend = rbf.Trend(column=0, knots=(8.0, 12.0, 16.0), direction=1, harmonics=1)
    q = 0.3
    model = rbf.fit_rbf(x, y, is_direction=DIRS3, shape=q, trend=trend)
    np.testing.assert_allclose(rbf.predict_rbf(model, x), y, atol=1e-8)
    lo, span = model.space.lower, model.space.scale
    for k in (0, 33, 119):
        keep = np.arange(120) != k
        sub = rbf.fit_rbf(x[keep], y[keep], is_direction=DIRS3, shape=q, lo=lo, span=span, trend=trend)
        assert sub.trend == model.trend
        e = y[k] - rbf.predict_rbf(sub, x[k : k + 1])[0]
        np.testing.assert_allclose(model.loo_error[k], e, rtol=1e-6, atol=1e-9)


def test_trend_resolves_a_band_narrower_than_the_kernel():
    x, at = _states(300, seed=3), _states(2000, seed=4)
    plain = rbf.fit_rbf(x, _ridge(x), is_direction=DIRS3)
    trended = rbf.fit_rbf(x, _ridge(x), is_direction=DIRS3, trend=TREND)
    r_plain = np.corrcoef(rbf.predict_rbf(plain, at)[:, 0], _ridge(at))[0, 1]
    r_trend = np.corrcoef(rbf.predict_rbf(trended, at)[:, 0], _ridge(at))[0, 1]
    assert r_plain < 0.85 and r_trend > 0.99, (r_plain, r_trend)
    # and the leave-one-out error, which chooses it from the training states alone, agrees
    assert np.sqrt(np.mean(trended.loo_error**2)) < 0.5 * np.sqrt(np.mean(plain.loo_error**2))
