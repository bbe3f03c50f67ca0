"""Reading ``platform.yaml`` and reading/writing ``results/hydro/platform.nc``.

``platform.nc`` is NetCDF-4 (engine ``netcdf4``), so any NetCDF tool reads it. NetCDF has no
complex type: every complex variable ``v`` is stored as two float variables ``v_real`` and
``v_imag`` and listed in the global attribute ``complex_variables``; :func:`open_platform_nc`
recombines them, so ``write`` then ``open`` round-trips exactly. The file is written to a
temporary sibling and renamed into place (a killed run leaves no half file).
"""

from __future__ import annotations

import os
import uuid
from pathlib import Path

import numpy as np
import xarray as xr

from moorlife.io import read_yaml

__all__ = ["read_platform_config", "write_platform_nc", "open_platform_nc", "split_complex", "merge_complex"]

_REQUIRED = {
    "environment": ("rho_water", "gravity", "water_depth"),
    "platform": ("mass", "cm", "inertia_cm"),
    "tower": ("mass", "cm", "inertia_cm"),
    "rna": ("mass", "cm", "inertia_cm"),
    "turbine": ("rotor_radius", "hub_height", "cut_in", "cut_out", "ct_table"),
}


_NUMERIC = {
    "environment": ("rho_water", "gravity", "water_depth", "rho_air"),
    "platform": ("mass", "cm", "inertia_cm"),
    "tower": ("mass", "cm", "inertia_cm"),
    "rna": ("mass", "cm", "inertia_cm"),
    "turbine": ("rotor_radius", "hub_height", "cut_in", "cut_out", "shutdown_ramp", "startup_ramp"),
    "": ("mooring_stiffness_diag", "morison_strip_length"),
}

#: Fields with a fixed number of values.
_LENGTH = {
    ("platform", "cm"): 3,
    ("tower", "cm"): 3,
    ("rna", "cm"): 3,
    ("platform", "inertia_cm"): 3,
    ("tower", "inertia_cm"): 3,
    ("rna", "inertia_cm"): 3,
    ("", "mooring_stiffness_diag"): 6,
}


def read_platform_config(path: str | os.PathLike[str]) -> dict:
    """Read ``platform.yaml`` and check its blocks; errors name the file and the key.

    Raises
    ------
    ValueError
        On a missing block or field, or an invalid member or Ct table.
    """
    from moorlife.hydro import members_from_config
    from moorlife.turbine import ct_table

    p = Path(path)
    cfg = read_yaml(p)
    for block, keys in _REQUIRED.items():
        if block not in cfg:
            raise ValueError(f"{p}: block '{block}' is missing")
        for k in keys:
            if k not in cfg[block]:
                raise ValueError(f"{p}: {block}.{k} is missing")
    for block, keys in _NUMERIC.items():
        for k in keys:
            v = cfg[block].get(k) if block else cfg.get(k)
            if v is None:
                continue
            vals = np.ravel(np.asarray(v, dtype=object))
            for n, x in enumerate(vals):
                if isinstance(x, bool) or not isinstance(x, (int, float)):
                    where = f"{block}.{k}" if block else k
                    raise ValueError(
                        f"{p}: {where}[{n}] = {x!r} is not a number "
                        "(YAML needs a sign in the exponent: write 1.5e+7, not 1.5e7)"
                    )
    for (block, k), size in _LENGTH.items():
        v = cfg[block].get(k) if block else cfg.get(k)
        if v is None:
            continue
        if np.ndim(v) != 1 or len(v) != size:
            where = f"{block}.{k}" if block else k
            raise ValueError(
                f"{p}: {where} = {v!r} must be a list of {size} numbers" + (" (x, y, z in m)" if k == "cm" else "")
            )
    members_from_config(cfg, str(p))
    ct_table(cfg["turbine"], str(p))
    return cfg


def split_complex(ds: xr.Dataset) -> xr.Dataset:
    """Replace every complex variable ``v`` by ``v_real`` and ``v_imag``."""
    out = ds.copy()
    names = [k for k, v in ds.data_vars.items() if np.iscomplexobj(v.values)]
    for k in names:
        v = out[k]
        out = out.drop_vars(k)
        out[f"{k}_real"] = v.real.assign_attrs(v.attrs)
        out[f"{k}_imag"] = v.imag.assign_attrs(v.attrs)
    out.attrs["complex_variables"] = " ".join(names)
    return out


def merge_complex(ds: xr.Dataset) -> xr.Dataset:
    """Inverse of :func:`split_complex`."""
    out = ds.copy()
    names = str(ds.attrs.get("complex_variables", "")).split()
    for k in names:
        re, im = out[f"{k}_real"], out[f"{k}_imag"]
        out = out.drop_vars([f"{k}_real", f"{k}_imag"])
        out[k] = (re + 1j * im).assign_attrs(re.attrs)
    out.attrs.pop("complex_variables", None)
    return out


def write_platform_nc(ds: xr.Dataset, path: str | os.PathLike[str]) -> Path:
    """Write the hydrodynamic dataset as NetCDF-4, atomically."""
    dst = Path(path)
    dst.parent.mkdir(parents=True, exist_ok=True)
    tmp = dst.parent / f".{dst.name}.tmp-{uuid.uuid4().hex[:8]}"
    out = split_complex(ds)
    for k, v in list(out.attrs.items()):  # NetCDF attributes: no bools, no nested lists
        if isinstance(v, bool):
            out.attrs[k] = int(v)
    try:
        out.to_netcdf(tmp, engine="netcdf4")
        os.replace(tmp, dst)
    finally:
        if tmp.exists():
            tmp.unlink()
    return dst


def open_platform_nc(path: str | os.PathLike[str]) -> xr.Dataset:
    """Read ``platform.nc`` (loaded into memory, complex variables recombined).

    Raises
    ------
    FileNotFoundError, ValueError
        If the file is missing or lacks a contract variable.
    """
    p = Path(path)
    if not p.exists():
        raise FileNotFoundError(f"{p}: no such file")
    with xr.open_dataset(p, engine="netcdf4") as f:
        ds = merge_complex(f.load())
    for v in ("added_mass", "added_mass_inf", "damping", "excitation", "hydrostatic_stiffness"):
        if v not in ds:
            raise ValueError(f"{p}: variable '{v}' is missing (not a moorlife platform.nc)")
    return ds
