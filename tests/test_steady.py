"""Tests of moorlife.simulate.steady: the start at the linear periodic steady state."""

from __future__ import annotations

import math

import numpy as np
import pytest
from test_simulate import SIM, STATS, moored, sea, synthetic_model

from moorlife import environment as env
from moorlife import simulate as sim
from moorlife.simulate.batch import batch_forcing, period_grid, record_part
from moorlife.simulate.steady import drag_linearisation, linear_stiffness, periodic_response


def _linear_forcing(m, rec_grid):
    """Irregular waves with slow drift on one whole period of ``rec_grid``'s synthesis, no wind."""
    grid = period_grid(rec_grid)
    ph, _ = env.case_streams(3, "MS1", [0, 1], grid.n_fft // 2 + 1)
    waves = env.wave_components(
        grid, [4.0, 2.0], [11.0, 8.0], [250.0, 300.0], [3.3, 3.3], ph, omega_min=0.05, omega_max=3.0
    )
    wind = np.zeros((2, grid.n_steps + 1))
    return sim.build_forcing(m, grid, waves, wind, np.array([270.0, 270.0]), kin_every=1, second_order=True)


@pytest.mark.parametrize("kernel", [False, True], ids=["state_space", "convolution"])
def test_a_linear_model_started_steady_follows_its_periodic_solution(kernel):
    """On a linear model the start is an exact periodic solution: integrating from it follows the
    frequency-domain response from the first step (the radiation memory's history included),
    where the start at rest at the mean equilibrium is off by many standard deviations."""
    m = synthetic_model(kernel=kernel)
    rec_grid = env.record_grid(600.0, 0.0, 0.1)
    f = _linear_forcing(m, rec_grid)
    eq = sim.mean_equilibrium(m, f)
    k = linear_stiffness(m, eq.displacement, sim.mean_load(m, f))
    resp = periodic_response(m, f, rec_grid.n_fft, q_mean=eq.displacement, stiffness=k)
    start = sim.steady_start(m, f, rec_grid.n_fft)
    np.testing.assert_allclose(start.displacement, resp["displacement"][:, 0])
    fr = record_part(f, rec_grid)
    steady = sim.integrate(m, fr, transient=0.0, start=start).motion
    at_rest = sim.integrate(m, fr, transient=0.0, start=sim.equilibrium_start(m, fr)).motion
    ref = resp["displacement"][:, : steady.shape[2]].transpose(0, 2, 1)
    for d in (0, 1, 2, 4):  # surge (slow drift), sway, heave, pitch
        sd = ref[:, d].std()
        assert np.abs(steady[:, d] - ref[:, d]).max() < 0.05 * sd, d
        assert np.abs(at_rest[:, d, :2000] - ref[:, d, :2000]).max() > 1.0 * sd, d


def test_drag_linearisation_matches_the_gaussian_closed_form():
    """For isotropic Gaussian normal velocity of sd s, E[|u| I + u u^T / |u|] = 1.5 s sqrt(pi / 2) P."""
    m = synthetic_model(strips=True)
    rng = np.random.default_rng(7)
    ns = m.strip_pos.shape[0]
    u = rng.normal(0.0, 0.8, size=(200_000, 3, ns))
    u[:, 2, :] = 0.0  # vertical strips: the velocity normal to them
    load, damping = drag_linearisation(m, u)
    cn = m.strip_cdn[0]  # strip 0 at (0, 0, -10) has normal drag only
    expected = cn * 1.5 * 0.8 * math.sqrt(math.pi / 2)
    # strip 1 (axial drag only) adds nothing to horizontal damping: surge from strip 0 alone
    assert damping[0, 0] == pytest.approx(expected, rel=0.01)
    assert damping[1, 1] == pytest.approx(expected, rel=0.01)
    # roll/pitch about the origin through the strip at z = -10: the lever arm squared
    assert damping[4, 4] == pytest.approx(100.0 * expected, rel=0.01)
    # the load of one sample is the Morison drag of the undisturbed velocity
    s0 = u[0, :, 0]
    f0 = cn * math.hypot(s0[0], s0[1]) * s0[:2]
    assert load[0, 0] == pytest.approx(f0[0], rel=1e-9)
    assert load[0, 1] == pytest.approx(f0[1], rel=1e-9)


def test_the_record_is_the_start_of_its_period():
    """The steady start synthesises one whole period; its first steps are the record's forcing bit for bit."""
    m = moored("MS3")
    from moorlife.settings import SimulationSettings

    s = SimulationSettings.from_config({**SIM, "start": "steady"})
    kw = dict(case_ids=np.array([3, 4]), mooring_system="MS3", seed=2, model=m, settings=s)
    rec_grid = env.record_grid(s.duration, s.transient, s.dt)
    whole = record_part(batch_forcing(sea(2), grid=period_grid(rec_grid), **kw), rec_grid)
    own = batch_forcing(sea(2), **kw)
    for field in ("force", "wind", "kinematics", "wind_dir"):
        np.testing.assert_array_equal(getattr(whole, field), getattr(own, field), err_msg=field)
    assert whole.grid == own.grid


def test_steady_start_is_bit_identical_batch_or_single():
    m = moored("MS3", kind="dynamic")
    cfg = {**SIM, "start": "steady", "duration": 120.0, "transient": 30.0}
    kw = dict(mooring_system="MS3", seed=5, model_inputs=m, sim_cfg=cfg, fatigue_cfg={}, stats_cfg=STATS)
    both = sim.simulate_batch(sea(3), case_ids=np.array([10, 11, 12]), **kw)
    one = sim.simulate_batch({k: v[1:2] for k, v in sea(3).items()}, case_ids=np.array([11]), **kw)
    for name in (*sim.names.SIM_SCALAR_VARS, *sim.names.SIM_LINE_VARS):
        np.testing.assert_array_equal(both[name][1:2], one[name], err_msg=name)
    rest = sim.simulate_batch(sea(3), case_ids=np.array([10, 11, 12]), **{**kw, "sim_cfg": {**cfg, "start": "rest"}})
    assert not np.array_equal(rest["surge_std"], both["surge_std"])


def test_steady_start_sits_near_the_converged_nonlinear_state():
    """Drag, thrust and catenary lines: over a whole period, the linear steady state is far nearer the
    state a long nonlinear run reaches at the same instant than the mean equilibrium is."""
    from moorlife.settings import SimulationSettings

    m = moored("MS3")
    s = SimulationSettings.from_config({**SIM, "duration": 600.0, "transient": 0.0})
    rec_grid = env.record_grid(s.duration, s.transient, s.dt)
    one = sea(1, hs=[4.0], wind_speed=[8.0])
    f = batch_forcing(
        one, case_ids=np.array([1]), mooring_system="MS3", seed=4, model=m, settings=s, grid=period_grid(rec_grid)
    )
    n, ke = rec_grid.n_fft, f.kin_every
    # the reference: from the mean equilibrium through two whole periods, kept over the third
    steps = 3 * n - 1
    three = sim.Forcing(
        grid=env.RecordGrid(dt=f.grid.dt, n_steps=steps, n_fft=n, d_omega=f.grid.d_omega),
        force=np.concatenate([f.force[:, :n]] * 3, axis=1),
        wind=np.concatenate([f.wind[:, :n]] * 3, axis=1),
        wind_dir=f.wind_dir,
        kin_every=ke,
        kinematics=np.concatenate([f.kinematics[:, : n // ke]] * 4, axis=1)[:, : steps // ke + 2],
    )
    ref = sim.integrate(m, three, transient=2 * n * f.grid.dt, start=sim.equilibrium_start(m, three)).motion[0]
    eq = sim.mean_equilibrium(m, f)
    k = linear_stiffness(m, eq.displacement, sim.mean_load(m, f))
    lin = periodic_response(m, f, n, q_mean=eq.displacement, stiffness=k)["displacement"][0]
    np.testing.assert_allclose(sim.steady_start(m, f, n).displacement[0], lin[0])
    at = np.arange(0, ref.shape[1], 50)
    for d in (0, 1):  # surge and sway, where the slow drift lives
        steady = np.sqrt(np.mean((lin[at, d] - ref[d, at]) ** 2))
        rest = np.sqrt(np.mean((eq.displacement[0, d] - ref[d, at]) ** 2))
        assert steady < 0.2 * rest, (d, steady, rest)  # 0.007 against 0.29-0.39 m when written


def test_line_damping_is_measured_once_for_dynamic_lines_only():
    """The dynamic lines take energy out of a slow surge or sway (drag, seabed friction); heavier
    lines take more; quasi-static lines have none. Cached per model object."""
    from moorlife.simulate.steady import line_damping

    light, heavy = moored("MS1", kind="dynamic"), moored("MS6", kind="dynamic")
    b1, b6 = line_damping(light), line_damping(heavy)
    assert b1[0, 0] > 0 and b1[1, 1] > 0
    assert b6[0, 0] > 1.5 * b1[0, 0]
    assert np.count_nonzero(b1) == 2  # surge and sway only
    assert line_damping(light) is b1
    np.testing.assert_array_equal(line_damping(moored("MS1")), np.zeros((6, 6)))
