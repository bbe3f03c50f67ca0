"""Choice of the sea states to simulate, and the conventional scatter matrix.

Two things live here (Barrera et al. 2019, section 3.2 and section 4.1):

* **Maximum dissimilarity** (MDA, Camus et al. 2011) over the 5-D sea-state points
  ``(W, beta, Hs, Tp, alpha)``: the training states are picked greedily so that each new
  state is the one farthest from its nearest already-selected state. A further, disjoint
  set of *validation* states is kept only to check the reconstruction.
* **The discrete matrix** the paper compares against: the hindcast binned by Hs, then W,
  then Tp; each non-empty bin is represented by the mean Hs, W, Tp of its hours, the most
  likely wave and wind directions, and its probability of occurrence.

The normalised distance (scalars by their range, directions on the circle, divided by 180
deg) is the one of :mod:`moorlife.space`, shared with the RBF reconstruction; its functions
are re-exported here. The ranges used by the selection are stored in the attributes of
``results/selection/cases.zarr`` (``norm_lo`` / ``norm_span``), so that later stages use
exactly the same metric.

Kernels take numpy arrays and return numpy arrays; :func:`select_cases` and
:func:`discrete_states` are thin xarray adapters producing the stores of the output
contract (``results/selection/cases.zarr`` and ``results/selection/discrete.zarr``).

Modules: :mod:`~moorlife.selection.dissimilarity` (maximum dissimilarity, validation states),
:mod:`~moorlife.selection.reference` (the brute-force reference of MDA),
:mod:`~moorlife.selection.scatter` (the scatter matrix), :mod:`~moorlife.selection.adapters`
(the xarray adapters).
"""

from __future__ import annotations

from moorlife.selection.adapters import discrete_states, hindcast_points, select_cases
from moorlife.selection.dissimilarity import (
    VALIDATION_RULES,
    VALIDATION_STREAM_KEY,
    mda,
    select_validation,
)
from moorlife.selection.reference import mda_bruteforce
from moorlife.selection.scatter import (
    DEFAULT_HS_EDGES,
    DEFAULT_TP_EDGES,
    DEFAULT_WIND_EDGES,
    ScatterMatrix,
    check_edges,
    class_labels,
    classify,
    modal_direction,
    scatter_matrix,
)
from moorlife.space import nearest_distance, normalise, pairwise_distance, scaling_from

__all__ = [
    "check_edges",
    "classify",
    "VALIDATION_RULES",
    "VALIDATION_STREAM_KEY",
    "DEFAULT_HS_EDGES",
    "DEFAULT_WIND_EDGES",
    "DEFAULT_TP_EDGES",
    "scaling_from",
    "normalise",
    "pairwise_distance",
    "nearest_distance",
    "mda",
    "mda_bruteforce",
    "select_validation",
    "modal_direction",
    "class_labels",
    "ScatterMatrix",
    "scatter_matrix",
    "hindcast_points",
    "select_cases",
    "discrete_states",
]
