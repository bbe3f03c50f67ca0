"""The restructured kernels give the plain loops' numbers bit for bit (issue 23, target 3).

The simulator's cost was cut by reordering work, never the arithmetic of one number: sums keep
their order, every product its operands. These tests hold each restructured kernel to a plain
reference (Python floats, one operation at a time, in the order of the physics' formula), for
batch sizes that take every path (blocks of cases, the cases left over, one case alone).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from moorlife.simulate.kernel import Body, Excitation, Radiation, Rotor, Strips, _convolve, _rhs


def _radiation(rng, npair, nlag, stride):
    kpi = rng.integers(0, 6, npair)
    kpj = rng.integers(0, 6, npair)
    ker = rng.standard_normal((npair, nlag)) * 10.0 ** rng.integers(-3, 4, (npair, 1))
    empty = np.zeros(0)
    return Radiation(
        ss_row_start=np.zeros(1, dtype=np.int64),
        ss_column=np.zeros(0, dtype=np.int64),
        ss_value=empty,
        ss_input=np.zeros((0, 6)),
        ss_output=np.zeros((6, 0)),
        kernel=ker,
        kernel_stride=stride,
        kernel_force_dof=kpi,
        kernel_velocity_dof=kpj,
    )


def _convolution_reference(rad, velocities, j, out):
    """``out[b, kpi[p]] -= sum_i ker[p, i] v_(j - (nlag - 1 - i) stride)[b, kpj[p]]``, oldest lag first."""
    ker, stride = rad.kernel, rad.kernel_stride
    npair, nlag = ker.shape
    for p in range(npair):
        for b in range(out.shape[0]):
            acc = 0.0
            for i in range(nlag):
                step = j - (nlag - 1 - i) * stride
                x = float(velocities[step][b, rad.kernel_velocity_dof[p]]) if step >= 0 else 0.0
                acc += float(ker[p, i]) * x
            out[b, rad.kernel_force_dof[p]] -= acc


@pytest.mark.parametrize("nb", [1, 3, 4, 6, 9])
@pytest.mark.parametrize(("npair", "stride"), [(10, 2), (3, 1), (5, 3)])
def test_convolution_equals_the_plain_sum(nb, npair, stride):
    rng = np.random.default_rng(100 * nb + npair)
    nlag = 13
    rad = _radiation(rng, npair, nlag, stride)
    hist = np.zeros((stride, 6, 2 * nlag, nb))
    acc = np.zeros((npair, nb))
    velocities = []
    for j in range(5 * nlag * stride):
        velocities.append(rng.standard_normal((nb, 6)))
        out = rng.standard_normal((nb, 6))
        ref = out.copy()
        _convolve(j, velocities[-1], hist, rad, acc, out)
        _convolution_reference(rad, velocities, j, ref)
        np.testing.assert_array_equal(out, ref, err_msg=f"step {j}")


def _strip_records(rng, nb, ns, nk):
    """A platform with nothing but Morison strips (unit inverse mass, no stiffness, no thrust)."""
    axis = rng.standard_normal((3, ns))
    axis /= np.linalg.norm(axis, axis=0)
    strips = Strips(
        position=rng.uniform(-40.0, 40.0, (3, ns)),
        axis=axis,
        drag_normal=rng.uniform(0.0, 5e4, ns),
        drag_axial=rng.uniform(0.0, 5e4, ns) * (rng.random(ns) < 0.5),
        loads=np.zeros((6, ns)),
    )
    body = Body(
        inverse_mass=np.eye(6),
        stiffness=np.zeros((6, 6)),
        damping=np.zeros((6, 6)),
        trim_load=np.zeros(6),
        hub=np.array([0.0, 0.0, 90.0]),
        fairleads=np.zeros((3, 3)),
    )
    rotor = Rotor(
        wind_speed=np.array([-100.0, 100.0]),
        thrust=np.zeros(2),
        filter_a=np.zeros((0, 0)),
        filter_b=np.zeros((0, 1)),
        filter_c=np.zeros((1, 0)),
        filter_d=np.ones((1, 1)),
    )
    wave = Excitation(
        force=np.zeros((nb, 2 * nk + 2, 6)),
        wind=np.zeros((nb, 2 * nk + 2)),
        wind_dir=np.tile([1.0, 0.0], (nb, 1)),
        kinematics=rng.standard_normal((nb, nk, 3, ns)).astype(np.float32),
        kin_every=2,
    )
    return body, strips, rotor, wave


def _strip_reference(strips, wave, b, tk, v):
    """Force and moment of the strips on case ``b`` at kinematics time ``tk``, strip after strip."""
    jk = int(tk)
    wk = tk - jk
    k0, k1 = wave.kinematics[b, jk], wave.kinematics[b, jk + 1]
    vx, vy, vz, wx, wy, wz = (float(x) for x in v)
    total = [0.0] * 6
    for s in range(strips.position.shape[1]):
        px, py, pz = (float(x) for x in strips.position[:, s])
        ax, ay, az = (float(x) for x in strips.axis[:, s])
        ux = (1 - wk) * float(k0[0, s]) + wk * float(k1[0, s]) - (vx + wy * pz - wz * py)
        uy = (1 - wk) * float(k0[1, s]) + wk * float(k1[1, s]) - (vy + wz * px - wx * pz)
        uz = (1 - wk) * float(k0[2, s]) + wk * float(k1[2, s]) - (vz + wx * py - wy * px)
        ua = ux * ax + uy * ay + uz * az
        nx, ny, nz = ux - ua * ax, uy - ua * ay, uz - ua * az
        un = math.sqrt(nx * nx + ny * ny + nz * nz)
        ca = float(strips.drag_axial[s]) * abs(ua) * ua
        cn = float(strips.drag_normal[s])
        fx, fy, fz = cn * un * nx + ca * ax, cn * un * ny + ca * ay, cn * un * nz + ca * az
        for d, x in enumerate((fx, fy, fz, py * fz - pz * fy, pz * fx - px * fz, px * fy - py * fx)):
            total[d] += x
    return np.array(total)


@pytest.mark.parametrize("ns", [1, 7, 78])
def test_strip_loads_equal_the_plain_sum(ns):
    rng = np.random.default_rng(ns)
    nb, nk = 3, 6
    body, strips, rotor, wave = _strip_records(rng, nb, ns, nk)
    rad = _radiation(rng, 0, 0, 1)
    for b, j, frac in ((0, 0, 0.0), (1, 3, 0.5), (2, 7, 1.0), (2, 8, 0.25)):
        y = np.concatenate([rng.standard_normal(6), rng.standard_normal(6)])
        dy = np.full(12, np.nan)
        _rhs(b, frac, j, y, dy, np.zeros((nb, 6)), np.zeros(6), body, rad, strips, rotor, wave)
        np.testing.assert_array_equal(dy[:6], y[6:])
        np.testing.assert_array_equal(dy[6:], _strip_reference(strips, wave, b, (j + frac) / 2, y[6:]))
