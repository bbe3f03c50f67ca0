"""Frames, direction conventions and seeds shared by every module.

Global frame (the paper's): origin at the still water line on the platform centreline,
``x`` from west to east, ``y`` from south to north, ``z`` up. Metocean directions are
nautical, degrees clockwise from north, the direction the wind or waves come *from*.
Capytaine and the simulator use the mathematical *propagation* angle: radians,
counter-clockwise from ``+x``, the direction the waves travel *to*.

Random streams derive from ``(global seed, mooring system, case id)`` only, never from a
worker or the order of execution, so results do not depend on scheduling.
"""

from __future__ import annotations

import zlib

import numpy as np
import numpy.typing as npt

__all__ = [
    "propagation_angle",
    "nautical_from_propagation",
    "flow_vector",
    "circular_difference",
    "case_rng",
    "case_seed_sequence",
]


def propagation_angle(nautical_from_deg: npt.ArrayLike) -> np.ndarray:
    """Convert a nautical "coming from" direction to a propagation angle.

    Parameters
    ----------
    nautical_from_deg : array_like
        Degrees clockwise from north, direction of origin.

    Returns
    -------
    numpy.ndarray
        Radians counter-clockwise from ``+x`` (east), direction of travel, in ``[-pi, pi)``.

    Examples
    --------
    Waves from the west (270 deg) travel east (0 rad):

    >>> float(propagation_angle(270.0))
    0.0
    """
    theta = np.deg2rad(270.0 - np.asarray(nautical_from_deg, dtype=float))
    return (theta + np.pi) % (2.0 * np.pi) - np.pi


def nautical_from_propagation(angle_rad: npt.ArrayLike) -> np.ndarray:
    """Inverse of :func:`propagation_angle`, in ``[0, 360)`` degrees."""
    return (270.0 - np.rad2deg(np.asarray(angle_rad, dtype=float))) % 360.0


def flow_vector(nautical_from_deg: npt.ArrayLike) -> np.ndarray:
    """Unit vector ``(..., 2)`` in ``(x, y)`` of the direction of travel."""
    theta = propagation_angle(nautical_from_deg)
    return np.stack([np.cos(theta), np.sin(theta)], axis=-1)


def circular_difference(a_deg: npt.ArrayLike, b_deg: npt.ArrayLike) -> np.ndarray:
    """Absolute angular difference folded to ``[0, 180]`` degrees."""
    d = np.abs(np.asarray(a_deg, dtype=float) - np.asarray(b_deg, dtype=float)) % 360.0
    return np.minimum(d, 360.0 - d)


def _stable_key(name: str) -> int:
    return zlib.crc32(name.encode("utf-8"))


def case_seed_sequence(seed: int, mooring_system: str, case_id: int, stream: str = "case") -> np.random.SeedSequence:
    """The seed sequence of one simulated sea state.

    Parameters
    ----------
    seed : int
        The study's global seed (``config.yaml: seed``).
    mooring_system : str
        Mooring-system id, e.g. ``"MS3"``; hashed with CRC-32 so it is stable across
        processes and Python versions (unlike ``hash``).
    case_id : int
        The sea state's id along its dimension (``case``, or ``bin`` for the discrete matrix).
    stream : str
        The dimension the id belongs to. ``"case"`` (training and validation states) keeps
        the entropy ``[seed, system, id]``; any other stream appends its CRC-32, so bin 3 of
        the scatter matrix and case 3 of the selection get independent phases.
    """
    entropy = [int(seed), _stable_key(mooring_system), int(case_id)]
    if stream != "case":
        entropy.append(_stable_key(stream))
    return np.random.SeedSequence(entropy)


def case_rng(seed: int, mooring_system: str, case_id: int, stream: str = "case") -> np.random.Generator:
    """A PCG64 generator for one sea state, see :func:`case_seed_sequence`."""
    return np.random.default_rng(case_seed_sequence(seed, mooring_system, case_id, stream))
