"""Dynamic lumped-mass lines: closed-form node forces, static limit, determinism, and the
peer comparison with MoorDyn (python ``moordyn``) on a prescribed fairlead motion.

Line data: paper Table 4 (copied here); hydrodynamic and seabed coefficients: the OC4 MoorDyn
deck of the OpenFAST r-test (Cd 2.0, Ca 0.8, CdAx 0.4, CaAx 0.25, kbot 3e6, cbot 3e5, BA -1).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from moorlife.mooring import dynamic as dyn
from moorlife.mooring import fairlead_positions, lines, make_mooring
from moorlife.mooring import quasistatic as qs

MS2 = {
    "mooring_system": "MS2",
    "mass_kg_per_m": 125.6,
    "pretension_kN": 1112.0,
    "link_diameter_mm": 79.0,
    "equivalent_diameter_m": 0.1398,
    "EA_N": 7.45e8,
    "MBS_N": 7200284.0,
    "chain": "studless",
}
MS5 = dict(
    MS2,
    mooring_system="MS5",
    mass_kg_per_m=462.0,
    pretension_kN=4117.0,
    link_diameter_mm=152.0,
    equivalent_diameter_m=0.2679,
    EA_N=2.62e9,
    MBS_N=22363193.0,
)
LAYOUT = lines.oc4_layout(None)


def _surge(t):
    """5 m at 100 s plus 1 m at 10 s, smoothly ramped in over 20 s: position and velocity."""
    w1, w2 = 2 * np.pi / 100.0, 2 * np.pi / 10.0
    x = 5 * np.sin(w1 * t) + np.sin(w2 * t)
    v = 5 * w1 * np.cos(w1 * t) + w2 * np.cos(w2 * t)
    tt = np.minimum(t, 20.0)
    ramp = 0.5 * (1.0 - np.cos(np.pi * tt / 20.0))
    dramp = np.where(t < 20.0, 0.5 * np.pi / 20.0 * np.sin(np.pi * tt / 20.0), 0.0)
    return x * ramp, v * ramp + x * dramp


def _run_ours(props, cfg, t, batch=1):
    model = make_mooring("dynamic", props, LAYOUT, cfg, batch=batch)
    state = model.init(fairlead_positions(LAYOUT, np.zeros((batch, 3))))
    X, V = _surge(t)
    out = np.empty((t.size, batch, 3))
    out[0] = model.tension(state)
    vf = np.zeros((batch, 3, 3))
    for i in range(1, t.size):
        rf = fairlead_positions(LAYOUT, np.tile([X[i], 0.0, 0.0], (batch, 1)))
        vf[..., 0] = V[i]
        model.step(state, rf, vf, t[i] - t[i - 1])
        out[i] = model.tension(state)
    return out


def _moordyn_deck(path, props, settings, dtm, fric_damp):
    lt = (
        f"main {props.equivalent_diameter} {props.mass} {props.EA} -{settings.internal_damping_ratio} 0 "
        f"{settings.cd_normal} {settings.ca_normal} {settings.cd_axial} {settings.ca_axial}"
    )
    pts = [f"{k + 1} Fixed {a[0]:.9f} {a[1]:.9f} {a[2]:.9f} 0 0 0 0" for k, a in enumerate(LAYOUT.anchors)]
    pts += [f"{k + 4} Coupled {f[0]:.9f} {f[1]:.9f} {f[2]:.9f} 0 0 0 0" for k, f in enumerate(LAYOUT.fairleads_body)]
    lns = [f"{k + 1} main {k + 1} {k + 4} {LAYOUT.length} {settings.n_segments} -" for k in range(3)]
    text = "\n".join(
        [
            "--------------------- MoorDyn Input File ---------------------",
            "moorlife test deck (OC4 geometry, paper Table 4 chain)",
            "----------------------- LINE TYPES ---------------------------",
            "Name Diam MassDen EA BA/-zeta EI Cd Ca CdAx CaAx",
            "(-) (m) (kg/m) (N) (N-s/-) () (-) (-) (-) (-)",
            lt,
            "---------------------- POINTS --------------------------------",
            "Node Type X Y Z M V CdA CA",
            "(-) (-) (m) (m) (m) (kg) (m^3) (m^2) (-)",
            *pts,
            "---------------------- LINES ---------------------------------",
            "Line LineType AttachA AttachB UnstrLen NumSegs Outputs",
            "(-) (-) (-) (-) (m) (-) (-)",
            *lns,
            "---------------------- OPTIONS -------------------------------",
            f"{dtm} dtM",
            f"{settings.seabed_stiffness} kbot",
            f"{settings.seabed_damping} cbot",
            f"{LAYOUT.depth} WtrDpth",
            f"{settings.water_density} rho",
            f"{settings.gravity} g",
            "1.0 dtIC",
            "60.0 TmaxIC",
            "4.0 CdScaleIC",
            "0.001 threshIC",
            f"{settings.friction_coefficient} FrictionCoefficient",
            f"{fric_damp} FricDamp",
            "------------------------- need this line ----------------------",
            "",
        ]
    )
    path.write_text(text)
    return path


def _run_moordyn(deck, t):
    moordyn = pytest.importorskip("moordyn")
    system = moordyn.Create(str(deck))
    x0 = LAYOUT.fairleads_body.ravel()
    moordyn.Init(system, list(x0), [0.0] * 9)
    X, V = _surge(t)
    out = np.empty((t.size, 3))
    out[0] = np.nan
    for i in range(1, t.size):
        x = (LAYOUT.fairleads_body + [X[i], 0.0, 0.0]).ravel()
        f = np.asarray(moordyn.Step(system, list(x), list(np.tile([V[i], 0.0, 0.0], 3)), t[i - 1], t[i] - t[i - 1]))
        out[i] = np.linalg.norm(f.reshape(3, 3), axis=1)  # force at the coupled point, not GetLineFairTen
    moordyn.Close(system)
    return out


# ------------------------------------------------------------------ closed forms
def test_node_forces_closed_forms():
    props = lines.line_properties(MS2)
    settings = lines.mooring_settings(None)
    model = dyn.line_model(props, LAYOUT, settings)
    N = model.n_segments
    l0 = LAYOUT.length / N
    # a straight horizontal line stretched by 0.1 %, lying 0.01 m into the seabed, nodes moving
    r = np.zeros((N + 1, 3))
    r[:, 0] = np.linspace(0.0, 1.001 * LAYOUT.length, N + 1)
    r[:, 2] = -LAYOUT.depth - 0.01
    v = np.zeros_like(r)
    v[:, 1] = 0.5  # sideways (normal) motion, sliding on the seabed
    F, M = dyn.node_forces(model, r, v)
    T = props.EA * 0.001
    D = props.equivalent_diameter
    i = N // 2
    drag = 0.5 * 1025.0 * 2.0 * D * l0 * 0.5 * 0.5
    Bz = 0.01 * 3e6 * D * l0
    wet = props.wet_weight * l0
    assert F[i, 0] == pytest.approx(0.0, abs=1e-6 * T)  # tensions cancel on an interior node
    assert F[i, 2] == pytest.approx(Bz - wet, rel=1e-9)
    assert F[i, 1] == pytest.approx(-drag - 0.7 * abs(Bz), rel=1e-9)  # drag + saturated friction
    assert F[0, 0] == pytest.approx(T, rel=1e-9)  # end nodes feel the segment tension
    # below the slip velocity the friction is proportional to the speed
    v[:, 1] = 0.002
    F, M = dyn.node_forces(model, r, v)
    drag = 0.5 * 1025.0 * 2.0 * D * l0 * 0.002 * 0.002
    assert F[i, 1] == pytest.approx(-drag - 0.7 * abs(Bz) * 0.2, rel=1e-9)
    # added mass: transverse Ca, axial CaAx on the equivalent-diameter volume
    M = M[i]
    V = math.pi / 4 * D**2 * l0
    assert M[0, 0] == pytest.approx(props.mass * l0 + 1025.0 * V * 0.25, rel=1e-12)
    assert M[1, 1] == pytest.approx(props.mass * l0 + 1025.0 * V * 0.8, rel=1e-12)


def test_static_state_matches_catenary():
    for row in (MS2, MS5):
        props = lines.line_properties(row)
        model = make_mooring("dynamic", props, LAYOUT, {"mooring": {"relaxation_time": 10.0}}, batch=1)
        state = model.init(fairlead_positions(LAYOUT, np.zeros((1, 3))))
        H, V = qs.catenary_solve(796.732, 186.0, LAYOUT.length, props.EA, props.wet_weight)
        T = model.tension(state)[0]
        np.testing.assert_allclose(T, math.hypot(H, V), rtol=5e-3)
        assert np.abs(state.v).max() < 1e-3


def test_slow_motion_reaches_the_quasistatic_surface():
    props = lines.line_properties(MS2)
    cfg = {"mooring": {"relaxation_time": 10.0, "friction_coefficient": 0.0}}
    dyn_model = make_mooring("dynamic", props, LAYOUT, cfg, batch=1)
    qs_model = make_mooring("quasistatic", props, LAYOUT, cfg, batch=1)
    r = fairlead_positions(LAYOUT, np.zeros((1, 3)))
    state = dyn_model.init(r)
    qstate = qs_model.init(r)
    dt, period = 0.5, 2000.0
    for t in np.arange(dt, 400.0 + dt / 2, dt):  # 8 m surge, 2000 s period: drag negligible
        x = 8.0 * np.sin(2 * np.pi * t / period)
        v = 8.0 * 2 * np.pi / period * np.cos(2 * np.pi * t / period)
        rf = fairlead_positions(LAYOUT, [[x, 0.0, 0.0]])
        dyn_model.step(state, rf, np.tile([v, 0.0, 0.0], (1, 3, 1)), dt)
    qs_model.step(qstate, rf, None, dt)
    np.testing.assert_allclose(dyn_model.tension(state), qs_model.tension(qstate), rtol=5e-3)


def test_batch_members_are_independent_and_deterministic():
    props = lines.line_properties(MS2)
    cfg = {"mooring": {"relaxation_time": 5.0}}
    t = np.arange(0.0, 20.0 + 1e-9, 0.1)
    one = _run_ours(props, cfg, t, batch=1)
    two = _run_ours(props, cfg, t, batch=3)
    np.testing.assert_array_equal(two[:, 0], one[:, 0])
    np.testing.assert_array_equal(two[:, 2], one[:, 0])
    assert np.all(np.isfinite(one)) and one[-1, 0, 1] != one[0, 0, 1]


def test_bad_shapes_are_refused():
    props = lines.line_properties(MS2)
    model = make_mooring("dynamic", props, LAYOUT, {"mooring": {"relaxation_time": 0.0}}, batch=2)
    state = model.init(fairlead_positions(LAYOUT, np.zeros((2, 3))))
    with pytest.raises(ValueError, match="shape"):
        model.step(state, np.zeros((1, 3, 3)), np.zeros((1, 3, 3)), 0.1)
    with pytest.raises(ValueError, match="kind"):
        make_mooring("fem", props, LAYOUT, None)
    r = fairlead_positions(LAYOUT, np.zeros((2, 3)))
    r[1, 2, 0] = np.nan
    with pytest.raises(FloatingPointError, match=r"MS2.*\(batch, line\) \[1, 2\]"):
        model.step(state, r, np.zeros_like(r), 0.1)


def test_time_step_convergence():
    props = lines.line_properties(MS2)
    t = np.arange(0.0, 60.0 + 1e-9, 0.1)

    def run(h):
        return _run_ours(props, {"mooring": {"relaxation_time": 5.0, "max_time_step": h}}, t)[200:, 0, 1]

    ref = run(0.00625)
    # rms error relative to the standard deviation; seabed touchdown transients make the
    # pointwise maximum error non-monotonic, the rms converges
    err = {h: np.sqrt(np.mean((run(h) - ref) ** 2)) / np.std(ref) for h in (0.1, 0.05, 0.0125)}
    assert err[0.1] < 0.05 and err[0.05] < 0.02 and err[0.0125] < 0.005
    assert err[0.0125] < err[0.05] < err[0.1]


def test_ros2_and_bdf2_agree():
    props = lines.line_properties(MS2)
    t = np.arange(0.0, 80.0 + 1e-9, 0.1)
    a = _run_ours(props, {"mooring": {"relaxation_time": 5.0, "integrator": "bdf2"}}, t)[300:, 0, :]
    b = _run_ours(props, {"mooring": {"relaxation_time": 5.0, "integrator": "ros2"}}, t)[300:, 0, :]
    np.testing.assert_allclose(a.std(axis=0), b.std(axis=0), rtol=0.01)
    np.testing.assert_allclose(np.ptp(a, axis=0), np.ptp(b, axis=0), rtol=0.02)
    assert not np.array_equal(a, b)


# ------------------------------------------------------------------ peer: MoorDyn
@pytest.mark.slow
@pytest.mark.parametrize(("row", "friction"), [(MS2, 0.7), (MS5, 0.0)], ids=["MS2-friction", "MS5-frictionless"])
def test_fairlead_tension_statistics_match_moordyn(tmp_path, row, friction):
    props = lines.line_properties(row)
    cfg = {"mooring": {"friction_coefficient": friction}}
    settings = lines.mooring_settings(cfg)
    # MoorDyn's friction is min(mu * FricDamp * |v|, mu * Fn): the same saturation at our slip
    # velocity for a node resting with its own wet weight
    fric_damp = props.wet_weight * LAYOUT.length / settings.n_segments / settings.friction_slip_velocity
    deck = _moordyn_deck(tmp_path / "moordyn.dat", props, settings, 0.001, fric_damp if friction else 200.0)
    t = np.arange(0.0, 250.0 + 1e-9, 0.1)  # the simulator's step; default mooring.max_time_step
    ours = _run_ours(props, cfg, t)[:, 0, :]
    ref = _run_moordyn(deck, t)
    keep = t >= 50.0
    for k in range(3):
        a, b = ours[keep, k], ref[keep, k]
        assert a.mean() == pytest.approx(b.mean(), rel=0.05)
        assert a.std() == pytest.approx(b.std(), rel=0.05)
        assert np.ptp(a) == pytest.approx(np.ptp(b), rel=0.05)


def test_a_slack_line_whose_newton_solve_breaks_down_still_starts_static():
    """MS1 pushed 21.6 m off (11.0, 18.6 m): Newton's static solve of the slack leeward line meets a
    singular matrix (most of the line on the seabed). The start falls back on the catenary and the
    relaxation settles it: the tensions are the quasi-static ones (found by the steady start of
    issue 23, which starts storm states off their mean offset)."""
    from test_simulate import ROWS

    props = lines.line_properties({**ROWS["MS1"], "mooring_system": "MS1"})
    offset = np.array([[11.0, 18.6, 0.0]])
    r = fairlead_positions(LAYOUT, offset)
    model = make_mooring("dynamic", props, LAYOUT, {}, batch=1)
    newton = []
    for k in range(3):
        nodes = dyn.initial_nodes(model.model, LAYOUT.anchors[k], r[0, k], LAYOUT.length, props)
        dyn._static_solve_flat(nodes, model.model.params, model._w, 200, 1e-6 * props.wet_weight * LAYOUT.length)
        newton.append(np.isfinite(nodes).all())
    assert not all(newton)  # the case exercises the fallback
    state = model.init(r)
    static = make_mooring("quasistatic", props, LAYOUT, {}, batch=1)
    expected = static.tension(static.init(r))[0]
    np.testing.assert_allclose(model.tension(state)[0], expected, rtol=0.01)
