"""Thrust from the Ct table, shutdown/startup ramps and the pitch-band notch filter."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import scipy.signal

from moorlife.io import read_yaml
from moorlife.turbine import (
    ct_table,
    discretise,
    filter_response,
    filter_signal,
    notch_filter,
    relative_wind,
    thrust,
    thrust_coefficient,
)

ROOT = Path(__file__).resolve().parents[1]
AREA = np.pi * 63.0**2

# Published thrust (kN) of NREL/turbine-models@be1ca72e Offshore/NREL_5MW_126_RWT.csv,
# the table chosen in config/platform.yaml (its Ct column is derived from these).
PUBLISHED_KN = {
    3: 171.7,
    5: 268.9,
    8: 478.0,
    10: 691.496,
    11.3: 819.271,
    11.4: 805.112,
    12: 689.957,
    15: 520.5,
    20: 418.8,
    25: 369.3,
}


@pytest.fixture(scope="module")
def table():
    return ct_table(read_yaml(ROOT / "config/platform.yaml")["turbine"])


def test_thrust_matches_published_table(table):
    ws, ct = table
    v = np.array(list(PUBLISHED_KN))
    got = thrust(v, ws, ct, rho_air=1.225, rotor_area=AREA) / 1e3
    np.testing.assert_allclose(got, list(PUBLISHED_KN.values()), rtol=2e-3)
    # peak near rated (11.3 m/s), not at cut-out: the property mooring fatigue depends on
    vv = np.linspace(3, 25, 2201)
    assert abs(vv[np.argmax(thrust(vv, ws, ct))] - 11.3) < 0.05


def test_shutdown_and_startup_ramps(table):
    ws, ct = table
    t25 = thrust(25.0, ws, ct)
    t3 = thrust(3.0, ws, ct)
    np.testing.assert_allclose(thrust([25.25, 25.5, 25.75], ws, ct), t25 * np.array([0.75, 0.5, 0.25]), rtol=1e-12)
    assert thrust(26.0, ws, ct) == 0.0 and thrust(30.0, ws, ct) == 0.0
    np.testing.assert_allclose(thrust(2.5, ws, ct), 0.5 * t3, rtol=1e-12)
    assert thrust(2.0, ws, ct) == 0.0 and thrust(-3.0, ws, ct) == 0.0
    # continuity at cut-out (no jump other than the ramp start)
    assert abs(thrust(25.0 + 1e-9, ws, ct) - t25) < 1e-3 * t25


def test_thrust_coefficient_interpolates(table):
    ws, ct = table
    np.testing.assert_allclose(thrust_coefficient([10.05], ws, ct), [0.5 * (0.905425262 + 0.902755344)])


def test_ct_table_errors():
    with pytest.raises(ValueError, match=r"p\.yaml: turbine\.ct_table\.ct\[1\] = -0\.5"):
        ct_table({"ct_table": {"wind_speed": [3, 4, 5], "ct": [1.0, -0.5, 0.3]}}, "p.yaml")
    with pytest.raises(ValueError, match=r"wind_speed must increase; row 2 = 4"):
        ct_table({"ct_table": {"wind_speed": [3, 5, 4], "ct": [1.0, 0.5, 0.3]}}, "p.yaml")
    with pytest.raises(ValueError, match="equal-length"):
        ct_table({"ct_table": {"wind_speed": [3, 4], "ct": [1.0]}}, "p.yaml")


def test_notch_response_closed_form():
    w0, q = 0.234, 1.5
    f = notch_filter(w0, q)
    assert abs(filter_response(f, w0)[0]) < 1e-12
    np.testing.assert_allclose(abs(filter_response(f, [1e-6, 1e3])), [1.0, 1.0], atol=1e-3)
    # -3 dB edges of a band of width w0/Q around w0
    half = w0 / (2 * q)
    edges = np.sqrt(w0**2 + half**2) + np.array([-half, half])
    np.testing.assert_allclose(abs(filter_response(f, edges)), 1 / np.sqrt(2), rtol=1e-9)
    # peer: scipy's transfer function of the same (A, B, C, D)
    num, den = scipy.signal.ss2tf(f.A, f.B[:, None], f.C[None, :], [[f.D]])
    np.testing.assert_allclose(num[0], [1.0, 0.0, w0**2], atol=1e-12)
    np.testing.assert_allclose(den, [1.0, w0 / q, w0**2], atol=1e-12)


def test_filter_steps_match_scipy_and_remove_band():
    w0, dt = 0.234, 0.05
    f = notch_filter(w0, 1.0)
    t = np.arange(0, 600, dt)
    u = 11.0 + np.sin(w0 * t) + 0.5 * np.sin(10 * w0 * t)
    y = filter_signal(f, u, dt)
    _, y_ref, _ = scipy.signal.lsim(
        (f.A, f.B[:, None], f.C[None, :], [[f.D]]), u, t, X0=np.linalg.solve(-f.A, f.B * u[0]), interp=False
    )
    np.testing.assert_allclose(y, y_ref, atol=1e-9)
    tail = t > 300
    resid = y[tail] - 11.0 - 0.5 * np.sin(10 * w0 * t[tail])
    assert np.max(np.abs(resid)) < 0.08  # the pitch-band sine (amplitude 1) is removed
    assert abs(np.mean(y[tail]) - 11.0) < 0.01  # mean wind kept
    Ad, Bd = discretise(f, dt)
    assert np.all(np.abs(np.linalg.eigvals(Ad)) < 1)


def test_relative_wind():
    d = np.array([1.0, 0.0])  # wind blowing east
    np.testing.assert_allclose(relative_wind(12.0, [0.5, 3.0, 0.0], d), 11.5)
    np.testing.assert_allclose(relative_wind([12.0, 10.0], [[1.0, 0, 0], [-1.0, 0, 0]], d), [11.0, 11.0])
