"""Coupled time-domain simulation of the floating platform, one sea state or a batch.

The rigid platform obeys Cummins' equation about the SWL origin (``moorlife.conventions``)::

    (M + A_inf) a = F_exc(t) + F_drift(t) - K q - int_0^T K_r(tau) v(t - tau) dtau
                    + F_drag + F_thrust + F_moor + F_trim

with ``q = (surge, sway, heave, roll, pitch, yaw)`` (m, rad), ``K`` the hydrostatic stiffness
with gravity, the radiation memory as a convolution with the retardation kernel ``K_r`` of the
BEM damping (default; or the fitted state space ``dx/dt = A x + B v``, force ``-C x``), first-
order excitation ``F_exc`` and Newman's slow drift ``F_drift`` synthesised for the whole record
by FFT (:mod:`moorlife.environment`), Morison drag on the relative velocity of every strip, the
rotor thrust ``T = 0.5 rho_a A Ct(v) v^2`` of the relative wind ``v`` passed through a notch at
the pitch frequency and applied at the hub along the wind (nacelle aligned with the wind), and a
constant trim load (the ballast adjustment that keeps each mooring system's platform at its
design draft and even keel). ``A_inf`` is made consistent with the memory (Ogilvie), so that
the model reproduces the BEM ``A(omega)`` and ``B(omega)``.

The mooring is a separate model (quasi-static surface or dynamic lumped-mass lines,
:mod:`moorlife.mooring`), advanced once per step to the fairlead positions extrapolated to the
end of the step; the platform is driven by the mean of the start and end fairlead forces
(explicit partitioned coupling, second order). The platform's own states use classical RK4
with forcing interpolated linearly inside the step; the convolution is held over the step.
The whole batch is advanced by one Numba kernel per step.

Design notes
------------
* Loads use linearised kinematics (small rotations): strip and hub velocities are
  ``v + omega x p`` with the body-frame position ``p``; the fairleads use the exact rotation.
* Wave kinematics for drag are evaluated at the strips' mean positions (first order).
* Every record starts as ``simulation.start`` says: at the linear periodic steady state of its
  own forcing (``steady``, :mod:`~moorlife.simulate.steady`), at rest at its mean equilibrium
  (``equilibrium``, :mod:`~moorlife.simulate.initial`: the static offset under its mean thrust
  and mean drift, the lines in their static shape there, the filters at their steady states), or
  at rest at the trimmed origin (``rest``). The kept record starts after ``transient``;
  statistics use only the kept part.
* A batch is bit-identical to its cases run alone: every random stream comes from
  ``case_rng(seed, mooring_system, case_id)`` and the kernel treats cases independently.

Modules, one concept each (this package re-exports their public API):
:mod:`~moorlife.simulate.model` (the model inputs), :mod:`~moorlife.simulate.forcing` (waves,
drag kinematics and wind on the integration grid), :mod:`~moorlife.simulate.kernel` (the Numba
kernels), :mod:`~moorlife.simulate.initial` (the start of a record: the mean equilibrium),
:mod:`~moorlife.simulate.steady` (the start at the linear periodic steady state),
:mod:`~moorlife.simulate.integration` (the step loop, :func:`integrate`),
:mod:`~moorlife.simulate.linear` (linear analysis, verification), :mod:`~moorlife.simulate.summary`
(statistics of a record), :mod:`~moorlife.simulate.batch` (one batch of sea states) and
:mod:`~moorlife.simulate.prepare` (model preparation, once per mooring system).
"""

from __future__ import annotations

from moorlife import names  # noqa: F401 - callers read ``simulate.names``
from moorlife.simulate.batch import batch_forcing, simulate_batch
from moorlife.simulate.forcing import Forcing, build_forcing, forcing_from
from moorlife.simulate.initial import (
    Equilibrium,
    InitialState,
    at_rest,
    equilibrium_start,
    mean_equilibrium,
    mean_load,
    static_offsets,
)
from moorlife.simulate.integration import Record, _run_compiled, integrate  # noqa: F401 - tests
from moorlife.simulate.kernel import rotation_matrix
from moorlife.simulate.linear import (
    frequency_response,
    linear_natural_periods,
    radiation_impedance,
    without_radiation_memory,
)
from moorlife.simulate.model import ModelInputs, build_model
from moorlife.simulate.prepare import (  # noqa: F401 - _strips_from_members: benchmarks
    _strips_from_members,
    attach_mooring,
    effective_added_mass_inf,
    platform_from,
    prepare_model,
    static_equilibrium,
)
from moorlife.simulate.steady import steady_start
from moorlife.simulate.summary import (
    EXTRA_ATTRS,
    EXTRA_LINE_VARS,
    EXTRA_SCALAR_VARS,
    TIMESERIES_VARS,
    output_attrs,
    summarise,
)

__all__ = [
    "ModelInputs",
    "Forcing",
    "Record",
    "EXTRA_SCALAR_VARS",
    "EXTRA_LINE_VARS",
    "EXTRA_ATTRS",
    "TIMESERIES_VARS",
    "output_attrs",
    "prepare_model",
    "build_model",
    "attach_mooring",
    "platform_from",
    "build_forcing",
    "forcing_from",
    "batch_forcing",
    "InitialState",
    "Equilibrium",
    "at_rest",
    "mean_load",
    "static_offsets",
    "mean_equilibrium",
    "equilibrium_start",
    "steady_start",
    "integrate",
    "summarise",
    "simulate_batch",
    "rotation_matrix",
    "frequency_response",
    "linear_natural_periods",
    "without_radiation_memory",
    "radiation_impedance",
    "effective_added_mass_inf",
    "static_equilibrium",
]
