"""The result of a fit: parameters, their uncertainty, the data, the model and its residuals."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np

from ..effects._protocol import Result

__all__ = ["FitResult"]


@dataclass(frozen=True, eq=False)
class FitResult(Result):
    """Fitted parameters of a measured curve with their uncertainty.

    Attributes
    ----------
    params : dict
        Fitted (free) and fixed parameters by name, SI units (``E`` Pa, ``contact_point`` m,
        ``force_offset`` N, ``work_of_adhesion`` J/m², ``friction``, ``shear_modulus`` Pa).
    free : tuple of str
        The names that were fitted, in the order of :attr:`covariance`.
    stderr : dict
        Standard error of each free parameter (square root of the covariance's diagonal).
    covariance : ndarray
        ``s² (JᵀJ)⁻¹`` at the solution, ``s²`` the residual variance ``Σr²/(n - p)``.
    x, y : ndarray
        The data: the control (``depth`` m, ``displacement`` m or ``twist`` rad) and the
        measured response (``force`` N, ``tangential_force`` N or ``torque`` N·m).
    model : ndarray
        The fitted model at ``x``.
    residuals : ndarray
        ``model - y``.
    contact : Contact
        The fitted contact (profile and the materials with the fitted moduli).
    dof : int
        Degrees of freedom ``n - p``.
    nfev : int
        Model evaluations of the solver.
    meta : dict
        ``notes`` (warnings raised), ``citations``, ``model_errors`` and ``x_name``/``y_name``.
    """

    params: dict
    free: tuple
    stderr: dict
    covariance: np.ndarray
    x: np.ndarray
    y: np.ndarray
    model: np.ndarray
    residuals: np.ndarray
    contact: Any
    dof: int
    nfev: int
    meta: dict = field(default_factory=dict)

    units: ClassVar[dict[str, str]] = {
        "depth": "m", "force": "N", "force_fit": "N", "force_residual": "N",
        "displacement": "m", "tangential_force": "N", "tangential_force_fit": "N",
        "tangential_force_residual": "N",
        "twist": "rad", "torque": "N*m", "torque_fit": "N*m", "torque_residual": "N*m"}

    @property
    def citations(self) -> Any:
        """Sources of the model (see :func:`contactlab.cite`)."""
        return self.meta.get("citations", ("PH", "H1"))

    def to_dict(self) -> dict[str, Any]:
        """The data, the fitted model and the residuals by column (SI): ``<x>``, ``<y>``,
        ``<y>_fit``, ``<y>_residual`` (``depth``/``force``, ``displacement``/
        ``tangential_force``, ``twist``/``torque``)."""
        xn, yn = self.meta.get("x_name", "depth"), self.meta.get("y_name", "force")
        return {xn: self.x, yn: self.y, f"{yn}_fit": self.model, f"{yn}_residual": self.residuals}

    def confidence(self, level: float = 0.95) -> dict[str, tuple[float, float]]:
        """Confidence interval of each free parameter, ``value ± t·stderr`` with Student's t of
        :attr:`dof` degrees of freedom.

        Parameters
        ----------
        level : float
            Confidence level, ``0 < level < 1``.

        Raises
        ------
        ParameterError
            ``level`` outside (0, 1).
        """
        from ..params.checks import check_in_range
        lv = check_in_range("level", level, 0.0, 1.0, low_open=True, high_open=True,
                            what="the confidence level (e.g. 0.95)", unit="1")
        from scipy.stats import t
        q = float(t.ppf(0.5 + lv / 2.0, max(self.dof, 1)))
        return {k: (self.params[k] - q * self.stderr[k], self.params[k] + q * self.stderr[k])
                for k in self.free}

    def _model_errors(self) -> dict[str, Any]:
        return dict(self.meta.get("tip_model_errors", {}))

    def plot(self, ax: Any = None) -> Any:
        """Data, fit and residuals (two stacked axes; needs matplotlib). Returns the figure."""
        import matplotlib.pyplot as plt
        if ax is None:
            fig, (ax, axr) = plt.subplots(2, 1, sharex=True, height_ratios=(3, 1))
        else:
            fig = ax.figure
            axr = ax.twinx()
        xn, yn = self.meta.get("x_name", "depth"), self.meta.get("y_name", "force")
        xu, yu = self.units.get(xn, ""), self.units.get(yn, "")
        ax.plot(self.x, self.y, ".", ms=2, label="data")
        ax.plot(self.x, self.model, "-", label="fit")
        ax.set_ylabel(f"{yn} [{yu}]")
        ax.legend()
        axr.plot(self.x, self.residuals, ".", ms=2)
        axr.set_ylabel(f"residual [{yu}]")
        axr.set_xlabel(f"{xn} [{xu}]")
        return fig

    def __repr__(self) -> str:
        vals = ", ".join(f"{k}={self.params[k]:.6g}±{self.stderr[k]:.2g}" for k in self.free)
        return f"FitResult({vals}; n={self.x.size})"
