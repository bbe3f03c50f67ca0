"""Physical checks of hindcast sea states: breaking steepness, a floor on Tp, constant inputs.

Pure functions, numpy in, masks and reports out; the reader (:mod:`moorlife.io.hindcast`)
applies them and names the file, row and value.

Limits
------
* **Breaking steepness.** A sea state with ``Hs / (g / (2 pi) Tp^2) > 1/7`` cannot exist: the
  waves break (Stokes limit, DNV-RP-C205 section 3.5.5.4 on the steepness ``S = 2 pi Hs /
  (g Tp^2)``; ``g / (2 pi) = 1.56 m/s2``). Design sea states keep ``S <= 1/15`` for
  ``Tp >= 15 s`` and ``S <= 1/10`` for ``Tp <= 8 s``; 1/7 is the absolute bound.
* **A floor on Tp,** :data:`TP_FLOOR` = 1.0 s. Below it no sea state of interest exists and
  no hindcast resolves it: the highest frequency of the ERA5 and NORA3 (WAM) spectra is
  0.548 Hz, a period of 1.8 s, so a Tp under 1 s is a unit or coding error (Tp in ms, a frequency
  in Hz). With the steepness limit, Tp = 1 s allows Hs up to 0.22 m only.
* **Constant inputs.** The 5-D selection normalises every variable by its range and the RBF
  reconstruction needs every coordinate to vary: a variable that never changes over the study
  period (an all-zero wind column) is refused up front, naming the variable.

Policies (``sea_states``)
-------------------------
``error`` (default)
    Refuse the file at the first impossible state.
``drop``
    The impossible rows become missing hours (gaps), which the cleaning policy then
    interpolates up to ``hindcast.cleaning.max_gap_hours`` or refuses.
``clip``
    Keep Hs and raise Tp to the smallest period allowed (:func:`clipped_tp`).
Every row dropped or clipped is logged by the reader.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

__all__ = [
    "G_OVER_2PI",
    "BREAKING_STEEPNESS",
    "TP_FLOOR",
    "SEA_STATE_POLICIES",
    "SeaStateReport",
    "steepness",
    "check_sea_states",
    "clipped_tp",
    "constant_columns",
]

#: g / (2 pi) in m/s2 (g = 9.80665): deep-water wavelength L = 1.56 T^2.
G_OVER_2PI: float = 9.80665 / (2.0 * np.pi)
#: Largest steepness Hs / (1.56 Tp^2) of a sea state (breaking limit).
BREAKING_STEEPNESS: float = 1.0 / 7.0
#: Smallest Tp in s accepted from a hindcast (see the module notes).
TP_FLOOR: float = 1.0
#: Values of the ``sea_states`` policy.
SEA_STATE_POLICIES: tuple[str, ...] = ("error", "drop", "clip")


@dataclass(frozen=True)
class SeaStateReport:
    """Which rows are impossible, and why.

    Attributes
    ----------
    too_steep : ndarray of bool, shape (n,)
        Steepness above the limit.
    too_short : ndarray of bool, shape (n,)
        Tp below the floor.
    steepness : ndarray, shape (n,)
        Hs / (1.56 Tp^2); NaN where Hs or Tp is missing or not positive (those rows are left
        to the range checks of the validation).
    """

    too_steep: np.ndarray
    too_short: np.ndarray
    steepness: np.ndarray

    @property
    def bad(self) -> np.ndarray:
        """Rows that break either limit."""
        return self.too_steep | self.too_short

    def reason(self, i: int, max_steepness: float = BREAKING_STEEPNESS, tp_floor: float = TP_FLOOR) -> str:
        """Why row ``i`` is impossible, in words."""
        if self.too_short[i]:
            return f"Tp is below the floor of {tp_floor:g} s"
        return (
            f"steepness Hs / (1.56 Tp^2) = {self.steepness[i]:.3g} exceeds the breaking limit "
            f"{max_steepness:.4g} (1/{1.0 / max_steepness:.3g}, DNV-RP-C205)"
        )


def steepness(hs: npt.ArrayLike, tp: npt.ArrayLike) -> np.ndarray:
    """``Hs / (g / (2 pi) Tp^2)``, dimensionless; NaN where Hs or Tp is missing or <= 0."""
    h = np.asarray(hs, dtype=float)
    t = np.asarray(tp, dtype=float)
    ok = np.isfinite(h) & np.isfinite(t) & (h > 0) & (t > 0)
    out = np.full(np.broadcast(h, t).shape, np.nan)
    with np.errstate(divide="ignore", invalid="ignore"):
        s = h / (G_OVER_2PI * t * t)
    out[ok] = np.broadcast_to(s, out.shape)[ok]
    return out


def check_sea_states(
    hs: npt.ArrayLike,
    tp: npt.ArrayLike,
    *,
    max_steepness: float = BREAKING_STEEPNESS,
    tp_floor: float = TP_FLOOR,
) -> SeaStateReport:
    """Flag the physically impossible sea states.

    Parameters
    ----------
    hs, tp : array_like, shape (n,)
        Significant wave height in m and peak period in s. Missing or non-positive values are
        not flagged (the validation reports them with its own message).
    max_steepness : float
        Breaking limit of ``Hs / (1.56 Tp^2)``.
    tp_floor : float
        Smallest Tp in s.

    Returns
    -------
    SeaStateReport
    """
    if not (0 < max_steepness and 0 < tp_floor):
        raise ValueError(f"max_steepness and tp_floor must be positive, got {max_steepness!r}, {tp_floor!r}")
    s = steepness(hs, tp)
    t = np.asarray(tp, dtype=float)
    valid = np.isfinite(s)
    too_short = valid & (t < tp_floor)
    too_steep = valid & (s > max_steepness)
    return SeaStateReport(too_steep=too_steep, too_short=too_short, steepness=s)


def clipped_tp(
    hs: npt.ArrayLike,
    tp: npt.ArrayLike,
    *,
    max_steepness: float = BREAKING_STEEPNESS,
    tp_floor: float = TP_FLOOR,
) -> np.ndarray:
    """Tp raised to the smallest period allowed for its Hs: ``max(Tp, floor, sqrt(Hs / (1.56 S_max)))``.

    Rows with a missing or non-positive Hs or Tp are returned unchanged.
    """
    h = np.asarray(hs, dtype=float)
    t = np.asarray(tp, dtype=float)
    ok = np.isfinite(steepness(h, t))
    with np.errstate(invalid="ignore"):
        lowest = np.maximum(tp_floor, np.sqrt(np.where(ok, h, 0.0) / (G_OVER_2PI * max_steepness)))
    # the square root may round a hair below the limit: nudge up to the next float
    lowest = np.where(
        np.where(ok, h, 0.0) / (G_OVER_2PI * lowest * lowest) > max_steepness, np.nextafter(lowest, np.inf), lowest
    )
    return np.where(ok, np.maximum(t, lowest), t)


def constant_columns(values: dict[str, npt.ArrayLike]) -> list[str]:
    """Names of the variables whose finite values are all equal (or that have fewer than two).

    A constant coordinate has no range to normalise by and leaves the RBF system singular.
    """
    out = []
    for name, v in values.items():
        x = np.asarray(v, dtype=float)
        x = x[np.isfinite(x)]
        if x.size < 2 or float(np.ptp(x)) == 0.0:
            out.append(name)
    return out
