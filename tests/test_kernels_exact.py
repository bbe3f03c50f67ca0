"""The restructured kernels give the plain loops' numbers bit for bit (issue 23, target 3).

The simulator's cost was cut by reordering work, never the arithmetic of one number: sums keep
their order, every product its operands. These tests hold each restructured kernel to a plain
reference (Python floats, one operation at a time, in the order of the physics' formula), for
batch sizes that take every path (blocks of cases, the cases left over, one case alone).
"""

from __future__ import annotations

import numpy as np
import pytest

from moorlife.simulate.kernel import Radiation, _convolve


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
