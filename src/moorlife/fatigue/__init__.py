"""Interim step of the split of moorlife.fatigue into a sub-package: the old module, moved whole
to life.py so that its history follows; the next commit splits it along its banners."""

from moorlife.fatigue.life import *  # noqa: F403
from moorlife.fatigue.life import __all__  # noqa: F401
