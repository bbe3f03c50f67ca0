"""Experiment: the stack weights of ``choose: stack`` chosen on the late maximum-dissimilarity picks.

Usage::

    OMP_NUM_THREADS=1 python validation/stack_interior.py FIRST -- [reconstruction.py arguments]
    OMP_NUM_THREADS=1 python validation/stack_interior.py 500 -- --results results --systems MS2 \\
        --work DIR --variant stack_late=validation/overlays/gp_matern52_wind_all_frozen_sdT_stack.yaml

Maximum dissimilarity picks the edge of the sea-state cloud first (the first state is the
largest Hs) and fills its interior last, and the training rows of a fit are in pick order (the
case ids). The leave-one-out error of an early pick is an extrapolation to the edge, that of a
late pick an interpolation between close neighbours, as the 225 validation states (random
hindcast hours, ``selection.validation_rule: random``) are. Both parts of the blend are still
fitted on every training state; only the weight of each output (:func:`moorlife.lifecycle.stack_weights`)
is chosen on the leave-one-out of the training rows from FIRST on. The validation states and the
truth steer nothing. Measured in ``validation/reconstruction.md`` section 30 (a pilot).
"""

from __future__ import annotations

import sys
from typing import Any

from moorlife.lifecycle import fit

_ORIGINAL = fit.stack_weights


def late_picks(first: int) -> Any:
    """``stack_weights`` on the training rows from ``first`` on (the late maximum-dissimilarity picks)."""

    def weights(values: Any, loo_a: Any, loo_b: Any, log_output: Any, *args: Any, **kw: Any) -> Any:
        if len(values) <= first:
            raise SystemExit(f"stack_interior.py: FIRST {first} leaves no training row of {len(values)}")
        return _ORIGINAL(values[first:], loo_a[first:], loo_b[first:], log_output, *args, **kw)

    return weights


if __name__ == "__main__":
    import reconstruction  # beside this script: sys.path[0]

    mine, rest = reconstruction.split_argv(sys.argv[1:])
    if len(mine) != 1 or not mine[0].isdigit():
        raise SystemExit("usage: stack_interior.py FIRST -- [reconstruction.py arguments]")
    fit.stack_weights = late_picks(int(mine[0]))
    sys.exit(reconstruction.main(rest))
