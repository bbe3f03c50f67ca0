"""The BDF2 step of every line at once (``moorlife.mooring.lanes``) against the one-line reference step.

The fast path must give the bits of :func:`moorlife.mooring.dynamic.step_lines`, step after step,
where the branches of a line differ between lanes: some nodes on the seabed and sliding, some
lifting off, slack segments, with and without friction.
"""

from __future__ import annotations

import numpy as np
import pytest

from moorlife.mooring import dynamic as dyn
from moorlife.mooring import fairlead_positions, lanes, lines, make_mooring

ROW = {
    "mooring_system": "MS2",
    "mass_kg_per_m": 125.6,
    "pretension_kN": 1112.0,
    "link_diameter_mm": 79.0,
    "equivalent_diameter_m": 0.1398,
    "EA_N": 7.45e8,
    "MBS_N": 7200284.0,
    "chain": "studless",
}
LAYOUT = lines.oc4_layout(None)


def _path(t, batch):
    """Fairlead motions of ``batch`` cases: surge, sway and heave of different sizes and periods."""
    amp = np.array([[18.0, 0.0, 4.0], [-12.0, 9.0, -3.0], [2.0, -15.0, 6.0]])[:batch]
    per = np.array([[60.0, 30.0, 8.0], [45.0, 25.0, 11.0], [90.0, 12.0, 6.0]])[:batch]
    w = 2 * np.pi / per
    ramp = np.minimum(t / 30.0, 1.0)
    x = amp * np.sin(w * t) * ramp
    v = amp * w * np.cos(w * t) * ramp + (amp * np.sin(w * t) / 30.0 if t < 30.0 else 0.0)
    return x, v


@pytest.mark.parametrize("friction", [0.0, 1.0])
def test_lanes_step_the_bits_of_the_one_line_step(friction):
    batch, dt, n = 3, 0.1, 400
    cfg = {"mooring": {"relaxation_time": 5.0, "friction_coefficient": friction}}
    props = lines.line_properties(ROW)
    ref = make_mooring("dynamic", props, LAYOUT, cfg, batch=batch)
    fast = make_mooring("dynamic", props, LAYOUT, cfg, batch=batch)
    s_ref = ref.init(fairlead_positions(LAYOUT, np.zeros((batch, 3))))
    s_fast = dyn.DynamicState(*(a.copy() for a in s_ref))
    nsub = ref.substeps(dt)
    N = ref.model.n_segments
    ls, work = lanes.lane_state(batch * 3, N), lanes.lane_work(batch * 3, N)
    vf = np.zeros((batch, 3, 3))
    forces, tension = np.zeros((batch, 3, 3)), np.zeros((batch, 3))
    on_bed, slack = set(), 0
    for i in range(1, n + 1):
        x, v = _path(i * dt, batch)
        rf = fairlead_positions(LAYOUT, x)
        vf[...] = v[:, None, :]
        ref.step(s_ref, rf, vf, dt)
        if i == 1:  # the first step starts the BDF2 history (ROS2), as in the record loop
            fast.step(s_fast, rf, vf, dt)
            lanes.pack(s_fast, ls)
        else:
            lanes.step_lanes(ls, np.ascontiguousarray(rf), vf, dt, nsub, fast.model.params, work, forces, tension)
            np.testing.assert_array_equal(forces, s_ref.forces, err_msg=f"step {i}")
            np.testing.assert_array_equal(tension, s_ref.tension, err_msg=f"step {i}")
        on_bed.update(np.flatnonzero((s_ref.r[..., 2] < -LAYOUT.depth).any(axis=(0, 1))).tolist())
        seg = np.linalg.norm(np.diff(s_ref.r, axis=2), axis=-1)
        slack += int((seg < LAYOUT.length / N).sum())
    lanes.unpack(ls, s_fast)
    for name in ("r", "v", "r_prev", "v_prev"):
        np.testing.assert_array_equal(getattr(s_fast, name), getattr(s_ref, name), err_msg=name)
    # the branches were taken: nodes on the seabed (sliding with friction), slack segments
    assert len(on_bed) > 3 and slack > 0


def test_pack_and_unpack_are_inverse():
    rng = np.random.default_rng(3)
    st = dyn.DynamicState(
        r=rng.normal(size=(2, 3, 5, 3)),
        v=rng.normal(size=(2, 3, 5, 3)),
        forces=np.zeros((2, 3, 3)),
        tension=np.zeros((2, 3)),
        r_prev=rng.normal(size=(2, 3, 5, 3)),
        v_prev=rng.normal(size=(2, 3, 5, 3)),
        step_prev=np.zeros((2, 3)),
    )
    ls = lanes.lane_state(6, 4)
    lanes.pack(st, ls)
    arrays = lanes.lane_arrays(ls, 6, 4)
    np.testing.assert_array_equal(arrays["r"][:, :, 4], st.r[1, 1])  # case 1, line 1 is lane 1 * 3 + 1
    np.testing.assert_array_equal(arrays["v_prev"][:, :, 5], st.v_prev[1, 2])
    # the lanes past the last line (to a multiple of the block width) are copies of it
    rec = ls.nodes.reshape(-1, 5, lanes._NQ, lanes.W)
    assert rec.shape[0] * lanes.W >= 6
    for m in range(6, rec.shape[0] * lanes.W):
        np.testing.assert_array_equal(rec[m // lanes.W, :, :3, m % lanes.W], st.r[1, 2])
    back = dyn.DynamicState(*(np.zeros_like(a) for a in st))
    lanes.unpack(ls, back)
    for name in ("r", "v", "r_prev", "v_prev"):
        np.testing.assert_array_equal(getattr(back, name), getattr(st, name))


def test_a_non_finite_fairlead_is_refused():
    props = lines.line_properties(ROW)
    moor = make_mooring("dynamic", props, LAYOUT, {}, batch=1)
    st = moor.init(fairlead_positions(LAYOUT, np.zeros((1, 3))))
    N = moor.model.n_segments
    ls, work = lanes.lane_state(3, N), lanes.lane_work(3, N)
    lanes.pack(st, ls)
    rf = fairlead_positions(LAYOUT, np.zeros((1, 3)))
    rf[0, 1, 0] = np.nan
    with pytest.raises(FloatingPointError, match="non-finite"):
        lanes.step_lanes(
            ls, rf, np.zeros((1, 3, 3)), 0.1, 2, moor.model.params, work, np.zeros((1, 3, 3)), np.zeros((1, 3))
        )
