"""Validation of the mooring-system table (``config/mooring_systems.tsv``)."""

from __future__ import annotations

import re

import numpy as np
import pandas as pd

__all__ = ["MOORING_COLUMNS", "validate_mooring_systems"]

#: column -> (description, units); every column is required.
MOORING_COLUMNS: dict[str, tuple[str, str]] = {
    "mooring_system": ("identifier used in results/{ms}/, e.g. MS1", ""),
    "mass_kg_per_m": ("chain mass per unit length in air", "kg m-1"),
    "pretension_kN": ("fairlead pretension at rest (paper Table 4)", "kN"),
    "link_diameter_mm": ("nominal chain link diameter d", "mm"),
    "equivalent_diameter_m": ("hydrodynamic equivalent diameter of the chain", "m"),
    "EA_N": ("axial stiffness", "N"),
    "MBS_N": ("minimum breaking strength", "N"),
    "chain": ("chain type: studless or stud", ""),
}
_ID = re.compile(r"^[A-Za-z0-9_-]+$")


def validate_mooring_systems(df: pd.DataFrame, source: str = "mooring_systems.tsv") -> pd.DataFrame:
    """Check the table and index it by ``mooring_system``.

    Raises
    ------
    ValueError
        Naming the file, column, row and value of the first problem.
    """
    missing = [c for c in MOORING_COLUMNS if c not in df.columns]
    if missing:
        # the found names are never echoed: a wrong path may name a file with secrets in it
        raise ValueError(
            f"{source}: missing column(s) {missing}; expected the tab-separated columns {list(MOORING_COLUMNS)} "
            f"(the file's header has {len(df.columns)} column(s))"
        )
    if df.empty:
        raise ValueError(f"{source}: no mooring systems defined")
    for i, ms in enumerate(df["mooring_system"], start=2):
        if not isinstance(ms, str) or not _ID.match(ms):
            raise ValueError(f"{source}: row {i}, column 'mooring_system': {ms!r} is not a valid id ([A-Za-z0-9_-]+)")
    dup = df["mooring_system"][df["mooring_system"].duplicated()]
    if len(dup):
        raise ValueError(f"{source}: column 'mooring_system': duplicated id {dup.iloc[0]!r}")
    for col in MOORING_COLUMNS:
        if col in ("mooring_system", "chain"):
            continue
        values = pd.to_numeric(df[col], errors="coerce").to_numpy(dtype=float)
        bad = ~(np.isfinite(values) & (values > 0))
        if bad.any():
            i = int(np.flatnonzero(bad)[0])
            raise ValueError(
                f"{source}: row {i + 2} ({df['mooring_system'].iloc[i]}), column {col!r}: "
                f"{df[col].iloc[i]} must be a positive number"
            )
        df[col] = values
    weak = df["MBS_N"].to_numpy() <= 1e3 * df["pretension_kN"].to_numpy()
    if weak.any():
        i = int(np.flatnonzero(weak)[0])
        raise ValueError(
            f"{source}: row {i + 2} ({df['mooring_system'].iloc[i]}): MBS_N = {df['MBS_N'].iloc[i]:g} N is not above "
            f"the pretension pretension_kN = {df['pretension_kN'].iloc[i]:g} kN ({1e3 * df['pretension_kN'].iloc[i]:g} N): "
            "the line would break at rest (check the units: MBS in N, pretension in kN)"
        )
    bad_chain = ~df["chain"].isin(["studless", "stud"])
    if bad_chain.any():
        i = int(np.flatnonzero(bad_chain.to_numpy())[0])
        raise ValueError(f"{source}: row {i + 2}, column 'chain': {df['chain'].iloc[i]!r} must be 'studless' or 'stud'")
    return df.set_index("mooring_system", drop=False)
