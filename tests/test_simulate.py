"""Tests of moorlife.simulate: closed forms on a synthetic platform, frequency-domain
agreement, static balance, determinism, and (when the hydro fixture exists) the OC4 model."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from scipy.signal import find_peaks

from moorlife import environment as env
from moorlife import simulate as sim

DATA = Path(__file__).parent / "data"

# OC4-like diagonal figures (Robertson et al. 2014, via config/platform.yaml comments):
# mass + low-frequency added mass, hydrostatics with gravity, OC4 mooring stiffness at rest.
M6 = np.diag([1.3473e7 + 6.5e6, 1.3473e7 + 6.5e6, 1.3473e7 + 1.47e7, 1.4e10, 1.4e10, 1.8e10])
K6 = np.diag([0.0, 0.0, 3.82e6, 1.0e9, 1.0e9, 0.0])
KM = np.diag([7.08e4, 7.08e4, 1.91e4, 8.73e7, 8.73e7, 1.17e8])


def synthetic_model(*, radiation=True, strips=False, thrust=False, kind="linear", kernel=False):
    """A 6-DOF platform with one radiation state per DOF: Z(w) = b / (alpha - i w)."""
    om = np.linspace(0.02, 3.0, 150)
    hd = np.deg2rad(np.arange(-180.0, 180.0, 30.0))
    # excitation: surge/sway by heading, heave isotropic, pitch/roll coupled to surge/sway
    amp = 2.0e6 * np.exp(-(((om - 0.6) / 0.5) ** 2))
    exc = np.zeros((om.size, hd.size, 6), dtype=complex)
    exc[:, :, 0] = amp[:, None] * np.cos(hd)[None, :] * np.exp(1j * 0.3)
    exc[:, :, 1] = amp[:, None] * np.sin(hd)[None, :] * np.exp(1j * 0.3)
    exc[:, :, 2] = 1.5 * amp[:, None] * np.exp(-0.4j)
    exc[:, :, 4] = 2.0e7 * amp[:, None] / 2.0e6 * np.cos(hd)[None, :]
    drift = np.zeros((om.size, hd.size, 6))
    drift[:, :, 0] = 2.0e4 * om[:, None] ** 2 * np.cos(hd)[None, :]
    kw = dict(
        mass=M6,
        stiffness=K6,
        omega=om,
        headings=hd,
        excitation=exc,
        drift=drift,
        mooring_kind=kind,
        mooring_stiffness=KM,
        fairleads=np.array([[20.434, 35.393, -14.0], [-40.868, 0.0, -14.0], [20.434, -35.393, -14.0]]),
    )
    alpha = np.array([0.5, 0.5, 1.0, 0.8, 0.8, 0.5])
    beta = np.array([2.0e5, 2.0e5, 1.0e6, 3.0e8, 3.0e8, 1.0e8])
    if radiation and kernel:  # the same memory as a kernel K(t) = beta exp(-alpha t)
        t = np.arange(0.0, 40.0 + 1e-9, 0.05)
        kw.update(
            kernel=beta[None, :] * np.exp(-alpha[None, :] * t[:, None]),
            kernel_pairs=np.stack([np.arange(6), np.arange(6)], axis=1),
            kernel_dt=0.05,
        )
    elif radiation:
        kw.update(rad_a=np.diag(-alpha), rad_b=np.diag(beta), rad_c=np.eye(6))
    if strips:
        kw.update(
            strip_pos=np.array([[0.0, 0.0, -10.0], [-28.87, 0.0, -20.0]]),
            strip_axis=np.array([[0.0, 0.0, 1.0], [0.0, 0.0, 1.0]]),
            strip_cdn=np.array([0.5 * 1025 * 0.6 * 6.5 * 20.0, 0.0]),
            strip_cda=np.array([0.0, 0.5 * 1025 * 9.6 * math.pi * 24**2 / 4]),
        )
    if thrust:
        v = np.linspace(-30.0, 60.0, 901)
        kw.update(thrust_speed=v, thrust_force=0.5 * 1.225 * math.pi * 63**2 * 0.8 * v * np.abs(v))
    return sim.build_model(**kw)


def quiet_forcing(model, grid, nb=1, wind=0.0, wind_dir=270.0):
    n1 = grid.n_steps + 1
    ns = model.strip_pos.shape[0]
    return sim.Forcing(
        grid=grid,
        force=np.zeros((nb, n1, 6)),
        wind=np.full((nb, n1), wind),
        wind_dir=np.tile(
            np.atleast_2d(np.array([math.cos(math.radians(270 - wind_dir)), math.sin(math.radians(270 - wind_dir))])),
            (nb, 1),
        ),
        kin_every=1,
        kinematics=np.zeros((nb, grid.n_steps + 2, 3, ns), np.float32),
    )


def zero_crossing_period(y, dt, cycles=3):
    """Mean period of the first ``cycles`` oscillations of ``y`` (interpolated upward zero crossings)."""
    up = np.flatnonzero((y[:-1] < 0) & (y[1:] >= 0))
    tz = up + (-y[up]) / (y[up + 1] - y[up])
    return np.diff(tz[: cycles + 1]).mean() * dt


def test_undamped_decay_periods_match_closed_form():
    m = synthetic_model(radiation=False)
    grid = env.record_grid(400.0, 0.0, 0.1)
    rec = sim.integrate(m, quiet_forcing(m, grid), transient=0.0, q0=[[4.0, 0, 1.0, 0, 0.05, 0]])
    for d in (0, 2, 4):
        x = rec.motion[0, d]
        pk, _ = find_peaks(x)
        t_num = np.diff(pk).mean() * grid.dt
        t_ref = 2 * math.pi * math.sqrt(M6[d, d] / (K6[d, d] + KM[d, d]))
        assert t_num == pytest.approx(t_ref, rel=0.005)
        # RK4 at dt = 0.1 s keeps the amplitude of an undamped oscillator (no numerical damping)
        assert x[pk].max() == pytest.approx(x[0], rel=0.002)


def test_kernel_and_state_space_memories_agree():
    ss, ker = synthetic_model(), synthetic_model(kernel=True)
    w = np.linspace(0.05, 2.0, 12)
    np.testing.assert_allclose(sim.radiation_impedance(ker, w), sim.radiation_impedance(ss, w), rtol=0.01, atol=1.0)


def test_decay_with_radiation_memory_matches_linear_periods():
    m = synthetic_model()
    t_lin = sim.linear_natural_periods(m)
    grid = env.record_grid(600.0, 0.0, 0.1)
    rec = sim.integrate(m, quiet_forcing(m, grid), transient=0.0, q0=[[4.0, 0, 1.0, 0, 0.05, 0]])
    for d in (0, 2, 4):
        pk, _ = find_peaks(rec.motion[0, d])
        t_num = np.diff(pk[:4]).mean() * grid.dt
        assert t_num == pytest.approx(t_lin[d], rel=0.03)
        assert rec.motion[0, d, pk[-1]] < rec.motion[0, d, 0]  # radiation damps


@pytest.mark.parametrize("kernel", [False, True], ids=["statespace", "convolution"])
def test_regular_wave_matches_frequency_domain_rao(kernel):
    m = synthetic_model(kernel=kernel)
    grid = env.record_grid(600.0, 300.0, 0.1)
    k = int(round(0.7 / grid.d_omega))
    w = k * grid.d_omega
    theta = math.radians(-30.0)
    a = 0.5  # m
    waves = env.WaveComponents(
        index=np.array([k]), omega=np.array([w]), amplitude=np.array([[a + 0j]]), theta=np.array([theta])
    )
    f = sim.build_forcing(
        m, grid, waves, np.zeros((1, grid.n_steps + 1)), np.array([270.0]), kin_every=1, second_order=False
    )
    rec = sim.integrate(m, f, transient=300.0)
    rao = sim.frequency_response(m, [w], theta)[0]
    t = (np.arange(rec.motion.shape[-1]) + grid.n_steps - rec.motion.shape[-1]) * grid.dt
    basis = np.stack([np.cos(w * t), np.sin(w * t)], axis=1)
    for d in (0, 1, 2, 4):
        coef, *_ = np.linalg.lstsq(basis, rec.motion[0, d] - rec.motion[0, d].mean(), rcond=None)
        amp_td = math.hypot(*coef)
        assert amp_td == pytest.approx(abs(rao[d]) * a, rel=0.02), d
        # phase: x(t) = Re(xi a exp(-i w t)) = |xi| a cos(w t - arg xi)
        assert math.atan2(coef[1], coef[0]) == pytest.approx(np.angle(rao[d]), abs=0.03)


def test_steady_thrust_offset_is_static_balance():
    m = synthetic_model(thrust=True)
    grid = env.record_grid(300.0, 900.0, 0.1)
    f = quiet_forcing(m, grid, wind=11.4, wind_dir=270.0)
    # start near equilibrium to shorten the transient; the result must not depend on it
    rec = sim.integrate(m, f, transient=900.0, q0=[[8.0, 0, 0, 0, 0.05, 0]])
    thrust = 0.5 * 1.225 * math.pi * 63**2 * 0.8 * 11.4**2
    load = np.array([thrust, 0, 0, 0, thrust * 90.0, 0])
    q_static = np.linalg.solve(K6 + KM, load)
    np.testing.assert_allclose(rec.motion[0, [0, 4]].mean(axis=-1), q_static[[0, 4]], rtol=0.01)


def test_newman_mean_drift_force():
    m = synthetic_model()
    grid = env.record_grid(1800.0, 0.0, 0.2)
    ph, _ = env.case_streams(1, "MS1", [0], grid.n_fft // 2 + 1)
    waves = env.wave_components(grid, [3.0], [10.0], [270.0], [3.3], ph, omega_min=0.05, omega_max=3.0)
    f1 = sim.build_forcing(
        m, grid, waves, np.zeros((1, grid.n_steps + 1)), np.array([270.0]), kin_every=5, second_order=False
    )
    f2 = sim.build_forcing(m, grid, waves, np.zeros((1, grid.n_steps + 1)), np.array([270.0]), kin_every=5)
    drift = f2.force[0, :, 0] - f1.force[0, :, 0]
    d = 2.0e4 * waves.omega**2  # cos(0) = 1: waves from the west travel along +x
    expect = np.sum(np.abs(waves.amplitude[0]) ** 2 * d)
    n = grid.n_fft  # over the FFT period the slow-drift mean is exact; the record is most of it
    assert drift.mean() == pytest.approx(expect, rel=0.05)
    assert drift.min() >= 0.0  # positive coefficients give a non-negative force
    assert n >= grid.n_steps


def test_strip_drag_damps_heave_motion():
    m0 = synthetic_model(radiation=False)
    m1 = synthetic_model(radiation=False, strips=True)
    grid = env.record_grid(200.0, 0.0, 0.1)
    r0 = sim.integrate(m0, quiet_forcing(m0, grid), transient=0.0, q0=[[0, 0, 2.0, 0, 0, 0]])
    r1 = sim.integrate(m1, quiet_forcing(m1, grid), transient=0.0, q0=[[0, 0, 2.0, 0, 0, 0]])
    assert np.abs(r1.motion[0, 2, -300:]).max() < 0.5 * np.abs(r0.motion[0, 2, -300:]).max()
    # quadratic damping: the decrement per cycle shrinks with amplitude
    pk, _ = find_peaks(r1.motion[0, 2])
    ratios = r1.motion[0, 2, pk[1:]] / r1.motion[0, 2, pk[:-1]]
    assert ratios[-1] > ratios[0]


def test_bad_cases_are_rejected():
    m = synthetic_model()
    cases = {k: np.array([1.0]) for k in ("wind_speed", "wind_dir", "hs", "tp", "wave_dir")}
    cases["tp"] = np.array([-3.0])
    with pytest.raises(ValueError, match=r"case 7: tp = -3.0"):
        sim.simulate_batch(
            cases,
            case_ids=np.array([7]),
            mooring_system="MS1",
            seed=1,
            model_inputs=m,
            sim_cfg={"duration": 60.0, "transient": 0.0},
            fatigue_cfg=None,
            stats_cfg=None,
        )
    del cases["hs"]
    with pytest.raises(ValueError, match="missing"):
        sim.simulate_batch(
            cases,
            case_ids=np.array([7]),
            mooring_system="MS1",
            seed=1,
            model_inputs=m,
            sim_cfg={},
            fatigue_cfg=None,
            stats_cfg=None,
        )


# paper Table 4 (copied from config/mooring_systems.tsv)
ROWS = {
    "MS1": dict(
        mass_kg_per_m=92,
        pretension_kN=811,
        link_diameter_mm=68,
        equivalent_diameter_m=0.1199,
        EA_N=5.43e8,
        MBS_N=5420364,
        chain="studless",
    ),
    "MS3": dict(
        mass_kg_per_m=200,
        pretension_kN=1770,
        link_diameter_mm=100,
        equivalent_diameter_m=0.1763,
        EA_N=1.16e9,
        MBS_N=10944000,
        chain="studless",
    ),
    "MS6": dict(
        mass_kg_per_m=634,
        pretension_kN=5675,
        link_diameter_mm=178,
        equivalent_diameter_m=0.3138,
        EA_N=3.55e9,
        MBS_N=28664642,
        chain="studless",
    ),
}
QS = {"model": "quasistatic"}
SIM = {
    "duration": 240.0,
    "transient": 60.0,
    "dt": 0.1,
    "gamma": "dnv",
    "kinematics_dt": 0.5,
    "wind": {"spectrum": "npd", "f_max": 0.5},
}
STATS = {"block": 20.0, "method": "lmoments"}


def moored(ms, kind="quasistatic"):
    base = synthetic_model(thrust=True, strips=True)
    return sim.attach_mooring(base, {**ROWS[ms], "mooring_system": ms}, {"model": kind})


@pytest.fixture(scope="module")
def ms3():
    return moored("MS3")


def sea(n, **kw):
    base = dict(
        wind_speed=[12.1, 6.0, 18.0],
        wind_dir=[328.0, 90.0, 270.0],
        hs=[3.35, 1.0, 4.0],
        tp=[9.21, 8.0, 11.0],
        wave_dir=[316.0, 300.0, 270.0],
    )
    base.update(kw)
    return {k: np.asarray(v[:n], dtype=float) for k, v in base.items()}


def short_coupled_runs(ms="MS3"):
    """Two states, 60 s records, for each line kind (dynamic, then quasi-static): every kernel of a
    coupled simulation, compiled and run (``tests/test_numba_cache.py``, and the warm-up of the
    tiny study in ``conftest.py``)."""
    cfg = {**SIM, "duration": 60.0, "transient": 10.0}
    return {
        kind: sim.simulate_batch(
            sea(2),
            case_ids=np.array([3, 4]),
            mooring_system=ms,
            seed=5,
            model_inputs=moored(ms, kind),
            sim_cfg=cfg,
            fatigue_cfg={},
            stats_cfg={"block": 10.0, "method": "lmoments"},
        )
        for kind in ("dynamic", "quasistatic")
    }


def test_batch_is_bit_identical_to_single_cases(ms3):
    kw = dict(mooring_system="MS3", seed=5, model_inputs=ms3, sim_cfg=SIM, fatigue_cfg={}, stats_cfg=STATS)
    both = sim.simulate_batch(sea(3), case_ids=np.array([10, 11, 12]), **kw)
    one = sim.simulate_batch({k: v[1:2] for k, v in sea(3).items()}, case_ids=np.array([11]), **kw)
    for name in (*sim.names.SIM_SCALAR_VARS, *sim.names.SIM_LINE_VARS):
        assert name in both and both[name].shape[0] == 3
        np.testing.assert_array_equal(both[name][1:2], one[name], err_msg=name)
    for name in sim.names.GEV_VARS:
        assert f"gev_corr_{name}" in both
    assert both["tension_mpm"].shape == (3, 3)
    assert np.all(both["damage_sn"] > 0) and np.all(both["damage_tn"] > 0)
    # another seed changes the realisation
    other = sim.simulate_batch({k: v[1:2] for k, v in sea(3).items()}, case_ids=np.array([12]), **kw)
    assert other["surge_mpm"][0] != one["surge_mpm"][0]


def test_trim_load_keeps_the_platform_at_rest(ms3):
    grid = env.record_grid(120.0, 0.0, 0.1)
    rec = sim.integrate(ms3, quiet_forcing(ms3, grid), transient=0.0)
    assert np.abs(rec.motion[0, :3]).max() < 0.02  # m
    assert np.abs(rec.motion[0, 3:]).max() < 1e-4  # rad
    # the rest tension is the catenary pretension (paper Table 4: 1770 kN for MS3, within 2 %)
    np.testing.assert_allclose(rec.tension[0, :, -1], 1.770e6, rtol=0.02)


@pytest.mark.slow
def test_heavier_lines_reduce_offsets_and_raise_tensions():
    out = {}
    for ms in ("MS1", "MS3", "MS6"):
        m = moored(ms)
        out[ms] = sim.simulate_batch(
            sea(1, wind_speed=[11.4], wind_dir=[270.0], wave_dir=[270.0]),
            case_ids=np.array([1]),
            mooring_system="ref",
            seed=3,
            model_inputs=m,
            sim_cfg={**SIM, "duration": 300.0, "transient": 300.0},
            fatigue_cfg=None,
            stats_cfg=STATS,
        )
    surge = [out[k]["surge_mean"][0] for k in ("MS1", "MS3", "MS6")]
    ten = [out[k]["tension_mean"][0].max() for k in ("MS1", "MS3", "MS6")]
    assert surge[0] > surge[1] > surge[2] > 0
    assert ten[0] < ten[1] < ten[2]


def test_steady_wind_offset_equals_catenary_static_balance(ms3):
    """Issue 7 point 4: steady 11.4 m/s wind, no waves: the mean offset is the static balance of
    thrust against the (nonlinear, quasi-static) mooring restoring."""
    grid = env.record_grid(200.0, 800.0, 0.1)
    f = quiet_forcing(ms3, grid, wind=11.4, wind_dir=270.0)
    thrust = float(np.interp(11.4, ms3.thrust_speed, ms3.thrust_force))
    load = np.array([thrust, 0, 0, 0, thrust * ms3.hub[2], 0])
    q_st, ten_st = sim.static_equilibrium(ms3, load)
    rec = sim.integrate(ms3, f, transient=800.0, q0=[q_st * 0.9])
    mean = rec.motion[0].mean(axis=-1)
    assert q_st[0] > 5.0  # a real offset (m)
    np.testing.assert_allclose(mean[[0, 4]], q_st[[0, 4]], rtol=0.01)
    np.testing.assert_allclose(rec.tension[0].mean(axis=-1), ten_st, rtol=0.01)
    # the windward line (M2, anchored to the west) holds the platform: it tightens, M1/M3 slacken
    assert ten_st[1] > 1.77e6 > ten_st[0]
    assert ten_st[0] == pytest.approx(ten_st[2], rel=1e-6)


# --------------------------------------------------------------------------------------
# the OC4 model from the coarse Capytaine fixture of moorlife.hydro
# --------------------------------------------------------------------------------------

REPO = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def oc4():
    from moorlife import hydro
    from moorlife.io.platform import open_platform_nc, read_platform_config

    cfg = read_platform_config(REPO / "config/platform.yaml")
    pm = hydro.load_platform_model(open_platform_nc(DATA / "platform_coarse.nc"), cfg)
    return pm, sim.platform_from(pm, cfg, {})


def test_oc4_decay_periods_equal_coupled_eigenperiods(oc4):
    """The integrator reproduces the coupled linear eigenperiods; heave is OC4's 17.3 s."""
    import dataclasses

    pm, plat = oc4
    m = dataclasses.replace(plat, mooring_kind="linear", strip_cdn=plat.strip_cdn * 0, strip_cda=plat.strip_cda * 0)
    t_lin = sim.linear_natural_periods(m)
    for d, x0, dur in ((0, 5.0, 500.0), (2, 1.0, 100.0), (4, 0.03, 150.0)):
        grid = env.record_grid(dur, 0.0, 0.1)
        q0 = np.zeros((1, 6))
        q0[0, d] = x0
        rec = sim.integrate(m, quiet_forcing(m, grid), transient=0.0, q0=q0)
        assert zero_crossing_period(rec.motion[0, d], grid.dt) == pytest.approx(t_lin[d], rel=0.01), d
    assert t_lin[2] == pytest.approx(17.3, rel=0.05)  # OC4 heave (Robertson et al. 2014)
    # the convolution memory reproduces the BEM added mass and damping
    w = pm.omega[(pm.omega > 0.2) & (pm.omega < 2.0)]
    z = sim.radiation_impedance(plat, w)
    a_model = plat.mass[2, 2] - np.asarray(pm.mass)[2, 2] - z[:, 2, 2].imag / w
    idx = np.searchsorted(pm.omega, w)
    np.testing.assert_allclose(a_model, pm.added_mass[idx, 2, 2], rtol=0.01)
    np.testing.assert_allclose(z[:, 2, 2].real, pm.damping[idx, 2, 2], rtol=0.02, atol=0.01 * pm.damping[:, 2, 2].max())


def test_decay_without_memory_gives_the_oc4_one_dof_periods(oc4):
    """In the convention of the OC4 figures (constant A_inf, one DOF at a time) the decays give
    OC4's 107.5 / 17.3 / 26.8 s within 5 % even on the coarse fixture; the radiation memory
    lengthens surge by the A(w_n) - A_inf of the BEM (over 4 %), heave and pitch far less."""
    import dataclasses

    _, plat = oc4
    m = dataclasses.replace(plat, mooring_kind="linear", strip_cdn=plat.strip_cdn * 0, strip_cda=plat.strip_cda * 0)
    flat = sim.without_radiation_memory(m)
    assert np.all(sim.radiation_impedance(flat, np.array([0.05, 0.5, 2.0])) == 0.0)
    np.testing.assert_array_equal(flat.mass, m.mass)
    for d, x0, dur, oc4_period in ((0, 5.0, 450.0, 107.5), (2, 1.0, 70.0, 17.3), (4, 0.03, 110.0, 26.8)):
        held = tuple(i for i in range(6) if i != d)
        t_flat = sim.linear_natural_periods(flat, locked=held)[d]
        t_mem = sim.linear_natural_periods(m, locked=held)[d]
        assert t_flat == pytest.approx(
            2 * math.pi * math.sqrt(m.mass[d, d] / (m.stiffness + m.mooring_stiffness)[d, d])
        )
        grid = env.record_grid(dur, 0.0, 0.1)
        q0 = np.zeros((1, 6))
        q0[0, d] = x0
        rec = sim.integrate(flat, quiet_forcing(flat, grid), transient=0.0, q0=q0, locked=held)
        t_dec = zero_crossing_period(rec.motion[0, d], grid.dt)
        assert t_dec == pytest.approx(t_flat, rel=0.005), d
        assert t_dec == pytest.approx(oc4_period, rel=0.05), d
        assert t_mem / t_flat - 1 > (0.04 if d == 0 else 0.0), d
        assert t_mem / t_flat - 1 < (0.08 if d == 0 else 0.02), d


def test_locked_dofs_hold_and_give_the_one_dof_periods(oc4):
    """A pitch decay with every other DOF held reproduces the eigenperiod of the pitch block
    alone (OC4's one-DOF 26.8 s within 5 %); the held DOFs do not move even in waves."""
    import dataclasses

    _, plat = oc4
    m = dataclasses.replace(plat, mooring_kind="linear", strip_cdn=plat.strip_cdn * 0, strip_cda=plat.strip_cda * 0)
    held = (0, 1, 2, 3, 5)
    t_one = sim.linear_natural_periods(m, locked=held)
    t_all = sim.linear_natural_periods(m)
    assert np.isinf(t_one[list(held)]).all()
    assert t_one[4] > 1.04 * t_all[4]  # the surge-pitch coupling shortens the free pitch mode
    assert t_one[4] == pytest.approx(26.8, rel=0.05)
    grid = env.record_grid(150.0, 0.0, 0.1)
    q0 = np.array([[1.0, 0, 0, 0, 0.03, 0]])
    rec = sim.integrate(m, quiet_forcing(m, grid), transient=0.0, q0=q0, locked=held)
    y = rec.motion[0, 4]
    assert zero_crossing_period(y, grid.dt) == pytest.approx(t_one[4], rel=0.01)
    np.testing.assert_array_equal(rec.motion[0, held], np.broadcast_to(q0[0, list(held)][:, None], (5, y.size)))
    waves = env.wave_components(
        grid,
        np.array([4.0]),
        np.array([9.0]),
        np.array([300.0]),
        np.array([3.3]),
        env.case_streams(1, "MS1", [0], grid.n_fft // 2 + 1)[0],
        omega_min=float(m.omega.min()),
        omega_max=float(m.omega.max()),
    )
    f = sim.build_forcing(
        m, grid, waves, np.zeros((1, grid.n_steps + 1)), np.array([270.0]), kin_every=1, second_order=True
    )
    rec = sim.integrate(m, f, transient=0.0, locked=(0, 1, 5))
    assert np.all(rec.motion[0, [0, 1, 5]] == 0.0) and np.ptp(rec.motion[0, 2]) > 0.1
    with pytest.raises(ValueError, match="locked DOFs"):
        sim.integrate(m, f, transient=0.0, locked=range(6))
    with pytest.raises(ValueError, match="v0 must be 0"):
        sim.integrate(m, f, transient=0.0, v0=[[0.1, 0, 0, 0, 0, 0]], locked=(0,))


@pytest.mark.slow
def test_simulate_store_end_to_end(oc4, tmp_path):
    """Rule adapter path: cases.zarr -> map_cases (Dask) -> complete simulations.zarr."""
    import xarray as xr

    from moorlife.io import open_zarr, write_zarr
    from moorlife.stages import simulate as stage

    cases = xr.Dataset(
        {k: ("case", np.asarray(v, dtype=float)) for k, v in sea(3).items()}
        | {"hindcast_index": ("case", np.arange(3)), "role": ("case", np.array(["train", "train", "validate"]))},
        coords={"case": np.arange(3)},
    )
    write_zarr(cases, tmp_path / "results/selection/cases.zarr")
    out = tmp_path / "results/MS3/simulations.zarr"
    ds = stage.run(
        cases=tmp_path / "results/selection/cases.zarr",
        platform=DATA / "platform_coarse.nc",
        platform_cfg=REPO / "config/platform.yaml",
        store=out,
        dim="case",
        ms="MS3",
        row=ROWS["MS3"],
        seed=7,
        simulation={**SIM, "duration": 120.0, "transient": 30.0},
        mooring=QS,
        fatigue={},
        statistics=STATS,
        batch_size=2,
        threads=1,
    )
    back = open_zarr(out)
    for name in (*sim.names.SIM_SCALAR_VARS, *sim.names.SIM_LINE_VARS, "tension_mean", "hs", "role"):
        assert name in back, name
    assert back["tension_mpm"].dims == ("case", "line")
    assert back["tension_mean"].attrs["units"] == "N"
    assert np.all(np.isfinite(back["damage_sn"].values))
    np.testing.assert_array_equal(back["surge_mpm"].values, ds["surge_mpm"].values)


def test_keep_timeseries_returns_the_records(ms3):
    out = sim.simulate_batch(
        sea(2),
        case_ids=np.array([3, 4]),
        mooring_system="MS3",
        seed=5,
        model_inputs=ms3,
        sim_cfg={**SIM, "keep_timeseries": True, "duration": 120.0},
        fatigue_cfg=None,
        stats_cfg=STATS,
    )
    nt = int(round(120.0 / 0.1))
    assert out["ts_surge"].shape == (2, nt) and out["ts_surge"].dtype == np.float32
    assert out["ts_tension"].shape == (2, 3, nt)
    np.testing.assert_allclose(out["ts_tension"].max(axis=-1), out["tension_max"], rtol=1e-6)
    assert "damage_sn" not in out  # fatigue_cfg=None skips the damage
    assert sim.output_attrs("ts_pitch")["units"] == "rad"
    # one attribute registry (moorlife.names) covers every output, with units
    assert set(out) <= set(sim.names.SIM_OUTPUT_ATTRS)
    assert all(
        sim.output_attrs(name) == sim.names.SIM_OUTPUT_ATTRS[name] and "units" in sim.output_attrs(name) for name in out
    )
    with pytest.raises(KeyError):
        sim.output_attrs("ts_unknown")


@pytest.mark.parametrize("kin_every", [1, 2, 3])
def test_drag_kinematics_match_linear_wave_theory(kin_every):
    """Strip velocities of build_forcing = direct sum of Airy components (finite depth)."""
    m = synthetic_model(strips=True)
    grid = env.record_grid(200.0, 0.0, 0.1)
    rng = np.random.default_rng(3)
    idx = np.array([40, 75, 130])
    amp = (rng.normal(size=3) + 1j * rng.normal(size=3))[None, :] * 0.5
    w = idx * grid.d_omega
    theta = 0.4
    waves = env.WaveComponents(index=idx, omega=w, amplitude=amp, theta=np.array([theta]))
    f = sim.build_forcing(
        m, grid, waves, np.zeros((1, grid.n_steps + 1)), np.array([270.0]), kin_every=kin_every, second_order=False
    )
    k = env.wave_number(w, 200.0)
    t = np.arange(f.kinematics.shape[1]) * kin_every * grid.dt
    for s_, p in enumerate(m.strip_pos):
        ph = amp[0][None, :] * np.exp(
            1j * (k * (p[0] * np.cos(theta) + p[1] * np.sin(theta)))[None, :] - 1j * np.outer(t, w)
        )
        uh = np.real(ph * (w * np.cosh(k * (p[2] + 200.0)) / np.sinh(k * 200.0))[None, :]).sum(axis=1)
        uz = np.real(-1j * ph * (w * np.sinh(k * (p[2] + 200.0)) / np.sinh(k * 200.0))[None, :]).sum(axis=1)
        np.testing.assert_allclose(f.kinematics[0, :, 0, s_], uh * np.cos(theta), atol=2e-5)
        np.testing.assert_allclose(f.kinematics[0, :, 1, s_], uh * np.sin(theta), atol=2e-5)
        np.testing.assert_allclose(f.kinematics[0, :, 2, s_], uz, atol=2e-5)


def test_thrust_ramps_to_zero_above_cut_out(ms3):
    """Steady wind above cut-out + ramp (26 m/s): no thrust, the platform stays at its trim;
    the wind direction sets the offset direction (nacelle aligned with the wind)."""
    import dataclasses

    from moorlife import turbine

    v = np.arange(-40.0, 80.0, 0.02)
    ms3 = dataclasses.replace(
        ms3, thrust_speed=v, thrust_force=turbine.thrust(v, np.array([3.0, 11.4, 25.0]), np.array([0.8, 0.8, 0.08]))
    )
    calm = dict(hs=[0.0], tp=[8.0], wave_dir=[270.0])
    cfg = {**SIM, "wind": {"spectrum": "none"}, "duration": 120.0, "transient": 60.0}
    kw = dict(
        case_ids=np.array([1]),
        mooring_system="MS3",
        seed=1,
        model_inputs=ms3,
        sim_cfg=cfg,
        fatigue_cfg=None,
        stats_cfg=STATS,
    )
    off = sim.simulate_batch(sea(1, wind_speed=[30.0], wind_dir=[270.0], **calm), **kw)
    assert abs(off["surge_mean"][0]) < 0.05
    on = sim.simulate_batch(sea(1, wind_speed=[11.4], wind_dir=[0.0], **calm), **kw)
    assert on["sway_mean"][0] < -3.0  # wind from the north pushes the platform south
    assert abs(on["surge_mean"][0]) < 0.25 * abs(on["sway_mean"][0])  # the spread is not symmetric about y


@pytest.mark.parametrize("kind", ["quasistatic", "dynamic"])
def test_compiled_record_loop_equals_the_per_step_loop(kind, monkeypatch):
    """The one-call compiled loop (no per-step dispatch) gives the per-step loop's record bit for bit."""
    model = moored("MS1", kind)
    records, used = [], []
    from moorlife.simulate import batch, integration

    real_integrate, real_compiled = sim.integrate, sim._run_compiled

    def spy_integrate(*a, **k):
        records.append(real_integrate(*a, **k))
        return records[-1]

    def spy_compiled(*a, **k):
        used.append(real_compiled(*a, **k))
        return used[-1]

    monkeypatch.setattr(batch, "integrate", spy_integrate)
    monkeypatch.setattr(integration, "_run_compiled", spy_compiled)
    kw = dict(
        case_ids=np.array([3, 4]),
        mooring_system="MS1",
        seed=7,
        model_inputs=model,
        sim_cfg={**SIM, "duration": 150.0, "transient": 30.0},
        fatigue_cfg={},
        stats_cfg=STATS,
    )
    fast = sim.simulate_batch(sea(2), **kw)
    monkeypatch.setattr(integration, "_run_compiled", lambda *a, **k: False)
    slow = sim.simulate_batch(sea(2), **kw)
    assert used == [True] and len(records) == 2
    for field in ("motion", "accel", "tension"):
        a, b = getattr(records[0], field), getattr(records[1], field)
        assert np.isfinite(a).all() and np.ptp(a[:, 0]) > 0, field
        np.testing.assert_array_equal(a, b, err_msg=field)
    for name in fast:
        np.testing.assert_array_equal(fast[name], slow[name], err_msg=name)


# --------------------------------------------------------------------------------------
# the start of a record: the mean equilibrium (issue 23, target 2)
# --------------------------------------------------------------------------------------


def _independent_static_solve(model, load):
    """The static balance by scipy's root finder on the mooring package's own kinematics and loads."""
    from scipy.optimize import root

    from moorlife import mooring as moor

    props, layout, cfg, _ = model.mooring_args
    lines = moor.make_mooring("quasistatic", props, layout, cfg, batch=1)

    def residual(q):
        r, _ = moor.fairlead_kinematics(layout, q[None], np.zeros((1, 6)))
        f = np.array(lines.forces(lines.init(r)))
        return load + model.static_load + moor.mooring_loads(f, r, q[None, :3])[0] - model.stiffness @ q

    sol = root(residual, np.zeros(6), method="hybr", options={"xtol": 1e-12})
    assert sol.success
    return sol.x


def test_mean_load_is_the_thrust_and_the_mean_wave_force(ms3):
    grid = env.record_grid(100.0, 0.0, 0.1)
    f = quiet_forcing(ms3, grid, nb=2, wind=11.4, wind_dir=300.0)
    f.force[1, :, :] = np.arange(6.0) * 1e4 + np.sin(np.arange(grid.n_steps + 1))[:, None]  # a mean and a wiggle
    load = sim.mean_load(ms3, f)
    thrust = float(np.interp(11.4, ms3.thrust_speed, ms3.thrust_force))
    e = f.wind_dir[0]
    hub = ms3.hub
    expect = np.array([thrust * e[0], thrust * e[1], 0.0, -hub[2] * thrust * e[1], hub[2] * thrust * e[0], 0.0])
    expect[5] = hub[0] * thrust * e[1] - hub[1] * thrust * e[0]
    np.testing.assert_allclose(load[0], expect, rtol=1e-12, atol=1e-6)
    np.testing.assert_allclose(load[1] - load[0], f.force[1].mean(axis=0), rtol=1e-12, atol=1e-6)


def test_mean_offset_matches_a_separate_static_solve(ms3):
    """The start's offset is the static balance of its mean load, found here by another solver."""
    grid = env.record_grid(100.0, 0.0, 0.1)
    f = quiet_forcing(ms3, grid, wind=11.4, wind_dir=300.0)
    eq = sim.mean_equilibrium(ms3, f)
    q_ref = _independent_static_solve(ms3, sim.mean_load(ms3, f)[0])
    assert np.hypot(q_ref[0], q_ref[1]) > 5.0  # a real offset (m), off the axes (wind from 300 deg)
    np.testing.assert_allclose(eq.displacement[0, :3], q_ref[:3], atol=1e-6)
    np.testing.assert_allclose(eq.displacement[0, 3:], q_ref[3:], atol=1e-9)
    np.testing.assert_allclose(eq.residual[0], 0.0, atol=1e-3)
    q_one, ten = sim.static_equilibrium(ms3, sim.mean_load(ms3, f)[0])
    np.testing.assert_array_equal(q_one, eq.displacement[0])
    np.testing.assert_array_equal(ten, eq.tension[0])


@pytest.mark.parametrize("kind", ["quasistatic", "dynamic"])
def test_equilibrium_start_stays_put_without_waves(kind):
    """Steady wind, no waves: the platform started at its mean equilibrium does not move, and
    the rest start of the same record swings by metres (what the transient used to discard)."""
    model = moored("MS1", kind)
    grid = env.record_grid(150.0, 0.0, 0.1)
    f = quiet_forcing(model, grid, wind=11.4, wind_dir=300.0)
    start = sim.equilibrium_start(model, f)
    q0 = start.displacement.copy()
    rec = sim.integrate(model, f, transient=0.0, start=start)
    np.testing.assert_array_equal(start.displacement, q0)  # the caller's start is not modified
    drift = np.abs(rec.motion[0] - q0[0][:, None]).max(axis=-1)
    tol = (1e-9, 1e-11) if kind == "quasistatic" else (5e-3, 1e-5)  # m, rad
    assert drift[:3].max() < tol[0] and drift[3:].max() < tol[1], drift
    ten = rec.tension[0]
    assert np.ptp(ten, axis=-1).max() < (1e-3 if kind == "quasistatic" else 1e-3 * ten.mean())
    rest = sim.integrate(model, f, transient=0.0)
    assert np.abs(rest.motion[0, :2] - q0[0, :2, None]).max() > 3.0


def test_dynamic_lines_start_on_the_static_catenary_at_the_offset():
    from moorlife import mooring as moor
    from moorlife.mooring.quasistatic import catenary_profile

    model = moored("MS1", "dynamic")
    grid = env.record_grid(50.0, 0.0, 0.1)
    f = quiet_forcing(model, grid, wind=11.4, wind_dir=300.0)
    eq = sim.mean_equilibrium(model, f, check=True)
    start = sim.equilibrium_start(model, f)
    np.testing.assert_array_equal(start.displacement, eq.displacement)
    assert np.abs(eq.residual[0, :3]).max() < 200.0  # N, against a thrust of about 750 kN
    props, layout, cfg, proto = model.mooring_args
    r_f, _ = moor.fairlead_kinematics(layout, eq.displacement, np.zeros((1, 6)))
    lines = moor.DynamicMooring(proto.model, props, layout, proto.settings, 1)
    nodes = lines.init(r_f).r[0]  # (L, N + 1, 3)
    for k in range(3):
        d = r_f[0, k] - layout.anchors[k]
        span = float(np.hypot(d[0], d[1]))
        h, v = moor.catenary_solve(span, float(d[2]), layout.length, props.EA, props.wet_weight)
        s = np.linspace(0.0, layout.length, nodes.shape[1])
        prof = catenary_profile(s, h, v, layout.length, props.EA, props.wet_weight)
        along = (nodes[k, :, :2] - layout.anchors[k, :2]) @ (d[:2] / span)
        # node by node on the catenary (the lumped-mass seabed springs and segments: decimetres)
        np.testing.assert_allclose(along, prof[:, 0], atol=0.5)
        np.testing.assert_allclose(nodes[k, :, 2] - layout.anchors[k, 2], prof[:, 1], atol=0.5)
    rec = sim.integrate(model, f, transient=0.0, start=start)
    np.testing.assert_allclose(rec.tension[0, :, 0], eq.tension[0], rtol=5e-3)  # t = 0: the catenary's


def test_equilibrium_start_keeps_batches_bit_identical_with_dynamic_lines():
    model = moored("MS1", "dynamic")
    kw = dict(
        mooring_system="MS1",
        seed=5,
        model_inputs=model,
        sim_cfg={**SIM, "duration": 120.0},
        fatigue_cfg={},
        stats_cfg=STATS,
    )
    both = sim.simulate_batch(sea(2), case_ids=np.array([10, 11]), **kw)
    one = sim.simulate_batch({k: v[1:2] for k, v in sea(2).items()}, case_ids=np.array([11]), **kw)
    for name in both:
        np.testing.assert_array_equal(both[name][1:2], one[name], err_msg=name)


def test_forcing_from_is_the_same_realisation_later():
    m = synthetic_model(strips=True)
    grid = env.record_grid(100.0, 20.0, 0.1)
    ph, wph = env.case_streams(1, "MS1", [0], grid.n_fft // 2 + 1)
    waves = env.wave_components(grid, [2.0], [9.0], [270.0], [3.3], ph, omega_min=0.05, omega_max=3.0)
    wind = env.wind_series(grid, [10.0], wph, {"spectrum": "npd", "height": 90.0, "f_max": 0.5})
    f = sim.build_forcing(m, grid, waves, wind, np.array([270.0]), kin_every=2)
    g = sim.forcing_from(f, 200)
    assert g.grid.n_steps == grid.n_steps - 200 and g.grid.n_fft == grid.n_fft
    np.testing.assert_array_equal(g.force, f.force[:, 200:])
    np.testing.assert_array_equal(g.wind, f.wind[:, 200:])
    np.testing.assert_array_equal(g.kinematics, f.kinematics[:, 100:])
    assert g.kinematics.shape[1] == g.grid.n_steps // 2 + 2
    with pytest.raises(ValueError, match="multiple of kin_every"):
        sim.forcing_from(f, 201)


def test_short_transient_from_equilibrium_gives_the_long_transient_statistics(ms3):
    """Paired (one realisation, one kept window): 100 s from the mean equilibrium against 600 s
    from rest; the rest start with 100 s is the control that shows the transient is there."""
    from moorlife.settings import SimulationSettings, StatisticsSettings

    sea1 = sea(1, wind_speed=[12.0], wind_dir=[300.0], hs=[3.0], tp=[10.0], wave_dir=[280.0])
    s = SimulationSettings.from_config({**SIM, "duration": 400.0, "transient": 600.0})
    f = sim.batch_forcing(sea1, case_ids=np.array([1]), mooring_system="MS3", seed=2, model=ms3, settings=s)
    late = sim.forcing_from(f, 5000)

    def stats(rec):
        out = sim.summarise(
            rec,
            line_info=ms3.line_info,
            fatigue_cfg={},
            statistics=StatisticsSettings.from_config(STATS),
            mpm_duration=3600.0,
        )
        return {k: float(np.max(v)) for k, v in out.items() if not k.startswith("gev_corr")}

    long = stats(sim.integrate(ms3, f, transient=600.0))
    short = stats(sim.integrate(ms3, late, transient=100.0, start=sim.equilibrium_start(ms3, late)))
    control = stats(sim.integrate(ms3, late, transient=100.0))
    assert long["surge_mean"] > 3.0
    for key in ("surge_mean", "sway_mean", "surge_std", "surge_mpm", "tension_mean", "tension_std", "tension_mpm"):
        assert short[key] == pytest.approx(long[key], rel=0.02), key
    assert short["damage_sn"] == pytest.approx(long["damage_sn"], rel=0.05)
    worst = max(abs(control[k] / long[k] - 1) for k in ("surge_std", "tension_std", "damage_sn"))
    assert worst > 0.05  # without the equilibrium start, 100 s is not enough
