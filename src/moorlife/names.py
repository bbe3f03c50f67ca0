"""Dimension names, variable names, units and attributes, defined once (the attribute registry).

Every store in ``results/`` uses these names (see the output contract in the README).
Directions are degrees, nautical convention, "coming from", clockwise from north.
"""

from __future__ import annotations

__all__ = [
    "TIME",
    "CASE",
    "BIN",
    "LINE",
    "LINES",
    "CURVES",
    "METOCEAN_VARS",
    "METOCEAN_ATTRS",
    "SIM_LINE_VARS",
    "SIM_SCALAR_VARS",
    "SIM_ATTRS",
    "GEV_VARS",
    "SIM_EXTRA_SCALAR_VARS",
    "SIM_EXTRA_LINE_VARS",
    "SIM_TIMESERIES_VARS",
    "SIM_EXTRA_ATTRS",
    "SIM_TIMESERIES_ATTRS",
    "SIM_OUTPUT_ATTRS",
    "attrs_for",
    "output_attrs",
    "RBF_SPACES",
    "RBF_TRANSFORMS",
    "RBF_CHOICE_ATTRS",
]

# dimensions
TIME = "time"
CASE = "case"
BIN = "bin"
LINE = "line"
CURVE = "curve"
OMEGA = "omega"
DOF = "dof"
HEADING = "heading"

#: Mooring line labels. M2 points west (270 deg); M1 and M3 are at +-120 deg from it
#: (M1 to the north-east, M3 to the south-east), as OC4 lines 1-3.
LINES: tuple[str, ...] = ("M1", "M2", "M3")
#: Fatigue curve families: S-N (DNVGL-OS-E301) and T-N (API RP 2SK).
CURVES: tuple[str, ...] = ("sn", "tn")
DOFS: tuple[str, ...] = ("surge", "sway", "heave", "roll", "pitch", "yaw")

#: The five sea-state variables, in the order used for the 5-D selection / RBF space.
METOCEAN_VARS: tuple[str, ...] = ("wind_speed", "wind_dir", "hs", "tp", "wave_dir")
#: Which of them are directions (compared on the circle).
DIRECTION_VARS: frozenset[str] = frozenset({"wind_dir", "wave_dir"})

_DIRECTION_COMMENT = "nautical convention: degrees clockwise from north, direction the wind or waves come from"

METOCEAN_ATTRS: dict[str, dict[str, str]] = {
    "hs": {
        "units": "m",
        "standard_name": "sea_surface_wave_significant_height",
        "long_name": "significant wave height",
    },
    "tp": {
        "units": "s",
        "standard_name": "sea_surface_wave_period_at_variance_spectral_density_maximum",
        "long_name": "peak wave period",
    },
    "wave_dir": {
        "units": "degree",
        "standard_name": "sea_surface_wave_from_direction",
        "long_name": "wave direction",
        "comment": _DIRECTION_COMMENT,
    },
    "wind_speed": {
        "units": "m s-1",
        "standard_name": "wind_speed",
        "long_name": "wind speed at hub height",
    },
    "wind_dir": {
        "units": "degree",
        "standard_name": "wind_from_direction",
        "long_name": "wind direction at hub height",
        "comment": _DIRECTION_COMMENT,
    },
}

#: Per-line outputs of one simulated sea state (dims: case or bin, line).
SIM_LINE_VARS: tuple[str, ...] = ("tension_mpm", "damage_sn", "damage_tn")
#: Scalar outputs of one simulated sea state (dim: case or bin).
SIM_SCALAR_VARS: tuple[str, ...] = (
    "surge_mpm",
    "sway_mpm",
    "heave_mpm",
    "accel_mpm",
    "accel_p90",
    "accel_p95",
    "accel_p99",
)
#: Variables whose most probable maximum comes from a GEV fit; each has a
#: ``gev_corr_<name>`` companion with the fit quality (paper Table 5).
GEV_VARS: tuple[str, ...] = ("surge_mpm", "sway_mpm", "heave_mpm", "tension_mpm", "accel_mpm")

SIM_ATTRS: dict[str, dict[str, str]] = {
    "surge_mpm": {"units": "m", "long_name": "most probable maximum of |surge| offset"},
    "sway_mpm": {"units": "m", "long_name": "most probable maximum of |sway| offset"},
    "heave_mpm": {"units": "m", "long_name": "most probable maximum of |heave| offset"},
    "tension_mpm": {"units": "N", "long_name": "most probable maximum of fairlead tension"},
    "damage_sn": {"units": "1", "long_name": "S-N (DNVGL-OS-E301) Miner damage per hour of sea state"},
    "damage_tn": {"units": "1", "long_name": "T-N (API RP 2SK) Miner damage per hour of sea state"},
    "accel_mpm": {"units": "m s-2", "long_name": "most probable maximum of nacelle acceleration"},
    "accel_p90": {"units": "m s-2", "long_name": "90 % percentile of nacelle acceleration"},
    "accel_p95": {"units": "m s-2", "long_name": "95 % percentile of nacelle acceleration"},
    "accel_p99": {"units": "m s-2", "long_name": "99 % percentile of nacelle acceleration"},
}
for _name in GEV_VARS:
    SIM_ATTRS[f"gev_corr_{_name}"] = {
        "units": "1",
        "long_name": f"correlation of empirical and GEV-fitted distribution of maxima ({_name})",
    }


#: Extra scalar outputs of one simulated sea state, beyond the contract's ``SIM_SCALAR_VARS``.
SIM_EXTRA_SCALAR_VARS: tuple[str, ...] = (
    "surge_mean",
    "sway_mean",
    "heave_mean",
    "pitch_mean",
    "surge_std",
    "pitch_mpm",
    "offset_max",
    "gev_corr_pitch_mpm",
)
#: Extra per-line outputs of one simulated sea state.
SIM_EXTRA_LINE_VARS: tuple[str, ...] = ("tension_mean", "tension_std", "tension_max")
#: Time series kept when ``simulation.keep_timeseries`` is true: (B, nt) or (B, 3, nt).
SIM_TIMESERIES_VARS: tuple[str, ...] = (
    "ts_surge",
    "ts_sway",
    "ts_heave",
    "ts_roll",
    "ts_pitch",
    "ts_yaw",
    "ts_accel",
    "ts_tension",
)
SIM_EXTRA_ATTRS: dict[str, dict[str, str]] = {
    "surge_mean": {"units": "m", "long_name": "mean surge offset"},
    "sway_mean": {"units": "m", "long_name": "mean sway offset"},
    "heave_mean": {"units": "m", "long_name": "mean heave offset"},
    "pitch_mean": {"units": "deg", "long_name": "mean pitch angle"},
    "surge_std": {"units": "m", "long_name": "standard deviation of surge"},
    "pitch_mpm": {"units": "deg", "long_name": "most probable maximum of |pitch|"},
    "offset_max": {"units": "m", "long_name": "largest horizontal offset in the record"},
    "tension_mean": {"units": "N", "long_name": "mean fairlead tension"},
    "tension_std": {"units": "N", "long_name": "standard deviation of fairlead tension"},
    "tension_max": {"units": "N", "long_name": "largest fairlead tension in the record"},
    "gev_corr_pitch_mpm": {"units": "1", "long_name": "GEV fit correlation (pitch_mpm)"},
}
_TS_UNITS = {"ts_tension": "N", "ts_accel": "m s-2", "ts_roll": "rad", "ts_pitch": "rad", "ts_yaw": "rad"}
SIM_TIMESERIES_ATTRS: dict[str, dict[str, str]] = {
    _name: {"units": _TS_UNITS.get(_name, "m"), "long_name": f"time series of {_name[3:]} after the transient"}
    for _name in SIM_TIMESERIES_VARS
}
#: Attributes of every output of ``moorlife.simulate.simulate_batch``: the contract's
#: ``SIM_ATTRS``, the extras and the time series.
SIM_OUTPUT_ATTRS: dict[str, dict[str, str]] = {**SIM_ATTRS, **SIM_EXTRA_ATTRS, **SIM_TIMESERIES_ATTRS}


#: Candidate input spaces of the RBF reconstruction (``moorlife.lifecycle.spaces``): the paper's
#: normalised 5-D space, the same plus the rotor thrust T(W) at the hub wind speed, the 5-D
#: space with a weight on each scalar coordinate (``lifecycle.rbf.weights``), and the 5-D space
#: with a piecewise-linear trend in the wind speed (``lifecycle.rbf.wind_trend``).
RBF_SPACE_PAPER = "paper"
RBF_SPACE_THRUST = "thrust"
RBF_SPACE_WEIGHTED = "weighted"
RBF_SPACE_WIND_TREND = "wind_trend"
RBF_SPACES: tuple[str, ...] = (RBF_SPACE_PAPER, RBF_SPACE_THRUST, RBF_SPACE_WEIGHTED, RBF_SPACE_WIND_TREND)
#: Transforms of a rebuilt output: interpolated as is, or as log10 and back-transformed.
RBF_TRANSFORMS: tuple[str, ...] = ("linear", "log10")
#: The reconstruction's choice per output in ``lifecycle.zarr`` (dim ``output``), and the root
#: attributes ``rbf_choose`` and ``rbf_retransform`` (the ``lifecycle.rbf`` keys in force).
RBF_INPUT_SPACE = "input_space"
RBF_TRANSFORM = "transform"
RBF_LOG_FACTOR = "retransform_factor"
RBF_LOO_RMSE_UNITS = "loo_rmse_units"
RBF_CHOICE_ATTRS: dict[str, dict[str, str]] = {
    RBF_INPUT_SPACE: {
        "units": "1",
        "long_name": "RBF input space (paper: 5-D; thrust: + T(W); weighted: scalars weighted; paper:w+thrust:1-w: a blend, choose: stack)",
    },
    RBF_TRANSFORM: {"units": "1", "long_name": "RBF transform of the output (linear or log10)"},
    RBF_LOG_FACTOR: {"units": "1", "long_name": "back-transform factor c of a log10 output (c 10**f; 1: none)"},
    RBF_LOO_RMSE_UNITS: {"units": "1", "long_name": "leave-one-out RMSE in the output's units (training states)"},
}


def output_attrs(name: str) -> dict[str, str]:
    """Attributes of any output of ``moorlife.simulate.simulate_batch`` (contract or extra).

    Raises
    ------
    KeyError
        If ``name`` is not an output of the simulator.
    """
    if name in SIM_OUTPUT_ATTRS:
        return dict(SIM_OUTPUT_ATTRS[name])
    raise KeyError(f"{name!r} is not an output of simulate_batch")


def attrs_for(name: str) -> dict[str, str]:
    """Return the CF-style attributes of a contract variable.

    Parameters
    ----------
    name : str
        A metocean or simulation variable name.

    Returns
    -------
    dict
        A copy of its attributes (at least ``units``).

    Raises
    ------
    KeyError
        If the name is not part of the output contract.
    """
    if name in METOCEAN_ATTRS:
        return dict(METOCEAN_ATTRS[name])
    if name in SIM_ATTRS:
        return dict(SIM_ATTRS[name])
    raise KeyError(f"{name!r} is not a contract variable")
