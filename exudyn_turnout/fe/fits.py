"""Polynomial fits of the FE static stiffness along the switch: analogues of Eqs 10 and 14.

The paper fits the vertical static stiffness of the switch rail with a quadratic in x
(Eq 10, K_sw) and the lateral one with a line (Eq 14, K_sh). We fit the FE profile of
:mod:`exudyn_turnout.fe.stiffness` the same way (least squares, ascending powers), on
the rail and x range the turnout file's ``[layout.fits]`` names (for the UIC60 turnout:
the switch rail from the toe to 22 m, the range of Eq 10, held constant beyond as
Section 3.1.1 says; the stock rail from the toe to the end of the long bearers, since the
paper finds the lateral stiffness equal for all rails). :func:`with_fitted_profiles` returns
the turnout with its K_sw, K_sh replaced, so the co-running parameters (Delta_z, Delta_y,
Eqs 11, 15) can come from our FE instead of the paper's.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from exudyn_turnout.fe.layout import Layout, load_layout
from exudyn_turnout.fe.stiffness import StiffnessProfile
from exudyn_turnout.inputs.turnout import Polynomial, Turnout

__all__ = [
    "PolynomialFit",
    "TurnoutFits",
    "fit_polynomial",
    "fit_profile",
    "fit_turnout_profiles",
    "with_fitted_profiles",
]


@dataclass(frozen=True)
class PolynomialFit:
    """A least-squares polynomial K(x) of one rail's static stiffness."""

    rail: str  #: layout rail id
    direction: str  #: "vertical" or "lateral"
    coefficients: tuple[float, ...]  #: N/m, N/m^2, ... ascending powers of x
    x_min: float  #: m, fitted range
    x_max: float  #: m
    r_squared: float  #: coefficient of determination (-)
    n_points: int  #: sleepers used

    @property
    def polynomial(self) -> Polynomial:
        """As the turnout's :class:`~exudyn_turnout.inputs.turnout.Polynomial`.

        Held at its end values outside the fitted range.
        """
        return Polynomial(self.coefficients, self.x_min, self.x_max)

    def __call__(self, x: float) -> float:
        return self.polynomial(x)


@dataclass(frozen=True)
class TurnoutFits:
    """The two fits that replace the paper's Eqs 10 and 14 in a turnout."""

    K_sw: PolynomialFit  #: Eq 10 analogue (vertical, quadratic)
    K_sh: PolynomialFit  #: Eq 14 analogue (lateral, linear)


def fit_polynomial(x: ArrayLike, y: ArrayLike, degree: int) -> tuple[tuple[float, ...], float]:
    """Least-squares coefficients (ascending powers) and R^2 of a polynomial y(x).

    Parameters
    ----------
    x : array_like
        Abscissae (m).
    y : array_like
        Values to fit (any unit, e.g. N/m).
    degree : int
        Polynomial degree; needs more than ``degree`` points.

    Returns
    -------
    coefficients : tuple of float
        Coefficients of x^0, x^1, ... (unit of y per m^k).
    r_squared : float
        Coefficient of determination (-); 1 for constant y.

    Raises
    ------
    ValueError
        Too few points for the degree.
    """
    x, y = np.asarray(x, float), np.asarray(y, float)
    if len(x) <= degree:
        raise ValueError(f"need more than {degree} points for a degree-{degree} fit, got {len(x)}")
    coefficients = np.polynomial.polynomial.polyfit(x, y, degree)
    residual = y - np.polynomial.polynomial.polyval(x, coefficients)
    ss_tot = float(np.sum((y - y.mean()) ** 2))
    r_squared = 1.0 - float(np.sum(residual**2)) / ss_tot if ss_tot > 0 else 1.0
    return tuple(float(value) for value in coefficients), r_squared


def fit_profile(
    profile: StiffnessProfile, rail: str, direction: str, degree: int, x_min: float, x_max: float
) -> PolynomialFit:
    """Fit one rail's vertical or lateral static stiffness over [x_min, x_max].

    Parameters
    ----------
    profile : StiffnessProfile
        FE static stiffness at every sleeper.
    rail : str
        Layout rail id.
    direction : {"vertical", "lateral"}
        Which stiffness to fit.
    degree : int
        Polynomial degree (2 for Eq 10, 1 for Eq 14).
    x_min, x_max : float
        Fitted range of x (m); the sleepers inside it are used.

    Returns
    -------
    PolynomialFit
        The fit with its range, R^2 and number of sleepers.
    """
    x_sleepers, K_z, K_y = profile.of(rail)
    selected = (x_sleepers >= x_min) & (x_sleepers <= x_max)
    K = (K_z if direction == "vertical" else K_y)[selected]
    coefficients, r_squared = fit_polynomial(x_sleepers[selected], K, degree)
    return PolynomialFit(
        rail,
        direction,
        coefficients,
        float(x_min),
        float(x_max),
        r_squared,
        int(selected.sum()),
    )


def fit_turnout_profiles(
    profile: StiffnessProfile, turnout: Turnout, layout: Layout | None = None
) -> TurnoutFits:
    """Quadratic K_sw (Eq 10) and linear K_sh (Eq 14) from the FE profile.

    Parameters
    ----------
    profile : StiffnessProfile
        FE static stiffness at every sleeper, from
        :func:`~exudyn_turnout.fe.stiffness.static_stiffness_profile`.
    turnout : Turnout
        The turnout the profile was computed for.
    layout : Layout, optional
        Default :func:`~exudyn_turnout.fe.layout.load_layout` of the turnout; its
        ``fits`` name the rail and x range of each fit.

    Returns
    -------
    TurnoutFits
        The Eq 10 and Eq 14 analogues.
    """
    layout = layout or load_layout(turnout)
    vertical, lateral = layout.fits["K_sw"], layout.fits["K_sh"]
    return TurnoutFits(
        fit_profile(profile, vertical.rail, "vertical", 2, vertical.x_min, vertical.x_max),
        fit_profile(profile, lateral.rail, "lateral", 1, lateral.x_min, lateral.x_max),
    )


def with_fitted_profiles(turnout: Turnout, fits: TurnoutFits) -> Turnout:
    """The turnout with K_sw and K_sh replaced by the fitted polynomials.

    Parameters
    ----------
    turnout : Turnout
        The turnout; not modified.
    fits : TurnoutFits
        From :func:`fit_turnout_profiles`.

    Returns
    -------
    Turnout
        A copy whose Delta_z, Delta_y (Eqs 11, 15) follow the FE instead of the paper. The
        file's ``plain_track_end`` (plain track ahead of the toe, blended to the toe value
        over the bays before it) is kept where it lies ahead of the fit's range, as for
        the paper's polynomials; without it the fitted toe value would be held on plain
        track.
    """
    return dataclasses.replace(
        turnout,
        K_sw=_with_plain_end(fits.K_sw.polynomial, turnout.K_sw),
        K_sh=_with_plain_end(fits.K_sh.polynomial, turnout.K_sh),
    )


def _with_plain_end(fitted: Polynomial, paper: Polynomial) -> Polynomial:
    """The fitted polynomial with the paper polynomial's plain-track end, if ahead of it.

    Parameters
    ----------
    fitted : Polynomial
        From the FE fit.
    paper : Polynomial
        The turnout file's polynomial.

    Returns
    -------
    Polynomial
    """
    end = paper.plain_track_end
    if end is None or end >= fitted.x_min:
        return fitted
    return dataclasses.replace(fitted, plain_track_end=end)
