"""Mooring-line fatigue: rainflow counting, S-N and T-N Miner damage, corrosion,
mean-stress corrections and design fatigue factors (paper section 2.4 and section 4).

Everything here is a pure numerical kernel: numpy in, numpy out, SI units unless a
name says otherwise (stresses in MPa, as the S-N curves are written).

Conventions
-----------
* Tension in N, link (bar) diameter ``d`` in **m**, time in s, ages in years.
* S-N (DNVGL-OS-E301): ``N = a_D * S**-m`` with ``S`` the stress range in MPa on the
  nominal area of the two legs of a link, ``A_c = 2 * pi * d**2 / 4``.
* T-N (API RP 2SK): ``N * R**M = K`` with ``R = tension range / RBS`` (reference
  breaking strength = the chain's MBS).
* Miner's sum ``D = sum(n_i / N_i)``, no endurance limit (every cycle counts).
* Damage of a simulated record is reported **per hour of sea state**: the record's
  damage times ``3600 / duration``.

Rainflow counting follows ASTM E1049-85 section 5.4.4 (three-point rule) on the exact
turning points, with no binning; the residue counts as half cycles (``residue="half"``)
or is closed as if the record repeated (``residue="close"``: the cycles of one period of
the repeated record, ASTM E1049-85 5.4.5; the residue is joined with itself as in Marsh et
al. 2016 / fatpack).

The package holds one concept per module; everything is re-exported here, so that
``from moorlife.fatigue import rainflow`` and ``fatigue.hourly_damage`` work as before:

* :mod:`moorlife.fatigue.curves`: S-N and T-N curves, :class:`FatigueSettings`;
* :mod:`moorlife.fatigue.counting`: rainflow counting (compiled kernels; the module is not
  called ``rainflow``, which would be shadowed by the function :func:`rainflow` here);
* :mod:`moorlife.fatigue.chain`: stress area, R4S break load, corroded properties, mean stress;
* :mod:`moorlife.fatigue.damage`: Miner damage per hour of sea state;
* :mod:`moorlife.fatigue.design`: design fatigue factors;
* :mod:`moorlife.fatigue.life`: corrosion over the life, fatigue life, life summary;
* :mod:`moorlife.fatigue.spectral`: narrow-band and Dirlik estimates.
"""

# module constants, re-exported outside __all__ as before the split
from moorlife.fatigue.chain import MEAN_STRESS_METHODS as MEAN_STRESS_METHODS
from moorlife.fatigue.chain import (
    corroded_properties,
    mean_stress_factor,
    r4s_break_load,
    stress_area,
)
from moorlife.fatigue.counting import RESIDUE_METHODS as RESIDUE_METHODS
from moorlife.fatigue.counting import rainflow, rainflow_reference, turning_points
from moorlife.fatigue.curves import CHAINS as CHAINS
from moorlife.fatigue.curves import (
    DEFAULT_CURVES,
    FatigueSettings,
    SNCurve,
    TNCurve,
    fatigue_settings,
    get_curves,
)
from moorlife.fatigue.damage import SECONDS_PER_HOUR as SECONDS_PER_HOUR
from moorlife.fatigue.damage import (
    cycle_damage,
    hourly_damage,
    hourly_damage_xr,
    sn_damage,
    tn_damage,
)
from moorlife.fatigue.design import adjacent_damage_ratio, design_fatigue_factor
from moorlife.fatigue.life import HOURS_PER_YEAR as HOURS_PER_YEAR
from moorlife.fatigue.life import (
    annual_damage,
    corrosion_damage_factor,
    fatigue_life,
    life_summary,
    lifetime_damage_with_corrosion,
)
from moorlife.fatigue.spectral import dirlik_damage, dirlik_pdf, narrowband_damage, spectral_moments

__all__ = [
    "SNCurve",
    "TNCurve",
    "DEFAULT_CURVES",
    "FatigueSettings",
    "fatigue_settings",
    "get_curves",
    "turning_points",
    "rainflow",
    "rainflow_reference",
    "stress_area",
    "r4s_break_load",
    "corroded_properties",
    "mean_stress_factor",
    "sn_damage",
    "tn_damage",
    "cycle_damage",
    "hourly_damage",
    "hourly_damage_xr",
    "corrosion_damage_factor",
    "lifetime_damage_with_corrosion",
    "fatigue_life",
    "design_fatigue_factor",
    "adjacent_damage_ratio",
    "annual_damage",
    "life_summary",
    "spectral_moments",
    "narrowband_damage",
    "dirlik_damage",
    "dirlik_pdf",
]
