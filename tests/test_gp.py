"""Tests of moorlife.gp (the Gaussian process with a noise term, lifecycle.rbf.method: gp) on constructed data."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from sklearn.gaussian_process import GaussianProcessRegressor
from sklearn.gaussian_process.kernels import RBF, Matern, WhiteKernel
from sklearn.gaussian_process.kernels import ConstantKernel as C

from moorlife import gp, lifecycle, names, rbf
from moorlife.space import direction_mask

MASK = direction_mask()
COVARIANCES = ["gaussian", "matern52", "matern32"]


def _shape(covariance: str, length_scale, bounds="fixed"):
    """scikit-learn's kernel of a covariance family."""
    if covariance == "gaussian":
        return RBF(length_scale, bounds)
    return Matern(length_scale, bounds, nu={"matern52": 2.5, "matern32": 1.5}[covariance])


def _states(n: int, seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    return np.column_stack(
        [
            rng.uniform(0, 25, n),
            rng.uniform(0, 360, n),
            rng.uniform(0.3, 6, n),
            rng.uniform(4, 18, n),
            rng.uniform(0, 360, n),
        ]
    )


def _smooth(x: np.ndarray) -> np.ndarray:
    """A smooth 5-D surface: Hs, Tp, the wave direction on the circle, the wind speed."""
    w, _, hs, tp, alpha = x.T
    return (
        1.0 + 0.3 * hs**2 + 0.5 * np.exp(-(((tp - 11.0) / 4.0) ** 2)) + 0.4 * np.cos(np.deg2rad(alpha)) + 0.002 * w**2
    )


def test_chord_embedding_is_circular_and_matches_the_folded_distance_to_first_order():
    space = rbf.fit_space(_states(50, 0), MASK)
    pts = np.array([[5.0, 350.0, 1.0, 8.0, 0.0], [5.0, 10.0, 1.0, 8.0, 0.0], [5.0, 30.0, 1.0, 8.0, 0.0]])
    z = gp.chord_embed(pts, space)
    assert z.shape == (3, 7)
    d01, d12 = np.linalg.norm(z[0] - z[1]), np.linalg.norm(z[1] - z[2])
    assert d01 == pytest.approx(d12, rel=1e-12)  # 350 -> 10 deg across north, as 10 -> 30
    folded = rbf.squared_distances(rbf.normalise(pts[:2], space), rbf.normalise(pts[1:2], space), MASK)[0, 0]
    assert d01 == pytest.approx(np.sqrt(folded), rel=0.01)  # 20 deg: chord ~ arc
    assert gp.embedded_names(names.METOCEAN_VARS, MASK) == [
        "wind_speed",
        "hs",
        "tp",
        "cos_wind_dir",
        "cos_wave_dir",
        "sin_wind_dir",
        "sin_wave_dir",
    ]


@pytest.mark.parametrize("covariance", COVARIANCES)
def test_correlation_equals_scikit_learns_kernel(covariance):
    rng = np.random.default_rng(40)
    za, zb, ls = rng.normal(0, 1, (70, 4)), rng.normal(0, 1, (50, 4)), np.array([0.3, 0.7, 1.5, 4.0])
    np.testing.assert_allclose(
        gp.correlation(za, zb, ls, covariance), _shape(covariance, ls)(za, zb), rtol=1e-13, atol=1e-15
    )
    far = gp.correlation(za[:1], za[:1] + 1e4, ls, covariance)
    assert far[0, 0] == 0.0  # beyond exp(-708): zero, as in the prediction's rows
    with pytest.raises(ValueError, match="covariance 'cubic'"):
        gp.correlation(za, zb, ls, "cubic")


@pytest.mark.parametrize("covariance", COVARIANCES)
def test_mean_and_variance_equal_scikit_learns_predict(covariance):
    x = _states(60, 1)
    y = _smooth(x) + np.random.default_rng(2).normal(0, 0.2, 60)
    model = gp.fit_gp(x, y, is_direction=MASK, covariance=covariance)
    assert model.covariance == covariance
    shape = _shape(covariance, model.length_scale[0])
    kern = C(model.signal_var[0] / y.var()) * shape + WhiteKernel(model.noise_var[0] / y.var())
    ref = GaussianProcessRegressor(kern, alpha=0.0, normalize_y=True, optimizer=None).fit(
        gp.chord_embed(x, model.space), y
    )
    xq = _states(40, 3)
    mu, var = gp.predict_latent(model, xq, variance_of=[True])
    mu_ref, sd_ref = ref.predict(gp.chord_embed(xq, model.space), return_std=True)
    np.testing.assert_allclose(mu[:, 0], mu_ref, rtol=0, atol=1e-9)
    np.testing.assert_allclose(var[:, 0] + model.noise_var[0], sd_ref**2, rtol=1e-8)  # sklearn's includes the noise


@pytest.mark.parametrize("covariance", ["gaussian", "matern32"])
def test_closed_form_leave_one_out_equals_brute_force_refits(covariance):
    """R&W eq. 5.12 against scikit-learn refitted without each state (same hyperparameters and mean)."""
    x = _states(40, 4)
    y = np.column_stack([_smooth(x), np.exp(0.3 * x[:, 2])]) * np.random.default_rng(5).lognormal(0, 0.1, (40, 2))
    model = gp.fit_gp(x, y, is_direction=MASK, log_output=[False, True], covariance=covariance)
    z = gp.chord_embed(x, model.space)
    ty = np.column_stack([y[:, 0], np.log10(y[:, 1])])
    for j in range(2):
        kern = C(model.signal_var[j], "fixed") * _shape(covariance, model.length_scale[j]) + WhiteKernel(
            model.noise_var[j], "fixed"
        )
        brute = np.empty(40)
        var = np.empty(40)
        for i in range(40):
            keep = np.arange(40) != i
            ref = GaussianProcessRegressor(kern, alpha=0.0, optimizer=None).fit(z[keep], ty[keep, j] - model.mean[j])
            mu, sd = ref.predict(z[i : i + 1], return_std=True)
            brute[i], var[i] = ty[i, j] - model.mean[j] - mu[0], sd[0] ** 2
        np.testing.assert_allclose(model.loo_error[:, j], brute, rtol=1e-7, atol=1e-10)
        np.testing.assert_allclose(model.loo_var[:, j], var, rtol=1e-7)


def test_noisy_surface_recovered_better_than_by_exact_interpolation():
    """5-D, noise sd 0.25 on a surface of range ~10: the GP's error to the truth well below the exact RBF's."""
    x, xq = _states(200, 6), _states(500, 7)
    y = _smooth(x) + np.random.default_rng(8).normal(0, 0.25, 200)
    model = gp.fit_gp(x, y, is_direction=MASK)
    exact = rbf.fit_rbf(x, y, is_direction=MASK, shapes=rbf.shape_grid(0.05, 1.0, 10))
    err_gp = np.sqrt(np.mean((gp.predict_gp(model, xq)[:, 0] - _smooth(xq)) ** 2))
    err_rbf = np.sqrt(np.mean((rbf.predict_rbf(exact, xq)[:, 0] - _smooth(xq)) ** 2))
    assert err_gp < 0.6 * err_rbf
    assert np.sqrt(model.noise_var[0]) == pytest.approx(0.25, rel=0.25)  # the noise is recognised as noise
    assert np.sqrt(np.mean(model.loo_error**2)) < np.sqrt(np.mean(exact.loo_error**2))


def test_one_dimensional_noisy_function():
    rng = np.random.default_rng(9)
    x = np.sort(rng.uniform(0, 1, 60))[:, None]
    f = lambda t: np.sin(6 * t[:, 0])
    y = f(x) + rng.normal(0, 0.1, 60)
    model = gp.fit_gp(x, y, is_direction=[False])
    xq = np.linspace(0, 1, 301)[:, None]
    err_gp = np.sqrt(np.mean((gp.predict_gp(model, xq)[:, 0] - f(xq)) ** 2))
    exact = rbf.fit_rbf(x, y, is_direction=[False], shapes=rbf.shape_grid(0.002, 0.2, 12))
    err_rbf = np.sqrt(np.mean((rbf.predict_rbf(exact, xq)[:, 0] - f(xq)) ** 2))
    assert err_gp < 0.05 and err_gp < 0.5 * err_rbf


def test_matern_fits_a_rough_surface_better_than_the_squared_exponential():
    """Sample paths of a Matern 3/2 process (once differentiable, as the light lines' damage across
    rated wind is rough at the scale of the training states): the matern32 fit has the smaller
    leave-one-out error on every path, and predicts the held-out points of the paths better."""
    err, loo = {"gaussian": [], "matern32": []}, {"gaussian": [], "matern32": []}
    for seed in range(4):
        rng = np.random.default_rng(seed)
        t = rng.uniform(0, 1, (400, 1))
        path = np.linalg.cholesky(Matern(0.15, nu=1.5)(t) + 1e-10 * np.eye(400)) @ rng.standard_normal(400)
        y = path[:80] + rng.normal(0, 0.01, 80)
        for cov in err:
            model = gp.fit_gp(t[:80], y, is_direction=[False], covariance=cov)
            err[cov].append(np.mean((gp.predict_gp(model, t[80:])[:, 0] - path[80:]) ** 2))
            loo[cov].append(np.mean(model.loo_error**2))
    assert np.all(np.array(loo["matern32"]) < np.array(loo["gaussian"])), loo
    assert np.sqrt(np.sum(err["matern32"]) / np.sum(err["gaussian"])) < 0.85, err


def test_back_transform_of_log_output_is_unbiased():
    """log10 D = g(x) + N(0, s^2): the mean of E[D | x] over many hours matches the sample mean of D,
    with the noise's back-transform and with the predictive one; without one, the median.

    The training noise is standardised (mean 0, sd s exactly), so that what is tested is the
    back-transform, not the sampling error of 300 draws. The three back-transforms share one fit
    (they move no hyperparameter: the next test checks it).
    """
    s = 0.2  # 10**N(0, 0.2^2): median / mean = exp(-(ln 10)^2 s^2 / 2) = 0.90
    g = lambda t: -6.0 + 0.08 * t[:, 2] + 0.05 * np.cos(np.deg2rad(t[:, 4]))
    rng = np.random.default_rng(10)
    x = _states(300, 11)
    e = rng.normal(0, 1, 300)
    d = 10.0 ** (g(x) + s * (e - e.mean()) / e.std())
    xq = _states(4000, 12)
    truth = 10.0 ** (g(xq)[:, None] + rng.normal(0, s, (4000, 25)))  # 25 realisations per hour
    model = gp.fit_gp(x, d, is_direction=MASK, log_output=True, retransform="noise")
    assert model.log_factor[0] == pytest.approx(np.exp(0.5 * np.log(10) ** 2 * model.noise_var[0]))
    mean = truth.mean(axis=1).sum()
    for retransform in ("noise", "predictive"):
        ratio = gp.predict_gp(dataclasses.replace(model, retransform=retransform), xq).sum() / mean
        assert ratio == pytest.approx(1.0, abs=0.02), retransform
    median = dataclasses.replace(model, log_factor=np.ones(1), retransform="none")
    ratio_none = gp.predict_gp(median, xq).sum() / mean
    assert ratio_none == pytest.approx(np.exp(-0.5 * np.log(10) ** 2 * s**2), abs=0.02)  # the median


def test_predictive_back_transform_adds_the_latent_variance():
    x = _states(80, 13)
    d = 10.0 ** (-5 + 0.2 * x[:, 2] + np.random.default_rng(14).normal(0, 0.1, 80))
    m_noise = gp.fit_gp(x, d, is_direction=MASK, log_output=True, retransform="noise")
    m_pred = gp.fit_gp(x, d, is_direction=MASK, log_output=True, retransform="predictive")
    m_none = gp.fit_gp(x, d, is_direction=MASK, log_output=True, retransform="none")
    for m in (m_pred, m_none):  # the back-transform moves no hyperparameter (the test above relies on it)
        np.testing.assert_array_equal(m.length_scale, m_noise.length_scale)
        np.testing.assert_array_equal(m.weights, m_noise.weights)
    assert m_none.log_factor[0] == 1.0 and m_noise.log_factor[0] > 1.0
    xq = np.vstack([x[:5], _states(20, 15)])
    mu, var = gp.predict_latent(m_pred, xq, variance_of=[True])
    expected = 10.0 ** mu[:, 0] * np.exp(0.5 * np.log(10) ** 2 * (m_pred.noise_var[0] + var[:, 0]))
    np.testing.assert_allclose(gp.predict_gp(m_pred, xq)[:, 0], expected, rtol=1e-12)
    assert np.all(gp.predict_gp(m_pred, xq) > gp.predict_gp(m_noise, xq))
    far = gp.predict_latent(m_pred, xq[:5] + [[0, 0, 6.0, 0, 0]], variance_of=[True])[1]  # Hs beyond the data
    assert np.all(var[:5, 0] < far[:, 0])  # smaller at the training states than away from them


@pytest.mark.parametrize("covariance", gp.GP_COVARIANCES)
def test_fit_and_prediction_are_bit_identical_and_chunk_independent(covariance):
    x = _states(123, 16)  # not a multiple of the prediction's 8 partial sums: their tail is used
    y = np.column_stack([_smooth(x), np.exp(0.4 * x[:, 2])]) * np.random.default_rng(17).lognormal(0, 0.2, (123, 2))
    kw = dict(is_direction=MASK, log_output=[False, True], subsample=60, restarts=1, seed=3, covariance=covariance)
    a, b = gp.fit_gp(x, y, **kw), gp.fit_gp(x, y, **kw)
    for f in ("length_scale", "signal_var", "noise_var", "mean", "weights", "chol", "loo_error", "log_factor"):
        np.testing.assert_array_equal(getattr(a, f), getattr(b, f), err_msg=f)
    xq = _states(700, 18)
    p = gp.predict_gp(a, xq)
    np.testing.assert_array_equal(p, gp.predict_gp(b, xq, chunk_rows=37))
    mu, z = gp.predict_latent(a, xq)[0], gp.chord_embed(xq, a.space)
    for j in range(2):  # the compiled rows are the correlation of moorlife.gp.covariance
        ref = gp.correlation(z, a.centres, a.length_scale[j], covariance) @ a.weights[:, j] + a.mean[j]
        np.testing.assert_allclose(mu[:, j], ref, rtol=1e-12, atol=1e-12)
    other = gp.fit_gp(x, y, **{**kw, "seed": 4})  # another subsample: other hyperparameters
    assert not np.array_equal(other.length_scale, a.length_scale)


def test_bad_settings_are_refused():
    x = _states(20, 19)
    with pytest.raises(ValueError, match="kernel"):
        gp.fit_gp(x, x[:, 2], is_direction=MASK, kernel="matern")
    with pytest.raises(ValueError, match="covariance 'matern12'"):
        gp.fit_gp(x, x[:, 2], is_direction=MASK, covariance="matern12")
    with pytest.raises(ValueError, match="not positive"):
        gp.fit_gp(x, x[:, 2] - 3, is_direction=MASK, log_output=True)
    with pytest.raises(ValueError, match="gp.thrust = true with choose = 'per_output'"):
        lifecycle.RBFSettings.from_config({"method": "gp", "choose": "per_output", "gp": {"thrust": True}})
    with pytest.raises(ValueError, match=r"the GP's candidates are \['paper', 'thrust'\], not \['weighted'\]"):
        lifecycle.RBFSettings.from_config({"method": "gp", "choose": "per_output", "spaces": ["paper", "weighted"]})
    with pytest.raises(ValueError, match="min <= initial <= max"):
        lifecycle.RBFSettings.from_config({"method": "gp", "gp": {"noise": {"initial": 2.0}}})


def test_shared_hyperparameters_fit_the_group_jointly():
    """groups: one scikit-learn fit of a group's columns; its outputs share the length scales,
    the noise over signal ratio, the Cholesky factor and the prediction's kernel row."""
    x = _states(90, 20)
    rng = np.random.default_rng(21)
    f = _smooth(x)
    y = np.column_stack([f + rng.normal(0, 0.1, 90), 3.0 * f + 7.0 + rng.normal(0, 0.3, 90), np.sin(x[:, 3])])
    kw = dict(is_direction=MASK, subsample=0)
    alone = gp.fit_gp(x, y, **kw)
    shared = gp.fit_gp(x, y, groups=[0, 0, 1], **kw)
    np.testing.assert_array_equal(shared.length_scale[0], shared.length_scale[1])
    np.testing.assert_array_equal(shared.chol[0], shared.chol[1])
    assert shared.noise_var[0] / shared.signal_var[0] == shared.noise_var[1] / shared.signal_var[1]
    assert not np.array_equal(shared.length_scale[0], alone.length_scale[0])  # a joint fit, not the first column's
    # the joint fit is scikit-learn's own on the stacked columns
    z = gp.chord_embed(x, shared.space)
    k = C(1.0, (1e-3, 1e3)) * RBF(np.full(7, 0.3), (0.01, 100.0)) + WhiteKernel(1e-2, (1e-8, 1.0))
    ref = GaussianProcessRegressor(k, alpha=0.0, normalize_y=True, random_state=0).fit(z, y[:, :2])
    np.testing.assert_allclose(shared.length_scale[0], ref.kernel_.k1.k2.length_scale, rtol=1e-6)
    # a singleton group is the per-output fit, bit for bit
    for name in ("length_scale", "signal_var", "noise_var", "chol"):  # output first
        np.testing.assert_array_equal(getattr(shared, name)[2], getattr(alone, name)[2], err_msg=name)
    for name in ("weights", "loo_error"):  # output last
        np.testing.assert_array_equal(getattr(shared, name)[:, 2], getattr(alone, name)[:, 2], err_msg=name)
    xq = _states(300, 22)
    p_shared, p_alone = gp.predict_gp(shared, xq), gp.predict_gp(alone, xq)
    np.testing.assert_array_equal(p_shared[:, 2], p_alone[:, 2])
    # two noisy records of one surface: sharing pools them, and each column stays its own scale
    assert np.corrcoef(p_shared[:, 1], 3.0 * _smooth(xq) + 7.0)[0, 1] > 0.98
    with pytest.raises(ValueError, match="one label per output"):
        gp.fit_gp(x, y, groups=[0, 1], **kw)


def test_gp_share_groups_the_outputs_of_a_variable():
    cols = [("surge_mpm", None), ("damage_sn", "M1"), ("damage_tn", "M2"), ("tension_mpm", "M1"), ("tension_mpm", "M2")]
    assert lifecycle.gp_groups(cols, "none") is None
    np.testing.assert_array_equal(lifecycle.gp_groups(cols, "all"), [0, 0, 0, 0, 0])
    g = lifecycle.gp_groups(cols, "variable")
    assert g[1] == g[2] and g[3] == g[4] and len({g[0], g[1], g[3]}) == 3
    s = lifecycle.RBFSettings.from_config({"method": "gp", "gp": {"share": "variable"}})
    assert s.gp.share == "variable"
    with pytest.raises(ValueError, match="share"):
        lifecycle.RBFSettings.from_config({"method": "gp", "gp": {"share": "lines"}})


def _gls_reference(z, ty, ls, ratio, zq):
    """Universal kriging by hand: the GLS mean of [1, z] with B = R + ratio I, and its prediction at zq."""
    h = np.column_stack([np.ones(len(z)), z])
    b = gp.correlation(z, z, ls) + ratio * np.eye(len(z))
    bi = np.linalg.inv(b)
    beta = np.linalg.solve(h.T @ bi @ h, h.T @ bi @ ty)
    w = bi @ (ty - h @ beta)
    return np.column_stack([np.ones(len(zq)), zq]) @ beta + gp.correlation(zq, z, ls) @ w


def test_linear_prior_mean_is_universal_kriging():
    """prior_mean='linear': GLS coefficients, prediction and leave-one-out as written out by hand."""
    x = _states(50, 30)
    rng = np.random.default_rng(31)
    y = np.column_stack([2.0 + 0.3 * x[:, 0] + 0.2 * x[:, 3] + _smooth(x), np.exp(0.3 * x[:, 2])])
    y = y * rng.lognormal(0, 0.05, y.shape)
    model = gp.fit_gp(x, y, is_direction=MASK, log_output=[False, True], prior_mean="linear", retransform="none")
    z = gp.chord_embed(x, model.space)
    ty = np.column_stack([y[:, 0], np.log10(y[:, 1])])
    xq = _states(30, 32)
    zq = gp.chord_embed(xq, model.space)
    p = gp.predict_gp(model, xq)
    for j in range(2):
        ratio = model.noise_var[j] / model.signal_var[j]
        ref = _gls_reference(z, ty[:, j], model.length_scale[j], ratio, zq)
        np.testing.assert_allclose(p[:, j] if j == 0 else np.log10(p[:, j]), ref, rtol=1e-8, atol=1e-9)
        brute = np.empty(50)  # leave-one-out: the mean re-estimated without each state
        for i in range(50):
            keep = np.arange(50) != i
            brute[i] = ty[i, j] - _gls_reference(z[keep], ty[keep, j], model.length_scale[j], ratio, z[i : i + 1])[0]
        np.testing.assert_allclose(model.loo_error[:, j], brute, rtol=1e-6, atol=1e-9)
    assert model.slope.shape == (7, 2)
    assert gp.fit_gp(x, y, is_direction=MASK).slope is None  # the constant mean, as before


def test_linear_prior_mean_follows_a_trend_beyond_the_data():
    """Away from the training states the constant mean pulls the prediction back; the linear one does not."""
    x = _states(80, 33)
    x[:, 0] = np.random.default_rng(34).uniform(0, 15, 80)  # training winds 0-15 m/s
    f = lambda p: 1.0 + 0.4 * p[:, 0] + 0.2 * np.cos(np.deg2rad(p[:, 4]))  # noqa: E731
    y = f(x) + np.random.default_rng(35).normal(0, 0.02, 80)
    xq = _states(200, 36)
    xq[:, 0] = np.random.default_rng(37).uniform(20, 25, 200)  # and predict at 20-25 m/s
    kw = dict(is_direction=MASK, lo=[0, 0, 0.3, 4, 0], span=[25, 180, 5.7, 14, 180], subsample=0)
    err_const = np.abs(gp.predict_gp(gp.fit_gp(x, y, **kw), xq)[:, 0] - f(xq))
    err_lin = np.abs(gp.predict_gp(gp.fit_gp(x, y, prior_mean="linear", **kw), xq)[:, 0] - f(xq))
    assert np.median(err_lin) < 0.1 < np.median(err_const)


def test_linear_prior_mean_refuses_the_latent_variance():
    x = _states(20, 38)
    with pytest.raises(ValueError, match="prior mean"):
        gp.fit_gp(x, x[:, 2], is_direction=MASK, prior_mean="quadratic")
    with pytest.raises(ValueError, match="predictive"):
        gp.fit_gp(x, x[:, 2], is_direction=MASK, prior_mean="linear", retransform="predictive")
    model = gp.fit_gp(x, x[:, 2], is_direction=MASK, prior_mean="linear")
    with pytest.raises(ValueError, match="latent variance"):
        gp.predict_latent(model, x, variance_of=[True])
    with pytest.raises(ValueError, match="gp.mean = 'linear'"):
        lifecycle.RBFSettings.from_config({"method": "gp", "gp": {"mean": "linear", "indicator": "sd"}})


def _wind_plus_waves(x: np.ndarray) -> np.ndarray:
    """A narrow peak in the wind speed (modulated by its direction) plus a wave part in Hs: a sum."""
    w, wd, hs = x[:, 0], np.deg2rad(x[:, 1]), x[:, 2]
    return np.exp(-(((w - 12.0) / 2.0) ** 2)) * (1.2 + 0.3 * np.cos(wd)) + 0.08 * hs**2


WIND_COLUMNS = (0, 3, 5)  # wind_speed, cos_wind_dir, sin_wind_dir in chord_embed's order


@pytest.mark.parametrize("gated", [False, True])
def test_wind_term_mean_and_variance_equal_scikit_learns_sum_kernel(gated):
    """additive_columns: C k(l) + C_w [g g'] k_w(l_w on the wind's coordinates) + White, as
    scikit-learn predicts it with the same hyperparameters (``g`` the sea gate of gate_column);
    an output without the term is the plain fit."""
    from moorlife.gp.kernels import OnColumns, SeaGate

    assert [gp.embedded_names(names.METOCEAN_VARS, MASK)[c] for c in WIND_COLUMNS] == [
        "wind_speed",
        "cos_wind_dir",
        "sin_wind_dir",
    ]
    assert lifecycle.fit.wind_columns(MASK) == WIND_COLUMNS and lifecycle.fit.wave_height_column(MASK) == 1
    x = _states(100, 23)
    y = np.column_stack([_wind_plus_waves(x), _smooth(x)]) + np.random.default_rng(24).normal(0, 0.02, (100, 2))
    kw = dict(is_direction=MASK, covariance="matern52")
    gate_kw = dict(gate_column=1) if gated else {}
    model = gp.fit_gp(x, y, additive_columns=WIND_COLUMNS, additive_outputs=[True, False], **gate_kw, **kw)
    assert model.wind_var[0] > 0 and model.wind_var[1] == 0 and model.gate_column == (1 if gated else -1)
    assert np.isinf(model.wind_gate[1]) and (
        0.02 <= model.wind_gate[0] <= 2.0 if gated else np.isinf(model.wind_gate[0])
    )
    assert np.isinf(np.delete(model.wind_length_scale[0], WIND_COLUMNS)).all()
    assert (
        np.isfinite(model.wind_length_scale[0, list(WIND_COLUMNS)]).all() and np.isinf(model.wind_length_scale[1]).all()
    )
    z, xq = gp.chord_embed(x, model.space), _states(200, 25)
    mu, var = gp.predict_latent(model, xq, variance_of=[True, True])

    def kernel(unit: float, bounds):
        term = OnColumns(_shape("matern52", model.wind_length_scale[0, list(WIND_COLUMNS)]), WIND_COLUMNS)
        if gated:
            term = SeaGate(term, 1, model.wind_gate[0], "fixed")
        return (
            C(model.signal_var[0] / unit, bounds) * _shape("matern52", model.length_scale[0])
            + C(model.wind_var[0] / unit, bounds) * term
            + WhiteKernel(model.noise_var[0] / unit, bounds)
        )

    ref = GaussianProcessRegressor(kernel(y[:, 0].var(), "fixed"), alpha=0.0, normalize_y=True, optimizer=None)
    mu_ref, sd_ref = ref.fit(z, y[:, 0]).predict(gp.chord_embed(xq, model.space), return_std=True)
    np.testing.assert_allclose(mu[:, 0], mu_ref, rtol=0, atol=1e-9)
    np.testing.assert_allclose(var[:, 0] + model.noise_var[0], sd_ref**2, rtol=1e-8)
    plain = gp.fit_gp(x, y[:, 1], **kw)
    np.testing.assert_array_equal(gp.predict_gp(model, xq)[:, 1], gp.predict_gp(plain, xq)[:, 0])
    # the closed-form leave-one-out holds the wind term (B = R + (s_w / s) [g g'] R_w + ratio I):
    # scikit-learn refitted without one state, the same hyperparameters in y's own units
    i, keep = 7, np.arange(100) != 7
    brute = GaussianProcessRegressor(kernel(1.0, "fixed"), alpha=0.0, optimizer=None)
    brute.fit(z[keep], y[keep, 0] - model.mean[0])
    assert model.loo_error[i, 0] == pytest.approx(y[i, 0] - model.mean[0] - brute.predict(z[i : i + 1])[0], abs=1e-9)


def test_sea_gate_kernel_gradient_equals_finite_differences():
    """The gate's scale is a hyperparameter of the marginal likelihood: its gradient, and the base's."""
    from sklearn.gaussian_process.kernels import Matern

    from moorlife.gp.kernels import OnColumns, SeaGate

    z = np.random.default_rng(27).uniform(0, 1, (12, 7))
    k = SeaGate(OnColumns(Matern(np.full(3, 0.3), (1e-2, 1e2), nu=2.5), WIND_COLUMNS), 1, 0.3)
    kz, dk = k(z, eval_gradient=True)
    theta = k.theta
    assert theta.size == 4 and k.bounds.shape == (4, 2) and theta[0] == pytest.approx(np.log(0.3))
    for i in range(theta.size):
        step = 1e-6 * np.eye(theta.size)[i]
        fd = (k.clone_with_theta(theta + step)(z) - k.clone_with_theta(theta - step)(z)) / 2e-6
        np.testing.assert_allclose(dk[:, :, i], fd, atol=1e-8)
    np.testing.assert_allclose(np.diag(kz), k.diag(z))
    g = gp.covariance.gate(z[:, 1], 0.3)
    np.testing.assert_allclose(kz, np.outer(g, g) * k.base(z), rtol=1e-14)
    assert np.all(np.linalg.eigvalsh(kz + 1e-12 * np.eye(12)) > 0)


def test_sea_gate_keeps_the_wind_term_out_of_the_storm():
    """A wind part that fades as the sea grows (the light line's damage, section 21): the gated
    term recovers it better than the ungated one, which spreads the wind's peak into the storm."""
    x, xq = _states(150, 31), _states(800, 41)

    def f(p):
        return np.exp(-(((p[:, 0] - 12.0) / 2.0) ** 2)) * np.exp(-p[:, 2] / 1.5) + 0.05 * p[:, 2] ** 2

    y = f(x) + np.random.default_rng(1).normal(0, 0.02, 150)
    kw = dict(is_direction=MASK, covariance="matern52", additive_columns=WIND_COLUMNS)
    gated, plain = gp.fit_gp(x, y, gate_column=1, **kw), gp.fit_gp(x, y, **kw)
    err = lambda m, sel: np.sqrt(np.mean((gp.predict_gp(m, xq)[sel, 0] - f(xq)[sel]) ** 2))  # noqa: E731
    storm = xq[:, 2] > 4.0
    assert err(gated, storm) < 0.5 * err(plain, storm) and err(gated, ~storm) < 0.7 * err(plain, ~storm)
    span = gated.space.scale[2]  # the wave height's normalisation span (m)
    assert gated.wind_gate[0] * span == pytest.approx(1.5, rel=0.2)  # the fitted gate is the fade's 1.5 m


def test_wind_term_recovers_a_sum_of_a_wind_and_a_wave_part_better_than_the_product_kernel():
    """The constructed sum of section 21's diagnosis: half the error to the truth of the plain GP."""
    x, xq = _states(120, 30), _states(800, 40)
    y = _wind_plus_waves(x) + np.random.default_rng(0).normal(0, 0.02, 120)
    kw = dict(is_direction=MASK, covariance="matern52")
    add, plain = gp.fit_gp(x, y, additive_columns=WIND_COLUMNS, **kw), gp.fit_gp(x, y, **kw)
    err = lambda m: np.sqrt(np.mean((gp.predict_gp(m, xq)[:, 0] - _wind_plus_waves(xq)) ** 2))  # noqa: E731
    assert err(add) < 0.7 * err(plain)
    assert np.sqrt(np.mean(add.loo_error**2)) < np.sqrt(np.mean(plain.loo_error**2))  # seen by the training states too
    sub = gp.select_outputs(gp.fit_gp(x, np.column_stack([y, y]), additive_columns=WIND_COLUMNS, **kw), [1])
    np.testing.assert_array_equal(sub.wind_var, add.wind_var)
    np.testing.assert_array_equal(sub.wind_length_scale, add.wind_length_scale)


def test_wind_term_hyperparameters_on_their_own_subsample():
    """additive_subsample: the outputs with the term fit their hyperparameters on it, the others
    on subsample, each as a fit of its own with that subsample would (the same draw)."""
    x = _states(90, 28)
    y = np.column_stack([_wind_plus_waves(x), _smooth(x)]) + np.random.default_rng(29).normal(0, 0.02, (90, 2))
    kw = dict(is_direction=MASK, covariance="matern52", gate_column=1)
    both = gp.fit_gp(
        x, y, additive_columns=WIND_COLUMNS, additive_outputs=[True, False], subsample=40, additive_subsample=0, **kw
    )
    wind_all = gp.fit_gp(x, y[:, 0], additive_columns=WIND_COLUMNS, subsample=0, **kw)
    plain_40 = gp.fit_gp(x, y[:, 1], subsample=40, **kw)
    for f in ("length_scale", "signal_var", "noise_var", "wind_var", "wind_gate"):
        np.testing.assert_array_equal(getattr(both, f)[0], getattr(wind_all, f)[0], err_msg=f)
    for f in ("length_scale", "signal_var", "noise_var"):
        np.testing.assert_array_equal(getattr(both, f)[1], getattr(plain_40, f)[0], err_msg=f)
    same = gp.fit_gp(x, y[:, 0], additive_columns=WIND_COLUMNS, subsample=40, **kw)  # default: subsample's draw
    assert not np.array_equal(same.length_scale, wind_all.length_scale)
    np.testing.assert_array_equal(
        same.length_scale,
        gp.fit_gp(x, y[:, 0], additive_columns=WIND_COLUMNS, subsample=40, additive_subsample=40, **kw).length_scale,
    )


def test_wind_term_fit_started_from_the_plain_kernel():
    """additive_start: warm and frozen first fit the plain kernel on subsample states, as a fit
    without the term would; frozen keeps its length scales, warm starts from them. Both recover
    the constructed sum."""
    x = _states(120, 28)
    y = _wind_plus_waves(x) + np.random.default_rng(29).normal(0, 0.02, 120)
    kw = dict(is_direction=MASK, covariance="matern52", subsample=60)
    term = dict(additive_columns=WIND_COLUMNS, gate_column=1, additive_subsample=0)
    plain = gp.fit_gp(x, y, **kw)
    fits = {start: gp.fit_gp(x, y, additive_start=start, **term, **kw) for start in gp.GP_ADDITIVE_STARTS}
    np.testing.assert_array_equal(fits["frozen"].length_scale, plain.length_scale)
    assert not np.array_equal(fits["warm"].length_scale, plain.length_scale)  # fitted from there
    assert not np.array_equal(fits["warm"].length_scale, fits["joint"].length_scale)
    xq = _states(400, 5)
    for start, m in fits.items():
        assert m.wind_var[0] > 0 and np.isfinite(m.wind_gate[0])
        assert np.corrcoef(gp.predict_gp(m, xq)[:, 0], _wind_plus_waves(xq))[0, 1] > 0.99, start


def test_wind_term_bad_settings_are_refused():
    x = _states(30, 26)
    y = np.column_stack([x[:, 2], x[:, 3]])
    with pytest.raises(ValueError, match=r"additive_columns \[0, 9\]: need distinct columns of the 7"):
        gp.fit_gp(x, y, is_direction=MASK, additive_columns=(0, 9))
    with pytest.raises(ValueError, match=r"additive_columns \[0, 0\]"):
        gp.fit_gp(x, y, is_direction=MASK, additive_columns=(0, 0))
    with pytest.raises(ValueError, match=r"gate_column 3: need one of the 7 embedded coordinates, not the term's"):
        gp.fit_gp(x, y, is_direction=MASK, additive_columns=WIND_COLUMNS, gate_column=3)
    with pytest.raises(ValueError, match="gate_scale: need 0 < min <= initial <= max"):
        gp.fit_gp(x, y, is_direction=MASK, additive_columns=WIND_COLUMNS, gate_column=1, gate_scale=(3.0, 0.1, 2.0))
    with pytest.raises(ValueError, match="lifecycle.rbf.gp.wind_gate needs min <= initial <= max"):
        lifecycle.RBFSettings.from_config(
            {"method": "gp", "gp": {"wind_term": "damage", "wind_gate": {"initial": 5.0}}}
        )
    with pytest.raises(ValueError, match=r"outputs \[0, 1\] share their hyperparameters but not all have"):
        gp.fit_gp(x, y, is_direction=MASK, additive_columns=(0,), additive_outputs=[True, False], groups=[0, 0])
    with pytest.raises(ValueError, match="unknown GP additive_start 'cold'"):
        gp.fit_gp(x, y, is_direction=MASK, additive_columns=WIND_COLUMNS, additive_start="cold")
    with pytest.raises(ValueError, match="wind_term = 'damage' with share = 'all'"):
        lifecycle.RBFSettings.from_config({"method": "gp", "gp": {"wind_term": "damage", "share": "all"}})
    with pytest.raises(ValueError, match="wind_term"):
        lifecycle.RBFSettings.from_config({"method": "gp", "gp": {"wind_term": "waves"}})
    assert (
        lifecycle.RBFSettings.from_config({"method": "gp", "gp": {"wind_term": "all", "share": "all"}}).gp.wind_term
        == "all"
    )


def test_outputs_a_constant_factor_apart_share_one_hyperparameter_fit(monkeypatch):
    """Outputs whose standardised fit data are equal (a constant factor apart, log10: a constant
    apart, as the S-N and T-N damage of a line with equal slopes) take the first one's
    hyperparameters without a second fit: the same optimum, the same Cholesky factor and kernel
    row, each output its own scale. Outputs that differ by more than rounding are fitted apart."""
    x = _states(90, 30)
    rng = np.random.default_rng(31)
    d = np.exp(_smooth(x) + rng.normal(0, 0.05, 90))
    y = np.column_stack([d, 4.2 * d, np.exp(np.sin(x[:, 3])), 4.2 * d * (1 + rng.normal(0, 1e-6, 90))])
    calls = []
    fit = GaussianProcessRegressor.fit
    monkeypatch.setattr(GaussianProcessRegressor, "fit", lambda self, *a: calls.append(1) or fit(self, *a))
    m = gp.fit_gp(x, y, is_direction=MASK, log_output=True, covariance="matern52", subsample=60)
    assert len(calls) == 3  # outputs 0, 2 and 3; output 1 is output 0's twin
    np.testing.assert_array_equal(m.length_scale[1], m.length_scale[0])
    np.testing.assert_array_equal(m.chol[1], m.chol[0])
    np.testing.assert_allclose(m.signal_var[1], m.signal_var[0], rtol=1e-12)
    assert not np.array_equal(m.length_scale[3], m.length_scale[0])  # fitted on its own
    xq = _states(200, 32)
    p = gp.predict_gp(m, xq)
    np.testing.assert_allclose(p[:, 1], 4.2 * p[:, 0], rtol=1e-10)
    # the twin's hyperparameters are those of its own fit, to the optimiser's precision
    alone = gp.fit_gp(x, y[:, 1], is_direction=MASK, log_output=True, covariance="matern52", subsample=60)
    np.testing.assert_allclose(m.length_scale[1], alone.length_scale[0], rtol=1e-5)
    np.testing.assert_allclose(p[:, 1], gp.predict_gp(alone, xq)[:, 0], rtol=1e-6)
    # with the additive term: twins among the outputs with it, not across
    kw = dict(is_direction=MASK, log_output=True, covariance="matern52", subsample=60, gate_column=1)
    calls.clear()
    w = gp.fit_gp(x, y[:, :2], additive_columns=WIND_COLUMNS, additive_outputs=[True, True], **kw)
    assert len(calls) == 1
    for f in ("length_scale", "wind_length_scale", "wind_gate"):
        np.testing.assert_array_equal(getattr(w, f)[1], getattr(w, f)[0], err_msg=f)
    calls.clear()
    gp.fit_gp(x, y[:, :2], additive_columns=WIND_COLUMNS, additive_outputs=[True, False], **kw)
    assert len(calls) == 2


@pytest.mark.parametrize("wind", [False, True])
def test_training_weights_carry_a_weighted_sum_of_the_posterior_means(wind):
    """sum_h w_h (mu(x_h) - m) = sum_i G_i (y_i - m), G = training_weights: the posterior mean is
    linear in the training values (log10 for a log output), with or without the gated wind term."""
    x = _states(120, 31)
    y = np.column_stack([1e-6 * np.exp(_wind_plus_waves(x)), _smooth(x)])
    y *= np.exp(np.random.default_rng(32).normal(0, 0.05, y.shape))
    kw = dict(is_direction=MASK, covariance="matern52", log_output=[True, False])
    if wind:
        kw.update(additive_columns=WIND_COLUMNS, additive_outputs=[True, False], gate_column=1)
    model = gp.fit_gp(x, y, **kw)
    assert (model.wind_var is not None and model.wind_var[0] > 0) == wind
    xq = _states(300, 33)
    mu, _ = gp.predict_latent(model, xq)
    yt = np.column_stack([np.log10(y[:, 0]), y[:, 1]])
    w = np.random.default_rng(34).random((300, 2))
    g = gp.training_weights(model, xq, w)
    np.testing.assert_allclose(np.sum(g * (yt - model.mean), axis=0), np.sum(w * (mu - model.mean), axis=0), rtol=1e-9)
    one = gp.training_weights(model, xq, w[:, 0], outputs=[0], chunk_rows=41)
    np.testing.assert_allclose(one[:, 0], g[:, 0], rtol=0, atol=1e-9 * np.abs(g[:, 0]).max())
    with pytest.raises(ValueError, match="weights have shape"):
        gp.training_weights(model, xq, w[:, :1])


def test_training_weights_make_one_pass_per_shared_correlation():
    """Outputs that share their hyperparameters (a line's S-N and T-N) share one pass over the
    points; each output's weights are those it has alone."""
    from moorlife.gp.predict import _shared_correlation

    x = _states(80, 36)
    d = 1e-6 * np.exp(_wind_plus_waves(x))
    y = np.column_stack([d, 0.5 * d, _smooth(x)])
    model = gp.fit_gp(x, y, is_direction=MASK, log_output=[True, True, False], groups=[0, 0, 1])
    assert _shared_correlation(model, np.arange(3)) == [[0, 1], [2]]
    xq = _states(200, 37)
    w = np.random.default_rng(38).random((200, 3))
    g = gp.training_weights(model, xq, w)
    for j in range(3):
        alone = gp.training_weights(model, xq, w[:, j], outputs=[j])[:, 0]
        np.testing.assert_allclose(g[:, j], alone, rtol=0, atol=1e-9 * np.abs(alone).max())  # gemm vs gemv


def test_training_weights_refuse_a_linear_prior_mean():
    x = _states(40, 35)
    model = gp.fit_gp(x, _smooth(x), is_direction=MASK, prior_mean="linear")
    with pytest.raises(ValueError, match="linear prior mean"):
        gp.training_weights(model, x, np.ones(40))
