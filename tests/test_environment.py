"""Tests of moorlife.environment: spectra (closed forms), synthesis, seeding."""

from __future__ import annotations

import numpy as np
import pytest

from moorlife import environment as env


def test_dnv_gamma_rule_branches():
    # DNV-RP-C205 3.5.5.5: phi = Tp/sqrt(Hs); 5 below 3.6, 1 above 5, exp(5.75 - 1.15 phi) between
    hs = np.array([4.0, 4.0, 1.0, 4.0])
    tp = np.array([7.0, 8.4, 10.0, 12.0])  # phi = 3.5, 4.2, 10, 6
    g = env.dnv_gamma(hs, tp)
    np.testing.assert_allclose(g, [5.0, np.exp(5.75 - 1.15 * 4.2), 1.0, 1.0])
    # continuity at the breakpoints (within the rule's published rounding)
    assert abs(np.exp(5.75 - 1.15 * 3.6) - 5.0) < 0.1
    assert abs(np.exp(5.75 - 1.15 * 5.0) - 1.0) < 1e-12


def test_resolve_gamma_rejects_bad_values():
    with pytest.raises(ValueError, match="simulation.gamma"):
        env.resolve_gamma("goda", [1.0], [8.0])
    with pytest.raises(ValueError, match=">= 1"):
        env.resolve_gamma(0.5, [1.0], [8.0])
    np.testing.assert_array_equal(env.resolve_gamma(3.3, [1.0, 2.0], [8.0, 9.0]), [3.3, 3.3])


@pytest.mark.parametrize("gamma", [1.0, 2.2, 3.3, 5.0])
def test_jonswap_moments_and_peak(gamma):
    w = np.linspace(0.01, 12.0, 120001)
    hs, tp = 3.35, 9.21
    s = env.jonswap(w, hs, tp, gamma)
    m0 = np.trapezoid(s, w)
    # Goda's normalisation keeps 4 sqrt(m0) within ~1 % of Hs for 1 <= gamma <= 7
    assert abs(4 * np.sqrt(m0) / hs - 1) < 0.01
    # the peak sits at 2 pi / Tp
    assert abs(w[np.argmax(s)] - 2 * np.pi / tp) < 2e-3
    if gamma == 1.0:  # Pierson-Moskowitz closed form: m0 = Hs^2/16 exactly
        assert abs(m0 - hs**2 / 16) / (hs**2 / 16) < 1e-4


def test_jonswap_peak_enhancement_ratio():
    # at the peak S_J / S_PM = A_gamma * gamma
    wp = 2 * np.pi / 10.0
    r = env.jonswap([wp], 2.0, 10.0, 3.3)[0] / env.jonswap([wp], 2.0, 10.0, 1.0)[0]
    assert r == pytest.approx((1 - 0.287 * np.log(3.3)) * 3.3, rel=1e-12)


def test_wave_number_dispersion():
    w = np.array([0.05, 0.3, 1.0, 3.0])
    k = env.wave_number(w, 200.0)
    np.testing.assert_allclose(env.G * k * np.tanh(k * 200.0), w**2, rtol=1e-10)
    # deep-water limit
    assert k[-1] == pytest.approx(w[-1] ** 2 / env.G, rel=1e-10)


def test_npd_profile_inversion_and_spectrum_values():
    # DNV-RP-C205 2.3.2.11: U(z) = U0 (1 + C ln(z/10)), C = 0.0573 sqrt(1 + 0.148 U0)
    u0 = 10.0
    uz = u0 * (1 + 0.0573 * np.sqrt(1 + 0.148 * u0) * np.log(9.0))
    assert env.npd_mean_speed_10m(uz, 90.0) == pytest.approx(u0, rel=1e-10)
    # hand value: f = 0.01 Hz, z = 90, U0 = 10: f~ = 172*0.01*9^(2/3), S = 320*9^0.45/(1+f~^0.468)^(5/(3*0.468))
    ft = 172 * 0.01 * 9 ** (2 / 3)
    expect = 320 * 9**0.45 / (1 + ft**0.468) ** (5 / (3 * 0.468))
    assert env.npd_spectrum([0.01], uz, 90.0)[0] == pytest.approx(expect, rel=1e-9)


def test_kaimal_variance_equals_sigma_squared():
    f = np.logspace(-6, 3, 200001)
    s = env.kaimal_spectrum(f, 11.4, 0.1, 340.2)
    var = np.trapezoid(s, f)
    assert var == pytest.approx((0.1 * 11.4) ** 2, rel=0.01)


def test_synthesise_matches_direct_sum():
    grid = env.record_grid(100.0, 20.0, 0.5)
    rng = np.random.default_rng(1)
    idx = np.array([3, 7, 20])
    c = rng.normal(size=3) + 1j * rng.normal(size=3)
    s = env.synthesise(c[None, :], idx, grid)[0]
    t = np.arange(grid.n_steps + 1) * grid.dt
    direct = np.real((c[None, :] * np.exp(-1j * np.outer(t, idx * grid.d_omega))).sum(axis=1))
    np.testing.assert_allclose(s, direct, atol=1e-12)
    a = env.synthesise_complex(c[None, :], idx, grid)[0]
    np.testing.assert_allclose(a.real, direct, atol=1e-12)


def test_record_grid_never_repeats():
    g = env.record_grid(3600.0, 600.0, 0.1)
    assert g.n_steps == 42000
    assert g.n_fft >= g.n_steps + 1 and g.n_fft % 2 == 0
    assert g.d_omega == pytest.approx(2 * np.pi / (g.n_fft * 0.1))
    with pytest.raises(ValueError):
        env.record_grid(3600.0, 600.0, 0.0)


def test_synthesised_waves_have_the_target_hs():
    grid = env.record_grid(3 * 3600.0, 0.0, 0.5)
    ph, _ = env.case_streams(7, "MS1", [0], grid.n_fft // 2 + 1)
    waves = env.wave_components(grid, [2.5], [10.0], [270.0], [3.3], ph, omega_min=0.05, omega_max=3.0)
    eta = env.synthesise(waves.amplitude, waves.index, grid)[0]
    # deterministic amplitudes: the variance over the full FFT period is sum(|A|^2)/2 exactly
    assert np.sum(np.abs(waves.amplitude) ** 2) / 2 == pytest.approx(2.5**2 / 16, rel=0.02)
    assert 4 * eta.std() == pytest.approx(2.5, rel=0.03)
    assert waves.theta[0] == pytest.approx(0.0)  # from the west -> travelling east


def test_wind_series_mean_and_std():
    grid = env.record_grid(3600.0, 0.0, 0.25)
    _, wph = env.case_streams(3, "MS2", [5], grid.n_fft // 2 + 1)
    cfg = {"spectrum": "kaimal", "turbulence_intensity": 0.1, "length_scale": 340.2, "f_max": 2.0}
    u = env.wind_series(grid, [12.0], wph, cfg)[0]
    assert u.mean() == pytest.approx(12.0, abs=0.25)
    assert u.std() == pytest.approx(1.2, rel=0.15)
    steady = env.wind_series(grid, [12.0], wph, {"spectrum": "none"})[0]
    np.testing.assert_allclose(steady, 12.0, atol=1e-12)
    with pytest.raises(ValueError, match="simulation.wind.spectrum"):
        env.wind_series(grid, [12.0], wph, {"spectrum": "davenport"})


def test_case_streams_depend_only_on_seed_system_and_case():
    a_wave, a_wind = env.case_streams(11, "MS3", [4, 9], 100)
    b_wave, b_wind = env.case_streams(11, "MS3", [9], 100)
    np.testing.assert_array_equal(a_wave[1], b_wave[0])
    np.testing.assert_array_equal(a_wind[1], b_wind[0])
    c_wave, _ = env.case_streams(11, "MS4", [9], 100)
    assert not np.array_equal(c_wave[0], b_wave[0])
    assert not np.array_equal(a_wave[1], a_wind[1])


def test_case_streams_of_bins_are_independent_of_cases():
    """Bin k of the scatter matrix and case k of the selection draw different phases, while the
    case stream keeps its entropy [seed, CRC-32 of the system, id] (the stores already computed
    stay valid)."""
    import zlib

    case_wave, _ = env.case_streams(11, "MS3", [4], 100)
    bin_wave, bin_wind = env.case_streams(11, "MS3", [4], 100, stream="bin")
    assert not np.array_equal(case_wave, bin_wave)
    expected = np.random.default_rng(np.random.SeedSequence([11, zlib.crc32(b"MS3"), 4])).uniform(0.0, 2 * np.pi, 100)
    np.testing.assert_array_equal(case_wave[0], expected)
    again, _ = env.case_streams(11, "MS3", [7, 4], 100, stream="bin")
    np.testing.assert_array_equal(again[1], bin_wave[0])
    # independent draws: the phase differences of bin and case are uniform, not concentrated
    d = np.angle(np.exp(1j * (bin_wave[0] - case_wave[0])))
    assert np.abs(np.exp(1j * d).mean()) < 0.3
