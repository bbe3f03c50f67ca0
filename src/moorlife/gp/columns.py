"""A scikit-learn kernel that sees some input columns only (the additive wind term of :func:`~moorlife.gp.fit_gp`).

scikit-learn's kernels act on every column of their input. The additive term of
:func:`moorlife.gp.fit_gp` is a Matérn or squared-exponential kernel of the wind speed and
direction alone, added to the one of every coordinate; :class:`OnColumns` wraps the base kernel
and hands it those columns. Its hyperparameters, their bounds and their gradient are the base
kernel's, so scikit-learn's marginal-likelihood fit treats it as any other kernel.

Imported by :func:`moorlife.gp.fit_gp` only (scikit-learn is imported lazily there).
"""

from __future__ import annotations

from typing import Any

import numpy as np
from sklearn.gaussian_process.kernels import Hyperparameter, Kernel

__all__ = ["OnColumns"]


class OnColumns(Kernel):
    """``base(x[:, columns], x'[:, columns])``.

    Parameters
    ----------
    base : sklearn.gaussian_process.kernels.Kernel
        A stationary kernel with one length scale per column in ``columns`` (or one for all).
    columns : tuple of int
        The input columns the kernel sees, in order (kept as given: scikit-learn's ``clone``
        rebuilds the kernel from its parameters and checks they are the same objects).
    """

    def __init__(self, base: Kernel, columns: tuple[int, ...]) -> None:
        self.base = base
        self.columns = columns

    @property
    def hyperparameters(self) -> list[Hyperparameter]:
        return self.base.hyperparameters

    @property
    def theta(self) -> np.ndarray:
        return self.base.theta

    @theta.setter
    def theta(self, theta: np.ndarray) -> None:
        self.base.theta = theta

    @property
    def bounds(self) -> np.ndarray:
        return self.base.bounds

    def get_params(self, deep: bool = True) -> dict[str, Any]:
        params: dict[str, Any] = {"base": self.base, "columns": self.columns}
        if deep:
            params.update({f"base__{k}": v for k, v in self.base.get_params(deep=True).items()})
        return params

    def __call__(self, X: np.ndarray, Y: np.ndarray | None = None, eval_gradient: bool = False) -> Any:
        c = list(self.columns)
        return self.base(X[:, c], None if Y is None else Y[:, c], eval_gradient=eval_gradient)

    def diag(self, X: np.ndarray) -> np.ndarray:
        return self.base.diag(X[:, list(self.columns)])

    def is_stationary(self) -> bool:
        return self.base.is_stationary()

    @property
    def requires_vector_input(self) -> bool:
        return True
