"""Life-cycle reconstruction, life-cycle damage, the conventional baseline and the comparison.

Methodology steps 6-9 (Barrera et al. 2019, sections 3.4-4): the outputs of the simulated
training states are rebuilt for every hindcast hour with :mod:`moorlife.rbf`, validated on
the states kept aside, and the rebuilt hourly damage is summed over the hindcast. That sum is
compared with the damage of the discrete scatter matrix (probability x hourly damage x hours),
turned into a fatigue life and a design check (DNVGL-OS-E301 / API RP 2SK factors from
:mod:`moorlife.fatigue`), and the mooring systems are ranked by a recommendation rule.

Kernels take and return numpy arrays; :func:`reconstruct_lifecycle`,
:func:`discrete_damage_table` and :func:`summary_table` are the xarray/pandas adapters used
by the workflow scripts. Conventions:

* ``lifecycle damage`` is the sum of the hourly damage over every hour of the hindcast;
  per year it is divided by the hindcast length in years (hours / 8766), and over the design
  life it is the yearly damage times the design life.
* ``difference_pct = 100 (D_lifecycle - D_discrete) / D_lifecycle``: positive when the
  discrete matrix underestimates (the sign of the paper's Table 7).
* ``passes``: ``DFF x D_design_life <= 1`` with the design fatigue factor of the curve
  family's rule (``fatigue.design_factor``) and, for DNV, ``dF`` = the damage of the line
  adjacent to the most damaged one over the most damaged (:func:`fatigue.adjacent_damage_ratio`).

Modules: :mod:`~moorlife.lifecycle.settings` (``RBFSettings``, with ``GPSettings``), :mod:`~moorlife.lifecycle.outputs`
(outputs <-> matrices), :mod:`~moorlife.lifecycle.spaces` (the candidate input spaces: the
paper's 5-D space, or with the rotor thrust), :mod:`~moorlife.lifecycle.turbulence` (the
turbulent thrust, a thrust coordinate), :mod:`~moorlife.lifecycle.fit` (fit, with the
global or per-output choice, prediction and validation metrics),
:mod:`~moorlife.lifecycle.damage` (damage arithmetic), :mod:`~moorlife.lifecycle.uncertainty`,
:mod:`~moorlife.lifecycle.records` (the training records' seed noise in a sum),
:mod:`~moorlife.lifecycle.adapters` (the xarray/pandas adapters) and
:mod:`~moorlife.lifecycle.sensitivity`.
"""

from __future__ import annotations

from moorlife.lifecycle.adapters import (
    Fitted,
    band_sigma,
    discrete_damage_table,
    fit_reconstruction,
    reconstruct_lifecycle,
    records_term,
    summary_table,
    validation_sum_term,
)

# the private helpers _label, _points and _selection_scaling are re-exported for
# validation/rbf_thrust_coordinate.py, which rebuilds the matrices of reconstruct_lifecycle
from moorlife.lifecycle.adapters import _points as _points
from moorlife.lifecycle.adapters import _selection_scaling as _selection_scaling
from moorlife.lifecycle.damage import (
    DAMAGE_VARS,
    HOURS_PER_YEAR,
    damage_per_year,
    design_check,
    difference_pct,
    discrete_damage,
    life_damage,
    recommend,
)
from moorlife.lifecycle.fit import (
    Reconstruction,
    fit_outputs,
    gp_groups,
    loo_errors_in_units,
    predict_outputs,
)
from moorlife.lifecycle.outputs import (
    DEFAULT_OUTPUTS,
    output_columns,
    stack_outputs,
    unstack_outputs,
)
from moorlife.lifecycle.outputs import _label as _label
from moorlife.lifecycle.sensitivity import (
    corrosion_evolution,
    mean_stress_table,
    seed_lives,
)
from moorlife.lifecycle.settings import GPBounds, GPSettings, RBFSettings, rbf_settings
from moorlife.lifecycle.spaces import (
    ThrustCurve,
    TurbulentThrust,
    space_inputs,
    space_points,
    thrust_at,
    thrust_curve,
    turbulent_thrust,
)
from moorlife.lifecycle.stacking import stack_weights
from moorlife.lifecycle.uncertainty import (
    band_sigma_of,
    calibrate_coverage,
    coverage_needed,
    error_indicator,
    life_band,
    suggest_states,
    sum_seed_cv,
)
from moorlife.lifecycle.validation import validation_metrics, validation_r_interval

__all__ = [
    "HOURS_PER_YEAR",
    "DEFAULT_OUTPUTS",
    "DAMAGE_VARS",
    "RBFSettings",
    "GPSettings",
    "GPBounds",
    "rbf_settings",
    "output_columns",
    "stack_outputs",
    "unstack_outputs",
    "validation_metrics",
    "validation_r_interval",
    "Reconstruction",
    "Fitted",
    "fit_reconstruction",
    "records_term",
    "fit_outputs",
    "gp_groups",
    "predict_outputs",
    "ThrustCurve",
    "thrust_curve",
    "thrust_at",
    "turbulent_thrust",
    "TurbulentThrust",
    "space_inputs",
    "space_points",
    "life_damage",
    "damage_per_year",
    "design_check",
    "discrete_damage",
    "difference_pct",
    "recommend",
    "error_indicator",
    "loo_errors_in_units",
    "stack_weights",
    "suggest_states",
    "life_band",
    "band_sigma",
    "band_sigma_of",
    "validation_sum_term",
    "sum_seed_cv",
    "coverage_needed",
    "calibrate_coverage",
    "reconstruct_lifecycle",
    "discrete_damage_table",
    "summary_table",
    "seed_lives",
    "corrosion_evolution",
    "mean_stress_table",
]
