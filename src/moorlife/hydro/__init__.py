"""Interim step of the split of moorlife.hydro into a sub-package: the old module, moved whole
to mesh.py so that its history follows; the next commit splits it along its banners."""

from moorlife.hydro.mesh import *  # noqa: F403
from moorlife.hydro.mesh import __all__  # noqa: F401
