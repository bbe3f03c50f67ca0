"""moorlife: life-cycle fatigue of floating offshore wind turbine moorings.

Numerical kernels are pure (numpy in, numpy out); thin xarray adapters sit on top; all
disk access is in :mod:`moorlife.io`; Dask orchestration is in :mod:`moorlife.parallel`.
"""

__version__ = "0.1.0"

from pathlib import Path as _Path

from moorlife import _numba_cache

#: Numba's cache directory for this source (a fresh one after any edit: ``_numba_cache``)
NUMBA_CACHE_DIR = _numba_cache.pin(_Path(__file__).resolve().parent)
