"""scikit-learn kernels for the additive wind term of :func:`~moorlife.gp.fit_gp`.

scikit-learn's kernels act on every column of their input. The wind term is a Matérn or
squared-exponential kernel of the wind speed and direction alone (:class:`OnColumns`), faded
out as the sea grows (:class:`SeaGate`): a line's damage follows the wind where the waves are
small, and the waves where they are large. Their hyperparameters, bounds and gradients are
scikit-learn's, so its marginal-likelihood fit treats them as any other kernel.

Imported by :func:`moorlife.gp.fit_gp` only (scikit-learn is imported lazily there).
"""

from __future__ import annotations

from typing import Any

import numpy as np
from sklearn.gaussian_process.kernels import Hyperparameter, Kernel

from moorlife.gp.covariance import gate

__all__ = ["OnColumns", "SeaGate"]


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


class SeaGate(Kernel):
    """``g(x) g(x') base(x, x')`` with ``g = exp(-x[:, column] / scale)`` (:func:`moorlife.gp.covariance.gate`).

    A positive-definite kernel for any ``scale`` (a product of a rank-one and a positive-definite
    matrix, elementwise). ``scale`` is a hyperparameter (fitted in log, within ``scale_bounds``),
    listed before the base kernel's.

    Parameters
    ----------
    base : sklearn.gaussian_process.kernels.Kernel
    column : int
        The input column of the normalised wave height.
    scale : float
    scale_bounds : pair of float, or "fixed"
    """

    def __init__(self, base: Kernel, column: int, scale: float = 0.2, scale_bounds: Any = (0.02, 2.0)) -> None:
        self.base = base
        self.column = column
        self.scale = scale
        self.scale_bounds = scale_bounds

    @property
    def _fitted_scale(self) -> bool:
        return not (isinstance(self.scale_bounds, str) and self.scale_bounds == "fixed")

    @property
    def hyperparameters(self) -> list[Hyperparameter]:
        return [Hyperparameter("scale", "numeric", self.scale_bounds), *self.base.hyperparameters]

    @property
    def theta(self) -> np.ndarray:
        own = [np.log(self.scale)] if self._fitted_scale else []
        return np.concatenate([own, self.base.theta])

    @theta.setter
    def theta(self, theta: np.ndarray) -> None:
        if self._fitted_scale:
            self.scale = float(np.exp(theta[0]))
            theta = theta[1:]
        self.base.theta = theta

    @property
    def bounds(self) -> np.ndarray:
        if not self._fitted_scale:
            return self.base.bounds
        return np.vstack([np.log(np.atleast_2d(np.asarray(self.scale_bounds, dtype=float))), self.base.bounds])

    def get_params(self, deep: bool = True) -> dict[str, Any]:
        params: dict[str, Any] = {
            "base": self.base,
            "column": self.column,
            "scale": self.scale,
            "scale_bounds": self.scale_bounds,
        }
        if deep:
            params.update({f"base__{k}": v for k, v in self.base.get_params(deep=True).items()})
        return params

    def __call__(self, X: np.ndarray, Y: np.ndarray | None = None, eval_gradient: bool = False) -> Any:
        gx = gate(X[:, self.column], self.scale)
        if not eval_gradient:
            gy = gx if Y is None else gate(Y[:, self.column], self.scale)
            return np.outer(gx, gy) * self.base(X, Y)
        if Y is not None:
            raise ValueError("the gradient is only available when Y is None")
        w = np.outer(gx, gx)
        k, dk = self.base(X, None, eval_gradient=True)
        parts = [w[:, :, None] * dk]
        if self._fitted_scale:  # d/d log(scale) of g(x) g(x') = g g' (a + a'), a = x / scale
            a = X[:, self.column] / self.scale
            parts.insert(0, (w * k * (a[:, None] + a[None, :]))[:, :, None])
        return w * k, np.concatenate(parts, axis=2)

    def diag(self, X: np.ndarray) -> np.ndarray:
        return gate(X[:, self.column], self.scale) ** 2 * self.base.diag(X)

    def is_stationary(self) -> bool:
        return False

    @property
    def requires_vector_input(self) -> bool:
        return True
