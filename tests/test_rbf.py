"""Tests of moorlife.rbf: exact interpolation, polynomial reproduction, scipy agreement,
Rippa's closed form against brute-force leave-one-out, the circular metric and the kernel."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.interpolate import RBFInterpolator

from moorlife import rbf, selection

DIRS5 = np.array([False, True, False, False, True])  # (W, beta, Hs, Tp, alpha)


def _sea_states(n: int, seed: int = 0) -> np.ndarray:
    rng = np.random.default_rng(seed)
    return np.column_stack(
        [
            rng.uniform(0, 30, n),
            rng.uniform(0, 360, n),
            rng.uniform(0.2, 8, n),
            rng.uniform(3, 20, n),
            rng.uniform(0, 360, n),
        ]
    )


def _unit_box(n: int, d: int, seed: int) -> np.ndarray:
    return np.random.default_rng(seed).random((n, d))


def test_exact_interpolation_at_centres_5d_with_directions():
    x = _sea_states(120)
    y = np.column_stack([np.sin(x[:, 2]) + np.cos(np.deg2rad(x[:, 1])), x[:, 3] ** 2])
    for q in (0.1, 0.175, 0.4):
        model = rbf.fit_rbf(x, y, is_direction=DIRS5, shape=q)
        np.testing.assert_allclose(rbf.predict_rbf(model, x), y, rtol=0, atol=1e-9 * np.abs(y).max())


def test_log_output_interpolates_exactly_and_stays_positive():
    x = _sea_states(80, seed=3)
    dmg = 1e-7 * x[:, 2] ** 3 * np.exp(-(((x[:, 3] - 12) / 4) ** 2)) + 1e-12
    model = rbf.fit_rbf(x, dmg, is_direction=DIRS5, shape=0.2, log_output=True)
    np.testing.assert_allclose(rbf.predict_rbf(model, x)[:, 0], dmg, rtol=1e-8)
    assert np.all(rbf.predict_rbf(model, _sea_states(500, seed=4)) > 0)


@pytest.mark.parametrize("q", [0.1, 0.3, 1.0])
def test_linear_function_reproduced_exactly(q):
    x = _unit_box(60, 3, seed=1)
    coef = np.array([2.5, -1.0, 0.75])
    y = 4.0 + x @ coef
    model = rbf.fit_rbf(x, y, is_direction=[False] * 3, shape=q, lo=np.zeros(3), span=np.ones(3))
    xq = _unit_box(400, 3, seed=2) * 1.4 - 0.2  # also outside the hull
    np.testing.assert_allclose(rbf.predict_rbf(model, xq)[:, 0], 4.0 + xq @ coef, atol=1e-8)
    np.testing.assert_allclose(model.weights, 0.0, atol=1e-8)


def test_direction_trend_reproduced_exactly():
    """The directional trend cos/sin of the angle is in the polynomial space: no jump at north."""
    x = _sea_states(70, seed=5)
    y = 1.0 + 0.3 * x[:, 0] / 30 + np.cos(np.deg2rad(x[:, 4])) - 2 * np.sin(np.deg2rad(x[:, 1]))
    model = rbf.fit_rbf(x, y, is_direction=DIRS5, shape=0.15, lo=[0, 0, 0.2, 3, 0], span=[30, 180, 7.8, 17, 180])
    xq = _sea_states(300, seed=6)
    yq = 1.0 + 0.3 * xq[:, 0] / 30 + np.cos(np.deg2rad(xq[:, 4])) - 2 * np.sin(np.deg2rad(xq[:, 1]))
    np.testing.assert_allclose(rbf.predict_rbf(model, xq)[:, 0], yq, atol=1e-8)


@pytest.mark.parametrize("q", [0.15, 0.3])
def test_agrees_with_scipy_rbfinterpolator(q):
    x = _unit_box(150, 4, seed=7)
    y = np.column_stack([np.sin(3 * x[:, 0]) * x[:, 1] + x[:, 2] ** 2 - x[:, 3], np.exp(x[:, 0] - x[:, 3])])
    xq = _unit_box(2000, 4, seed=8)
    model = rbf.fit_rbf(x, y, is_direction=[False] * 4, shape=q, lo=np.zeros(4), span=np.ones(4))
    ours = rbf.predict_rbf(model, xq, chunk_rows=333)
    ref = RBFInterpolator(x, y, kernel="gaussian", epsilon=1.0 / q, degree=1)(xq)
    np.testing.assert_allclose(ours, ref, rtol=0, atol=1e-9 * np.abs(ref).max())
    # and the comparison is sensitive: another shape parameter gives other numbers
    assert not np.allclose(
        ours,
        rbf.predict_rbf(rbf.fit_rbf(x, y, is_direction=[False] * 4, shape=2 * q, lo=np.zeros(4), span=np.ones(4)), xq),
    )


def test_rippa_closed_form_equals_brute_force_leave_one_out():
    x = _sea_states(50, seed=9)
    y = np.column_stack([x[:, 2] ** 1.5 * np.cos(np.deg2rad(x[:, 4] - 300)), x[:, 0] / (1 + x[:, 3])])
    q = 0.25
    model = rbf.fit_rbf(x, y, is_direction=DIRS5, shape=q)
    lo, span = model.space.lower, model.space.scale
    for k in (0, 17, 49):
        keep = np.arange(50) != k
        sub = rbf.fit_rbf(x[keep], y[keep], is_direction=DIRS5, shape=q, lo=lo, span=span)
        e = y[k] - rbf.predict_rbf(sub, x[k : k + 1])[0]
        np.testing.assert_allclose(model.loo_error[k], e, rtol=1e-6, atol=1e-10)


def test_kernel_block_inverse_equals_the_full_inverse():
    x = _sea_states(80, seed=20)
    space = rbf.fit_space(x, DIRS5)
    z = rbf.normalise(x, space)
    d2 = rbf.squared_distances(z, z, DIRS5)
    basis = rbf.polynomial_basis(z, DIRS5)
    mat = rbf.augmented_matrix(d2, basis, 0.3)
    h, rcond = rbf.kernel_block_inverse(mat[:80, :80], basis)
    full = np.linalg.inv(mat)[:80, :80]
    np.testing.assert_allclose(h, full, rtol=1e-7, atol=1e-9 * np.abs(full).max())
    assert 0 < rcond < 1
    bad, rc = rbf.kernel_block_inverse(np.ones((80, 80)), basis)  # rank one: not positive definite
    assert bad is None and rc == 0.0


def test_rippa_picks_the_grid_minimum_and_sharing_reduces_distinct_shapes():
    x = _sea_states(150, seed=10)
    y = np.column_stack([np.sin(x[:, 2]) + x[:, 3] / 10 + 0.01 * k for k in range(4)] + [x[:, 0] ** 2 / 900])
    model_sel = rbf.fit_space(x, DIRS5)
    z = rbf.normalise(x, model_sel)
    d2 = rbf.squared_distances(z, z, DIRS5)
    basis = rbf.polynomial_basis(z, DIRS5)
    grid = rbf.shape_grid(0.05, 1.0, 12)
    curve = rbf.loo_curve(d2, basis, y, grid)
    q = rbf.choose_shapes(curve)
    np.testing.assert_array_equal(q, grid[np.argmin(curve.rms, axis=0)])
    model = rbf.fit_rbf(x, y, is_direction=DIRS5, shapes=grid)
    np.testing.assert_array_equal(model.shape, q)
    shared = rbf.choose_shapes(curve, share_tol=0.5)
    assert np.unique(shared).size <= np.unique(q).size
    best = curve.rms.min(axis=0)
    got = curve.rms[np.searchsorted(grid, shared), np.arange(y.shape[1])]
    assert np.all(got <= best * 1.5 + 1e-15)


def test_smoothed_rippa_closed_form_equals_brute_force_leave_one_out():
    """Rippa's ratio is the exact leave-one-out residual of the smoothed system too."""
    x = _sea_states(50, seed=11)
    y = np.column_stack([x[:, 2] ** 1.5 * np.cos(np.deg2rad(x[:, 4] - 300)), x[:, 0] / (1 + x[:, 3])])
    model = rbf.fit_rbf(x, y, is_direction=DIRS5, shape=0.3, smoothing=0.05)
    np.testing.assert_array_equal(model.smoothing, [0.05, 0.05])
    lo, span = model.space.lower, model.space.scale
    for k in (0, 23, 49):
        keep = np.arange(50) != k
        sub = rbf.fit_rbf(x[keep], y[keep], is_direction=DIRS5, shape=0.3, smoothing=0.05, lo=lo, span=span)
        e = y[k] - rbf.predict_rbf(sub, x[k : k + 1])[0]
        np.testing.assert_allclose(model.loo_error[k], e, rtol=1e-6, atol=1e-10)


def test_joint_smoothing_choice_is_the_loo_minimum_and_filters_noise():
    x = _sea_states(300, seed=12)
    truth = np.sin(x[:, 2] / 2) + x[:, 3] / 10 + 0.3 * np.cos(np.deg2rad(x[:, 1]))
    noisy = truth + 0.15 * np.random.default_rng(13).standard_normal(truth.size)
    y = np.column_stack([truth, noisy])
    grid = rbf.shape_grid(0.05, 1.0, 8)
    lams = [0.0, 0.01, 0.03, 0.1, 0.3]
    model = rbf.fit_rbf(x, y, is_direction=DIRS5, shapes=grid, smoothing=lams)
    assert model.smoothing[1] > 0  # the noisy output is smoothed
    # the choice is the joint leave-one-out minimum over (q0, lambda)
    z = rbf.normalise(x, model.space)
    d2 = rbf.squared_distances(z, z, DIRS5)
    basis = rbf.polynomial_basis(z, DIRS5)
    rms = np.stack([rbf.loo_curve(d2, basis, y, grid, lam).rms for lam in lams])
    for j in range(2):
        li, gi = np.unravel_index(np.argmin(rms[:, :, j]), rms.shape[:2])
        assert (model.smoothing[j], model.shape[j]) == (lams[li], grid[gi])
    # and it predicts the noise-free truth better than exact interpolation of the noise
    xt = _sea_states(400, seed=14)
    tt = np.sin(xt[:, 2] / 2) + xt[:, 3] / 10 + 0.3 * np.cos(np.deg2rad(xt[:, 1]))
    exact = rbf.fit_rbf(x, noisy, is_direction=DIRS5, shapes=grid)
    err_smooth = np.sqrt(np.mean((rbf.predict_rbf(model, xt)[:, 1] - tt) ** 2))
    err_exact = np.sqrt(np.mean((rbf.predict_rbf(exact, xt)[:, 0] - tt) ** 2))
    assert err_smooth < 0.8 * err_exact
    # a single candidate 0 is the exact interpolant, as a scalar 0
    one = rbf.fit_rbf(x, y, is_direction=DIRS5, shapes=grid, smoothing=[0.0])
    np.testing.assert_array_equal(one.weights, rbf.fit_rbf(x, y, is_direction=DIRS5, shapes=grid).weights)
    with pytest.raises(ValueError, match="non-negative"):
        rbf.fit_rbf(x, y, is_direction=DIRS5, shapes=grid, smoothing=[0.0, -0.1])


def test_distance_is_the_selection_metric():
    x = _sea_states(40, seed=11)
    space = rbf.fit_space(x, DIRS5)
    z = rbf.normalise(x, space)
    lo, span = selection.scaling_from(x, DIRS5)
    zs = selection.normalise(x, DIRS5, lo, span)
    np.testing.assert_array_equal(z, zs)
    np.testing.assert_allclose(
        np.sqrt(rbf.squared_distances(z, z, DIRS5)), selection.pairwise_distance(zs, zs, DIRS5), atol=1e-14
    )
    # 350 deg and 10 deg are 20 deg apart on the circle: 20 / 180 in normalised units
    a = rbf.normalise(np.array([[0, 350.0, 1, 5, 0]]), space)
    b = rbf.normalise(np.array([[0, 10.0, 1, 5, 0]]), space)
    np.testing.assert_allclose(rbf.squared_distances(a, b, DIRS5)[0, 0], (20 / 180) ** 2)


def test_fast_gaussian_within_one_ulp_of_numpy():
    d2 = np.random.default_rng(12).random((64, 900)) * 900
    d2[0, :6] = [0.0, 1e-300, 0.5, 708.0, 708.5, 1e6]
    g = rbf.gaussian(d2, 1.0)
    ref = np.exp(-d2)
    ref[d2 > 708.0] = 0.0
    ulps = np.abs(g - ref) / np.spacing(np.maximum(ref, np.finfo(float).tiny))
    assert ulps.max() <= 1.0
    assert g[0, 4] == 0.0 and g[0, 5] == 0.0 and g[0, 0] == 1.0


def test_prediction_independent_of_chunking():
    x = _sea_states(100, seed=13)
    y = np.column_stack([x[:, 2], x[:, 3] ** 0.5])
    model = rbf.fit_rbf(x, y, is_direction=DIRS5, shape=[0.1, 0.3])
    xq = _sea_states(1234, seed=14)
    a = rbf.predict_rbf(model, xq, chunk_rows=1234)
    b = rbf.predict_rbf(model, xq, chunk_rows=97)
    np.testing.assert_array_equal(a, b)


def test_prediction_independent_of_thread_counts():
    import numba

    x = _sea_states(300, seed=21)
    y = np.column_stack([np.sin(x[:, 2]) * x[:, 3], x[:, 0] ** 0.5, x[:, 2] ** 2])
    model = rbf.fit_rbf(x, y, is_direction=DIRS5, shape=[0.1, 0.2, 0.2])
    xq = _sea_states(5000, seed=22)
    before = numba.get_num_threads()
    try:
        outs = []
        for n in (1, min(2, numba.config.NUMBA_NUM_THREADS)):
            numba.set_num_threads(n)
            outs.append(rbf.predict_rbf(model, xq, chunk_rows=1000))
    finally:
        numba.set_num_threads(before)
    np.testing.assert_array_equal(outs[0], outs[1])


def test_nearest_centre():
    x = _sea_states(30, seed=15)
    model = rbf.fit_rbf(x, x[:, 2], is_direction=DIRS5, shape=0.2)
    xq = _sea_states(200, seed=16)
    dist, idx = rbf.nearest_centre(model, xq)
    z, zc = rbf.normalise(xq, model.space), model.centres
    full = np.sqrt(rbf.squared_distances(z, zc, DIRS5))
    np.testing.assert_array_equal(idx, np.argmin(full, axis=1))
    np.testing.assert_allclose(dist, full.min(axis=1))
    d0, i0 = rbf.nearest_centre(model, x)
    np.testing.assert_array_equal(i0, np.arange(30))
    np.testing.assert_allclose(d0, 0.0, atol=1e-15)


def test_bad_input_errors_name_the_problem():
    x = _sea_states(20, seed=17)
    y = x[:, 2].copy()
    y[5] = -1.0
    with pytest.raises(ValueError, match="output 0 .* row 5"):
        rbf.fit_rbf(x, y, is_direction=DIRS5, shape=0.2, log_output=True)
    y[5] = np.nan
    with pytest.raises(ValueError, match="output 0, row 5"):
        rbf.fit_rbf(x, y, is_direction=DIRS5, shape=0.2)
    x2 = x.copy()
    x2[3, 2] = np.inf
    with pytest.raises(ValueError, match="row 3, column 2"):
        rbf.fit_rbf(x2, x[:, 2], is_direction=DIRS5, shape=0.2)
    with pytest.raises(ValueError, match="positive"):
        rbf.fit_rbf(x, x[:, 2], is_direction=DIRS5, shape=0.0)
    with pytest.raises(ValueError, match="well-conditioned"):
        rbf.choose_shapes(rbf.LOOCurve(np.array([1.0, 2.0]), np.full((2, 1), np.inf), np.zeros(2)))


def test_choose_candidates_never_picks_a_nan_and_refuses_an_output_without_a_finite_one():
    """A NaN leave-one-out RMS loses to any finite one (np.min would propagate it, and the cover never end)."""
    rms = np.array([[np.nan, 1.0, 2.0], [3.0, np.nan, 1.0], [4.0, 2.0, np.inf]])
    for tol in (0.0, 0.5):
        np.testing.assert_array_equal(rbf.choose_candidates(rms, tol), [1, 0, 1])
    with pytest.raises(ValueError, match="output 1: no candidate has a finite leave-one-out RMS"):
        rbf.choose_candidates(np.array([[1.0, np.nan], [2.0, np.inf]]))


@pytest.mark.parametrize("smoothing", [0.0, 0.03])
def test_loo_residuals_equal_rippa_on_the_block_inverse(smoothing):
    x = _sea_states(90, seed=21)
    y = np.column_stack([np.sin(x[:, 2]) + x[:, 3] / 10, np.log(1 + x[:, 0])])
    space = rbf.fit_space(x, DIRS5)
    z = rbf.normalise(x, space)
    d2 = rbf.squared_distances(z, z, DIRS5)
    basis = rbf.polynomial_basis(z, DIRS5)
    k = rbf.gaussian(d2, 0.3) + smoothing * np.eye(90)
    h, rc_h = rbf.kernel_block_inverse(k, basis)
    e, rc = rbf.loo_residuals(k, basis, y)
    ref = rbf.rippa_errors(h, y)
    np.testing.assert_allclose(e, ref, rtol=1e-7, atol=1e-9 * np.abs(ref).max())
    assert rc == rc_h > 0
    bad, rc0 = rbf.loo_residuals(np.ones((90, 90)), basis, y)
    assert bad is None and rc0 == 0.0


# ------------------------------------------------------------------ back-transform and per-output choice
def test_retransform_factor_known_answers():
    a = 0.2
    ly = np.array([[0.0], [1.0]])  # y = 1 and 10
    e = np.array([[a], [-a]])  # leave-one-out predictions 10**-a and 10**(1 + a)
    np.testing.assert_array_equal(rbf.retransform_factor(ly, e, "none"), [1.0])
    np.testing.assert_allclose(rbf.retransform_factor(ly, e, "smearing"), [(10**a + 10**-a) / 2], rtol=1e-15)
    np.testing.assert_allclose(rbf.retransform_factor(ly, e, "ratio"), [11 / (10**-a + 10 ** (1 + a))], rtol=1e-15)
    np.testing.assert_allclose(rbf.loo_error_in_units(10**ly, ly, e, [2.0])[:, 0], [1 - 2 * 10**-a, 10 - 2 * 10**1.2])
    # lognormal residuals: the smearing factor is the mean of 10**e = exp((sigma ln 10)^2 / 2)
    sigma = 0.15
    eps = np.random.default_rng(3).normal(0.0, sigma, (400_000, 1))
    got = rbf.retransform_factor(np.zeros_like(eps), eps, "smearing")[0]
    assert got == pytest.approx(np.exp((sigma * np.log(10)) ** 2 / 2), rel=2e-3)
    assert got > 1.05  # the median back-transform alone would be 5 % low
    with pytest.raises(ValueError, match="unknown back-transform"):
        rbf.retransform_factor(ly, e, "mean")


@pytest.mark.parametrize("method", ["smearing", "ratio"])
def test_back_transform_factor_equals_brute_force_leave_one_out(method):
    """The factor of a fit is that of the refits without each state, and multiplies every prediction."""
    x = _sea_states(40, seed=31)
    y = 10 ** (-6 + 0.3 * x[:, 2] + 0.2 * np.sin(x[:, 3]))  # decades of damage, wiggly in Tp
    q = 0.3
    plain = rbf.fit_rbf(x, y, is_direction=DIRS5, shape=q, log_output=True)
    model = rbf.fit_rbf(x, y, is_direction=DIRS5, shape=q, log_output=True, retransform=method)
    lo, span = model.space.lower, model.space.scale
    pred = np.empty(40)  # median (uncorrected) prediction at each state of the fit without it
    for k in range(40):
        keep = np.arange(40) != k
        sub = rbf.fit_rbf(x[keep], y[keep], is_direction=DIRS5, shape=q, log_output=True, lo=lo, span=span)
        pred[k] = rbf.predict_rbf(sub, x[k : k + 1])[0, 0]
    expect = np.mean(y / pred) if method == "smearing" else y.sum() / pred.sum()
    assert model.log_factor[0] == pytest.approx(expect, rel=1e-8)
    assert plain.log_factor[0] == 1.0 and abs(model.log_factor[0] - 1) > 1e-3
    xq = _sea_states(300, seed=32)
    np.testing.assert_allclose(
        rbf.predict_rbf(model, xq)[:, 0], model.log_factor[0] * rbf.predict_rbf(plain, xq)[:, 0], rtol=1e-13
    )
    np.testing.assert_array_equal(model.weights, plain.weights)


def test_per_output_choice_picks_log_for_lognormal_and_linear_for_linear_outputs():
    x = _sea_states(120, seed=41)
    lognormal = 10 ** (-7 + 0.5 * x[:, 2] + 0.3 * np.cos(np.deg2rad(x[:, 4])))  # spans four decades
    linear = 3.0 + 0.5 * x[:, 2] + 0.1 * x[:, 3] + 0.02 * x[:, 0]  # positive: log10 is a candidate too
    y = np.column_stack([lognormal, linear])
    geometry = [rbf.centre_geometry(x, DIRS5)]
    grid = rbf.shape_grid(0.05, 1.0, 8)
    choice = rbf.choose_per_output(
        geometry, y, shapes=grid, log_values=np.log10(y), log_candidate=[True, True], retransform="smearing"
    )
    np.testing.assert_array_equal(choice.log_output, [True, False])
    np.testing.assert_array_equal(choice.space, [0, 0])
    assert choice.best[0, 1, 0] < choice.best[0, 0, 0] and choice.best[0, 0, 1] < choice.best[0, 1, 1]
    # the score is the leave-one-out RMSE in the output's units of the predictor used (brute force)
    model = rbf.fit_rbf_fixed(
        x, y[:, :1], is_direction=DIRS5, shape=choice.shape[0], log_output=True, retransform="smearing"
    )
    lo, span = model.space.lower, model.space.scale
    err = np.empty(120)
    for k in range(120):
        keep = np.arange(120) != k
        sub = rbf.fit_rbf_fixed(
            x[keep], y[keep, :1], is_direction=DIRS5, shape=choice.shape[0], log_output=True, lo=lo, span=span
        )
        err[k] = y[k, 0] - model.log_factor[0] * rbf.predict_rbf(sub, x[k : k + 1])[0, 0]
    assert choice.loo_rmse[0] == pytest.approx(np.sqrt(np.mean(err**2)), rel=1e-6)
    # without a log candidate the lognormal output stays linear
    lin = rbf.choose_per_output(geometry, y, shapes=grid)
    np.testing.assert_array_equal(lin.log_output, [False, False])
    with pytest.raises(ValueError, match="no transform candidate"):
        rbf.choose_per_output(geometry, y, shapes=grid, linear_candidate=[False, True])


@pytest.mark.parametrize("trend", [False, True])
def test_training_weights_carry_a_weighted_sum_of_the_interpolant(trend):
    """sum_h w_h f(x_h) = sum_i G_i y_i, G = training_weights: the interpolant is linear in its
    training values (log10 for a log output), per shape and ridge, with or without a trend."""
    x = _sea_states(150, 3)
    y = np.column_stack([1e-5 * (1.0 + x[:, 2] ** 2), np.sin(x[:, 2]) + 0.05 * x[:, 3], x[:, 3] ** 2])
    kw = dict(is_direction=DIRS5, shape=[0.3, 0.3, 0.5], smoothing=[0.0, 1e-3, 0.0], log_output=[True, False, False])
    if trend:
        kw["trend"] = rbf.Trend(column=0, knots=(8.0, 12.0, 16.0), direction=1, harmonics=1)
    model = rbf.fit_rbf(x, y, **kw)
    assert (model.trend is not None) == trend
    xq = _sea_states(400, 4)
    w = np.random.default_rng(5).random((400, 3))
    f = rbf.predict_rbf(model, xq)
    f[:, 0] = np.log10(f[:, 0])  # the interpolated values
    yt = np.column_stack([np.log10(y[:, 0]), y[:, 1:]])
    g = rbf.training_weights(model, xq, w, train_points=x if trend else None)
    np.testing.assert_allclose(np.sum(g * yt, axis=0), np.sum(w * f, axis=0), rtol=1e-9)
    # one column of weights for every output; the chunking does not change the weights
    tp = x if trend else None
    g1 = rbf.training_weights(model, xq, w[:, 1], train_points=tp, chunk_rows=37)
    np.testing.assert_allclose(g1, rbf.training_weights(model, xq, w[:, 1], train_points=tp), rtol=1e-10, atol=0)
    np.testing.assert_allclose(np.sum(g1 * yt, axis=0), f.T @ w[:, 1], rtol=1e-9)
    one = rbf.training_weights(model, xq, w[:, 2], outputs=[2], train_points=tp)
    np.testing.assert_allclose(one[:, 0], g[:, 2], rtol=0, atol=1e-10 * np.abs(g[:, 2]).max())
    if trend:
        with pytest.raises(ValueError, match="train_points"):
            rbf.training_weights(model, xq, w)
    with pytest.raises(ValueError, match="weights have shape"):
        rbf.training_weights(model, xq, w[:, :2], train_points=x)
