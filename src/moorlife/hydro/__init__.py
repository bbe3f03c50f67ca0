"""Platform hydrodynamics: hull mesh, BEM (Capytaine), and the simulator's linear model.

Conventions (the package's, used everywhere in moorlife):

* Frame: origin at the still-water line on the platform centreline, x east, y north, z up;
  degrees of freedom ``surge, sway, heave, roll, pitch, yaw`` about the origin.
* Headings are *propagation* angles in radians, counter-clockwise from ``+x`` (the direction
  the waves travel to), see :func:`moorlife.conventions.propagation_angle`.
* **Phase convention: WAMIT's** ``exp(+i omega t)``. A wave component of amplitude ``a`` and
  phase ``phi`` has elevation ``eta(t) = Re[a exp(i(omega t + phi))] = a cos(omega t + phi)``
  at the origin, and exerts ``F(t) = Re[X a exp(i(omega t + phi))]`` with ``X`` the excitation
  per unit amplitude stored here. Capytaine solves with ``exp(-i omega t)``; its complex
  excitation is conjugated once, in :func:`run_bem`. WAMIT files are read as they are.
* Hydrostatic stiffness in ``platform.nc`` is buoyancy + waterplane only (as WAMIT ``.hst``);
  the gravity terms ``-m g z_G`` of the whole system are added in :func:`load_platform_model`.
* Mean drift coefficients ``drift[omega, heading, dof]`` are the mean force per wave
  amplitude squared (N/m^2, N m/m^2): a regular wave ``a cos(omega t)`` gives the mean force
  ``a^2 drift``.

The Capytaine part (:func:`run_bem`) is the only non-pure function; every other kernel is
numpy in, numpy out.

The package holds one concept per module; everything is re-exported here, so that
``from moorlife.hydro import run_bem`` and ``hydro.run_bem`` work as before:

* :mod:`moorlife.hydro.mesh`: the members of ``platform.yaml``, hull and lid panels, the
  Capytaine body;
* :mod:`moorlife.hydro.bem`: the Capytaine BEM (:func:`run_bem`), the far-field drift, the
  ``platform.nc`` dataset, and the ``hydro`` rule's driver (:func:`bem_from_settings`,
  :func:`richardson`);
* :mod:`moorlife.hydro.dihedral`: the exact shortcuts of the BEM of a hull with dihedral
  symmetry (``hydro.mesh.mirror_symmetry``): the influence matrix factorised by irreducible
  blocks, the headings solved in one sector only;
* :mod:`moorlife.hydro.body`: rigid-body mass, gravity stiffness, RAOs, natural periods;
* :mod:`moorlife.hydro.radiation`: the retardation kernel, Ogilvie's infinite-frequency added
  mass, the state-space fit;
* :mod:`moorlife.hydro.loads`: excitation and drift at a heading, Newman's slow drift,
  Morison drag;
* :mod:`moorlife.hydro.model`: the simulator's :class:`PlatformModel` and
  :func:`load_platform_model`.
"""

# module constants, re-exported outside __all__ as before the split
from moorlife.hydro.bem import DOF_NAMES as DOF_NAMES
from moorlife.hydro.bem import RADIATING_DOF as RADIATING_DOF
from moorlife.hydro.bem import (
    bem_from_settings,
    bem_settings,
    far_field_drift,
    frequency_grid,
    heading_grid,
    platform_dataset,
    richardson,
    run_bem,
    solver_depths,
    wavenumber,
)
from moorlife.hydro.body import (
    gravity_stiffness,
    motion_rao,
    natural_periods,
    rigid_body_mass_matrix,
    system_mass_properties,
)
from moorlife.hydro.loads import (
    drift_at,
    excitation_at,
    generalised_force,
    interp_heading,
    morison_drag_force,
    morison_elements,
    newman_drift_force,
    point_velocity,
)
from moorlife.hydro.mesh import BRACE_PANELS_AROUND as BRACE_PANELS_AROUND
from moorlife.hydro.mesh import (
    Member,
    annulus_panels,
    brace_extent,
    capytaine_body,
    hull_panels,
    lid_panels,
    members_from_config,
    n_around,
    wall_panels,
)
from moorlife.hydro.model import PlatformModel, load_platform_model
from moorlife.hydro.radiation import (
    StateSpace,
    added_mass_infinite_ogilvie,
    fit_state_space,
    retardation_kernel,
    state_space_kernel,
    state_space_response,
)

__all__ = [
    # geometry and mesh
    "Member",
    "members_from_config",
    "n_around",
    "wall_panels",
    "annulus_panels",
    "brace_extent",
    "hull_panels",
    "lid_panels",
    "capytaine_body",
    # BEM
    "frequency_grid",
    "heading_grid",
    "run_bem",
    "bem_from_settings",
    "richardson",
    "bem_settings",
    "wavenumber",
    "solver_depths",
    "far_field_drift",
    "platform_dataset",
    # rigid body and hydrostatics
    "rigid_body_mass_matrix",
    "system_mass_properties",
    "gravity_stiffness",
    "motion_rao",
    "natural_periods",
    # radiation
    "retardation_kernel",
    "added_mass_infinite_ogilvie",
    "fit_state_space",
    "StateSpace",
    "state_space_kernel",
    "state_space_response",
    # excitation, drift, drag
    "interp_heading",
    "excitation_at",
    "drift_at",
    "newman_drift_force",
    "morison_elements",
    "point_velocity",
    "morison_drag_force",
    "generalised_force",
    # the simulator's model
    "PlatformModel",
    "load_platform_model",
]
