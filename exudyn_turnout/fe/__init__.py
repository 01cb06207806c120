"""FE reference model of the turnout (numpy/scipy only; no exudyn).

The paper validates its co-running models against an Ansys model of the turnout that we
do not have; this package builds our own from the same Table 1 properties:

- :mod:`.timoshenko`  element matrices (Timoshenko beam and bar of order p, foundations);
- :mod:`.analytic`    closed forms: infinite Timoshenko beam on a two-layer support,
  simply supported Timoshenko beam (pinned-pinned frequency);
- :mod:`.layout`      the turnout geometry of the file's ``[layout]`` section;
- :mod:`.mesh`        rails, sleepers, pads; FE options (element size, absorbing ends);
- :mod:`.model`       sparse K, G, D, M of the vertical or lateral plane;
- :mod:`.solver`      exact condensation and sparse LU at each frequency;
- :mod:`.frf`         point receptance (a :class:`~exudyn_turnout.receptance.Receptance`);
- :mod:`.stiffness`   static stiffness at every sleeper (paper Fig. 1(b,c));
- :mod:`.fits`        Eq 10 / Eq 14 analogues fitted to it;
- :mod:`.continuous`  one rail on a smeared support, the check against the closed form;
- :mod:`.torsion`     rail torsion (60E1 section data, torsion-warping elements, pad roll);
- :mod:`.rail_head`   a contact on the rail head: load vector and displacement (passage).
"""

from exudyn_turnout.fe.fits import (
    PolynomialFit,
    TurnoutFits,
    fit_turnout_profiles,
    with_fitted_profiles,
)
from exudyn_turnout.fe.frf import fe_receptance
from exudyn_turnout.fe.layout import Layout, load_layout, plain_track_layout
from exudyn_turnout.fe.mesh import FEOptions
from exudyn_turnout.fe.rail_head import RailHeadPoint, rail_head_point
from exudyn_turnout.fe.stiffness import StiffnessProfile, static_stiffness_profile
from exudyn_turnout.fe.torsion import UIC60_SECTION, RailTorsionSection

__all__ = [
    "FEOptions",
    "Layout",
    "load_layout",
    "plain_track_layout",
    "fe_receptance",
    "StiffnessProfile",
    "static_stiffness_profile",
    "PolynomialFit",
    "TurnoutFits",
    "fit_turnout_profiles",
    "with_fitted_profiles",
    "RailTorsionSection",
    "UIC60_SECTION",
    "RailHeadPoint",
    "rail_head_point",
]
