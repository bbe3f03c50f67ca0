"""moorlife: life-cycle fatigue of floating offshore wind turbine moorings.

Numerical kernels are pure (numpy in, numpy out); thin xarray adapters sit on top; all
disk access is in :mod:`moorlife.io`; Dask orchestration is in :mod:`moorlife.parallel`.
"""

__version__ = "0.1.0"
