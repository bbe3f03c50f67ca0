"""moorlife.stats: GEV by L-moments against scipy and known parameters, most probable
maximum against closed forms (Rayleigh, Gaussian processes), fit correlation, percentiles."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import stats as sps
from scipy.optimize import brentq, minimize_scalar

from moorlife.stats import (
    GEVParams,
    block_maxima,
    fit_correlation,
    gev_cdf,
    gev_fit,
    gev_fit_lmoments,
    gev_from_lmoments,
    gev_mode,
    gev_mpm,
    gev_of_maximum,
    gev_quantile,
    lmoments,
    percentiles,
    plotting_positions,
)


def _p(loc, scale, k):
    return GEVParams(np.asarray(loc, float), np.asarray(scale, float), np.asarray(k, float))


@pytest.mark.parametrize("k", [-0.3, -0.1, 0.0, 0.2, 0.45])
def test_gev_functions_match_scipy(k):
    """Hosking's k is scipy's c: cdf, quantile and mode agree with scipy.stats.genextreme."""
    p = _p(1.0, 2.0, k)
    dist = sps.genextreme(k, loc=1.0, scale=2.0)
    x = np.linspace(-4.0, 12.0, 33)
    assert np.allclose(gev_cdf(p, x), dist.cdf(x), atol=1e-14)
    q = np.array([0.01, 0.2, 0.5, 0.9, 0.999])
    assert np.allclose(gev_quantile(p, q), dist.ppf(q), rtol=1e-12)
    lo, hi = dist.ppf(0.001), dist.ppf(0.9)
    mode = minimize_scalar(lambda v: -dist.pdf(v), bounds=(lo, hi), method="bounded", options={"xatol": 1e-10}).x
    assert float(gev_mode(p)) == pytest.approx(mode, abs=1e-6)


@pytest.mark.parametrize("k", [-0.2, 0.0, 0.25])
def test_gev_of_maximum_is_cdf_power(k):
    p = _p(3.0, 1.5, k)
    pn = gev_of_maximum(p, 37.5)
    x = np.linspace(2.0, 15.0, 27)
    assert np.allclose(gev_cdf(pn, x), gev_cdf(p, x) ** 37.5, atol=1e-13)


def test_lmoments_match_direct_definition():
    """Unbiased sample L-moments against Hosking's direct formula (sums over pairs/triples)."""
    x = np.array([3.1, 0.4, 2.2, 5.0, 1.7, 2.9, 0.8])
    n = x.size
    s = np.sort(x)
    l2 = sum(s[j] - s[i] for i in range(n) for j in range(i + 1, n)) / (2 * math.comb(n, 2))
    l3 = sum(s[k] - 2 * s[j] + s[i] for i in range(n) for j in range(i + 1, n) for k in range(j + 1, n)) / (
        3 * math.comb(n, 3)
    )
    a1, a2, t3 = lmoments(x)
    assert a1 == pytest.approx(x.mean()) and a2 == pytest.approx(l2) and t3 == pytest.approx(l3 / l2)


@pytest.mark.parametrize(("loc", "scale", "k"), [(3.0, 1.5, -0.2), (3.0, 1.5, 0.0), (-1.0, 0.3, 0.2), (10.0, 4.0, 0.4)])
def test_lmoment_fit_recovers_known_parameters(loc, scale, k):
    """200,000 GEV draws per row, 3 rows fitted at once: parameters within 1 % (shape 0.01)."""
    rng = np.random.default_rng(7)
    x = sps.genextreme.rvs(k, loc=loc, scale=scale, size=(3, 200_000), random_state=rng)
    p = gev_fit_lmoments(x)
    assert p.loc.shape == (3,)
    assert np.allclose(p.loc, loc, atol=0.01 * scale)
    assert np.allclose(p.scale, scale, rtol=0.01)
    assert np.allclose(p.shape, k, atol=0.01)


@pytest.mark.parametrize("k", [-0.9, -0.4, -0.05, 0.0, 1e-4, 0.1, 0.6, 0.95])
def test_gev_from_population_lmoments_is_exact(k):
    """Population L-moments of GEV(2, 3, k) (Hosking 1990 closed forms) invert to the
    parameters to 1e-9: the Newton refinement removes the rational approximation's error."""
    loc, scale = 2.0, 3.0
    if k == 0.0:
        l1, l2, t3 = loc + scale * np.euler_gamma, scale * math.log(2.0), 2 * math.log(3) / math.log(2) - 3
    else:
        g = math.gamma(1.0 + k)
        l1 = loc + scale * (1.0 - g) / k
        l2 = scale * (1.0 - 2.0**-k) * g / k
        t3 = 2.0 * (1.0 - 3.0**-k) / (1.0 - 2.0**-k) - 3.0
    p = gev_from_lmoments(l1, l2, t3)
    assert float(p.shape) == pytest.approx(k, abs=1e-9)
    assert float(p.loc) == pytest.approx(loc, abs=1e-8) and float(p.scale) == pytest.approx(scale, rel=1e-8)


def test_lmoments_and_mle_agree_on_a_moderate_sample():
    rng = np.random.default_rng(11)
    x = sps.genextreme.rvs(0.1, loc=5.0, scale=2.0, size=(3, 400), random_state=rng)
    a = gev_fit(x, "lmoments")
    b = gev_fit(x, "mle")
    assert np.allclose(gev_mode(a), gev_mode(b), rtol=0.03)
    assert np.allclose(a.shape, b.shape, atol=0.08)
    with pytest.raises(ValueError, match="lmoments"):
        gev_fit(x, "moments")


def test_gev_mpm_on_max_stable_gev_samples():
    """iid samples of G = F^(1/ns) make the block maxima of ns samples exactly GEV F; the
    MPM over the record must be the mode of F^nb (known parameters)."""
    ns, nb, dt = 50, 400, 0.5
    true = _p(100.0, 8.0, 0.15)
    g = gev_of_maximum(true, 1.0 / ns)
    rng = np.random.default_rng(3)
    x = sps.genextreme.rvs(float(g.shape), loc=float(g.loc), scale=float(g.scale), size=(20, ns * nb), random_state=rng)
    mpm, corr = gev_mpm(x, dt, block=ns * dt)
    expected = float(gev_mode(gev_of_maximum(true, nb)))
    assert mpm.shape == (20,) and corr.shape == (20,)
    assert np.mean(mpm) == pytest.approx(expected, rel=0.01)
    assert np.all(corr > 0.98)
    # a longer target duration extrapolates with F^(n * duration / record)
    mpm3, _ = gev_mpm(x, dt, block=ns * dt, duration=3 * ns * nb * dt)
    assert np.mean(mpm3) == pytest.approx(float(gev_mode(gev_of_maximum(true, 3 * nb))), rel=0.015)


def test_gev_mpm_rayleigh_peaks_closed_form():
    """N iid Rayleigh(sigma) peaks: MPM = mode of F^N (exact, numerically) ~ sigma sqrt(2 ln N).
    100 records x 36,000 peaks, blocks of 100: mean within 1 % of the exact mode, 1.5 %
    of the closed form."""
    n = 36_000
    rng = np.random.default_rng(3)
    x = rng.rayleigh(1.0, size=(100, n))

    def dlogpdf(v):
        big_f = 1.0 - np.exp(-v * v / 2.0)
        return 1.0 / v - v + (n - 1) * v * np.exp(-v * v / 2.0) / big_f

    exact = brentq(dlogpdf, 2.0, 6.0)
    mpm, corr = gev_mpm(x, 1.0, block=100.0)
    assert np.mean(mpm) == pytest.approx(exact, rel=0.01)
    assert np.mean(mpm) == pytest.approx(math.sqrt(2.0 * math.log(n)), rel=0.015)
    assert np.median(corr) > 0.99


def _gaussian_records(psd, n, dt, nrec, seed):
    f = np.fft.rfftfreq(n, dt)
    s = psd(f)
    s[0] = 0.0
    amp = np.sqrt(2.0 * s * f[1])
    phase = np.random.default_rng(seed).uniform(0.0, 2.0 * np.pi, (nrec, f.size))
    x = np.fft.irfft(amp * np.exp(1j * phase) * n / 2.0, n=n, axis=-1)
    m0 = np.trapezoid(s, f)
    m2 = np.trapezoid(f**2 * s, f)
    return x, m0, m2


@pytest.mark.parametrize(
    "psd",
    [
        # wave-frequency response, bandwidth 0.2 (Gaussian spectrum at 0.1 Hz)
        lambda f: np.exp(-0.5 * ((f - 0.1) / 0.02) ** 2) / (0.02 * np.sqrt(2 * np.pi)),
        # broad Pierson-Moskowitz shape, Tp 10 s
        lambda f: np.where(f > 0, f**-5.0 * np.exp(-1.25 * (0.1 / np.maximum(f, 1e-9)) ** 4), 0.0),
    ],
)
def test_gev_mpm_gaussian_process_closed_form(psd):
    """One-hour records of a zero-mean Gaussian process: the most probable 1-h maximum is
    sqrt(m0) sqrt(2 ln(nu0 T)) (Davenport 1964; nu0 = sqrt(m2/m0) the up-crossing rate).
    Mean over 120 records (dt 0.1 s, blocks 60 s) within 3 %."""
    with np.errstate(divide="ignore", invalid="ignore"):
        x, m0, m2 = _gaussian_records(psd, 36_000 * 4, 0.1, 30, seed=2)
    x = x.reshape(120, 36_000)
    mpm, corr = gev_mpm(x, 0.1, block=60.0)
    closed = math.sqrt(m0) * math.sqrt(2.0 * math.log(math.sqrt(m2 / m0) * 3600.0))
    assert np.mean(mpm) == pytest.approx(closed, rel=0.03)
    assert 0.97 < np.median(corr) <= 1.0


def test_fit_correlation_detects_a_bad_fit():
    """A bimodal sample of maxima is poorly described by one GEV: correlation drops."""
    rng = np.random.default_rng(5)
    good = sps.genextreme.rvs(0.1, loc=0.0, scale=1.0, size=60, random_state=rng)
    bad = np.concatenate([rng.normal(0.0, 0.05, 30), rng.normal(10.0, 0.05, 30)])
    c_good = fit_correlation(good, gev_fit_lmoments(good))
    c_bad = fit_correlation(bad, gev_fit_lmoments(bad))
    assert c_good > 0.98 and c_bad < c_good - 0.02
    assert np.isnan(fit_correlation(np.ones(10), gev_fit_lmoments(np.ones(10))))
    pp = plotting_positions(4)
    assert pp == pytest.approx((np.arange(1, 5) - 0.44) / 4.12)


def test_block_maxima_and_errors():
    x = np.arange(23.0).reshape(1, 23)
    assert block_maxima(x, 0.5, 2.0).tolist() == [[3.0, 7.0, 11.0, 15.0, 19.0]]
    with pytest.raises(ValueError, match="at least 5"):
        block_maxima(x, 0.5, 3.0)
    with pytest.raises(ValueError, match="shorter than two samples"):
        block_maxima(x, 0.5, 0.5)
    y = np.arange(30.0)
    y[12] = np.nan
    with pytest.raises(ValueError, match=r"index \(12,\)"):
        gev_mpm(y, 1.0, block=5.0)


def test_constant_record_gives_its_value():
    mpm, corr = gev_mpm(np.full((2, 100), 4.0), 1.0, block=10.0)
    assert mpm.tolist() == [4.0, 4.0] and np.all(np.isnan(corr))


def test_percentiles_shapes_and_values():
    x = np.arange(101.0)[None, None, :] * np.array([1.0, 2.0])[:, None, None]
    p = percentiles(x, [90, 95, 99])
    assert p.shape == (2, 1, 3)
    assert p[0, 0].tolist() == [90.0, 95.0, 99.0] and p[1, 0].tolist() == [180.0, 190.0, 198.0]
    assert percentiles(x, 50).shape == (2, 1)
    assert float(percentiles(np.array([0.0, 10.0]), 25)) == 2.5
    with pytest.raises(ValueError, match=r"\[0, 100\]"):
        percentiles(x, 101)
