"""Standard track irregularity spectra: ERRI B176 and FRA power spectral densities.

One-sided PSDs (m^2/(rad/m)) of vertical profile, alignment, cross-level and gauge
(:data:`PSD_COMPONENTS`): the ORE/ERRI B176 form with its low and high levels
(:func:`psd_profile_erri`, :func:`psd_cross_level_erri`, :func:`psd_gauge_erri`) and the
FRA track classes 1 to 6 (:func:`psd_profile_fra`, :func:`psd_cross_level_fra`), gathered
by name in :class:`TrackSpectrum` (:func:`track_spectrum`). Random irregularities drawn from
them are :func:`exudyn_turnout.inputs.irregularity.irregularity_from_psd`. Pure numpy.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = [
    "TrackSpectrum",
    "SPECTRUM_NAMES",
    "PSD_COMPONENTS",
    "psd_profile_erri",
    "psd_cross_level_erri",
    "psd_gauge_erri",
    "psd_profile_fra",
    "psd_cross_level_fra",
    "track_spectrum",
]

#: The four random components of a PSD irregularity (see
#: :func:`exudyn_turnout.inputs.irregularity.rail_channels`).
PSD_COMPONENTS = ("vertical", "lateral", "cross-level", "gauge")


def psd_profile_erri(Omega: np.ndarray, A: float, Omega_c: float, Omega_r: float) -> np.ndarray:
    """Vertical profile or alignment PSD of the ERRI B176 / German track spectra.

    S(Omega) = A Omega_c^2 / ((Omega^2 + Omega_r^2)(Omega^2 + Omega_c^2)), one-sided, in
    m^2/(rad/m) (ORE B176 form; as tabulated in W. Zhai, *Vehicle-Track Coupled Dynamics*,
    Springer 2020, Sect. 2.4, and G. Lei, *Railway Track Dynamics*, Springer 2017, Ch. 5).

    Parameters
    ----------
    Omega : ndarray
        rad/m, spatial angular frequency 2 pi / wavelength.
    A : float
        m rad, roughness coefficient (A_v vertical, A_a alignment).
    Omega_c, Omega_r : float
        rad/m, cut-off frequencies.

    Returns
    -------
    ndarray
        m^2/(rad/m).
    """
    W2 = np.asarray(Omega, dtype=float) ** 2
    return A * Omega_c**2 / ((W2 + Omega_r**2) * (W2 + Omega_c**2))


def psd_cross_level_erri(
    Omega: np.ndarray, A_v: float, b: float, Omega_c: float, Omega_r: float, Omega_s: float
) -> np.ndarray:
    """Cross-level PSD of the ERRI B176 / German track spectra, as a height difference.

    The angle spectrum S_theta = (A_v / b^2) Omega_c^2 Omega^2 / ((Omega^2 + Omega_r^2)
    (Omega^2 + Omega_c^2)(Omega^2 + Omega_s^2)) in rad^2/(rad/m) (Zhai 2020, Sect. 2.4) is
    converted to the height difference of the two rails, dh = 2 b theta:
    S_dh = 4 b^2 S_theta, in m^2/(rad/m).

    Parameters
    ----------
    Omega : ndarray
        rad/m.
    A_v : float
        m rad, the vertical roughness coefficient.
    b : float
        m, half the distance between the rolling circles (0.75 m).
    Omega_c, Omega_r, Omega_s : float
        rad/m, cut-off frequencies.

    Returns
    -------
    ndarray
        m^2/(rad/m), of the left minus the right rail height.
    """
    W2 = np.asarray(Omega, dtype=float) ** 2
    S_theta = (
        (A_v / b**2) * Omega_c**2 * W2 / ((W2 + Omega_r**2) * (W2 + Omega_c**2) * (W2 + Omega_s**2))
    )
    return 4.0 * b**2 * S_theta


def psd_gauge_erri(
    Omega: np.ndarray, A_g: float, Omega_c: float, Omega_r: float, Omega_s: float
) -> np.ndarray:
    """Gauge PSD of the German track spectra (Zhai 2020, Sect. 2.4).

    S_g = A_g Omega_c^2 Omega^2 / ((Omega^2 + Omega_r^2)(Omega^2 + Omega_c^2)
    (Omega^2 + Omega_s^2)), one-sided, m^2/(rad/m).

    Parameters
    ----------
    Omega : ndarray
        rad/m.
    A_g : float
        m rad, the gauge roughness coefficient.
    Omega_c, Omega_r, Omega_s : float
        rad/m, cut-off frequencies.

    Returns
    -------
    ndarray
        m^2/(rad/m).
    """
    W2 = np.asarray(Omega, dtype=float) ** 2
    return A_g * Omega_c**2 * W2 / ((W2 + Omega_r**2) * (W2 + Omega_c**2) * (W2 + Omega_s**2))


def psd_profile_fra(Omega: np.ndarray, k: float, A: float, Omega_c: float) -> np.ndarray:
    """Vertical profile or alignment PSD of the FRA track classes, in SI units.

    S(Omega) = k A Omega_c^2 / (Omega^2 (Omega^2 + Omega_c^2)) in cm^2/(rad/m) with A in
    cm^2 rad/m (V. K. Garg, R. V. Dukkipati, *Dynamics of Railway Vehicle Systems*,
    Academic Press 1984, Sect. 11; Zhai 2020, Sect. 2.4), times 1e-4 for m^2/(rad/m).

    Parameters
    ----------
    Omega : ndarray
        rad/m (> 0).
    k : float
        -, the safety factor (0.25).
    A : float
        cm^2 rad/m, roughness coefficient of the class (A_v or A_a).
    Omega_c : float
        rad/m, cut-off frequency.

    Returns
    -------
    ndarray
        m^2/(rad/m).
    """
    W2 = np.asarray(Omega, dtype=float) ** 2
    return 1e-4 * k * A * Omega_c**2 / (W2 * (W2 + Omega_c**2))


def psd_cross_level_fra(
    Omega: np.ndarray, k: float, A_v: float, Omega_c: float, Omega_s: float
) -> np.ndarray:
    """Cross-level (and gauge) PSD of the FRA track classes, in SI units.

    S(Omega) = 4 k A_v Omega_c^2 / ((Omega^2 + Omega_c^2)(Omega^2 + Omega_s^2)) in
    cm^2/(rad/m) (Garg & Dukkipati 1984, Sect. 11; Zhai 2020, Sect. 2.4), times 1e-4 for
    m^2/(rad/m); the cross-level as a height difference of the rails.

    Parameters
    ----------
    Omega : ndarray
        rad/m.
    k : float
        -, the safety factor (0.25).
    A_v : float
        cm^2 rad/m.
    Omega_c, Omega_s : float
        rad/m.

    Returns
    -------
    ndarray
        m^2/(rad/m).
    """
    W2 = np.asarray(Omega, dtype=float) ** 2
    return 1e-4 * 4.0 * k * A_v * Omega_c**2 / ((W2 + Omega_c**2) * (W2 + Omega_s**2))


@dataclass(frozen=True)
class TrackSpectrum:
    """A standard track irregularity spectrum and its parameters.

    Parameters
    ----------
    name : str
        ``ERRI-low``, ``ERRI-high`` or ``FRA-1`` ... ``FRA-6``.
    family : str
        ``"erri"`` (:func:`psd_profile_erri` etc.) or ``"fra"`` (:func:`psd_profile_fra`).
    A_v, A_a, A_g : float
        Roughness coefficients: m rad (ERRI), cm^2 rad/m (FRA; A_g unused there).
    Omega_c, Omega_r, Omega_s : float
        rad/m, cut-off frequencies (Omega_r unused for FRA).
    reference : str
        Where the parameters are tabulated.
    """

    name: str
    family: str
    A_v: float  #: m rad (ERRI) or cm^2 rad/m (FRA)
    A_a: float  #: m rad (ERRI) or cm^2 rad/m (FRA)
    A_g: float  #: m rad (ERRI); FRA: not used (gauge as cross-level)
    Omega_c: float  #: rad/m
    Omega_r: float  #: rad/m (ERRI only)
    Omega_s: float  #: rad/m
    reference: str = ""
    b: float = 0.75  #: m, half the distance between the rolling circles (ERRI cross-level)
    k: float = 0.25  #: -, FRA safety factor

    def psd(self, component: str, Omega: np.ndarray) -> np.ndarray:
        """One-sided PSD of a component (m^2/(rad/m)).

        Parameters
        ----------
        component : {"vertical", "lateral", "cross-level", "gauge"}
            Vertical profile, alignment, cross-level (left minus right height) and gauge
            (positive wider).
        Omega : ndarray
            rad/m (> 0).

        Returns
        -------
        ndarray
            m^2/(rad/m).
        """
        if component not in PSD_COMPONENTS:
            raise ValueError(f"component must be one of {', '.join(PSD_COMPONENTS)}")
        if self.family == "fra":
            if component == "vertical":
                return psd_profile_fra(Omega, self.k, self.A_v, self.Omega_c)
            if component == "lateral":
                return psd_profile_fra(Omega, self.k, self.A_a, self.Omega_c)
            return psd_cross_level_fra(Omega, self.k, self.A_v, self.Omega_c, self.Omega_s)
        if component == "vertical":
            return psd_profile_erri(Omega, self.A_v, self.Omega_c, self.Omega_r)
        if component == "lateral":
            return psd_profile_erri(Omega, self.A_a, self.Omega_c, self.Omega_r)
        if component == "cross-level":
            return psd_cross_level_erri(
                Omega, self.A_v, self.b, self.Omega_c, self.Omega_r, self.Omega_s
            )
        return psd_gauge_erri(Omega, self.A_g, self.Omega_c, self.Omega_r, self.Omega_s)


_ERRI_REF = (
    "ORE B176 form, low/high level parameters as tabulated in Zhai 2020 Sect. 2.4 "
    "(German track spectra, low/high interference); TO CONFIRM against ORE B176 (1989)"
)
_FRA_REF = "Garg & Dukkipati 1984 Sect. 11, FRA track classes, k = 0.25"

#: name -> (family, A_v, A_a, A_g, Omega_c, Omega_r, Omega_s, reference): see
#: :func:`track_spectrum`. ERRI: m rad, rad/m; FRA: cm^2 rad/m, rad/m.
_SPECTRA: tuple[tuple[str, str, float, float, float, float, float, float, str], ...] = (
    ("ERRI-low", "erri", 4.032e-7, 2.119e-7, 5.32e-8, 0.8246, 0.0206, 0.4380, _ERRI_REF),
    ("ERRI-high", "erri", 1.080e-6, 6.125e-7, 1.032e-7, 0.8246, 0.0206, 0.4380, _ERRI_REF),
    ("FRA-1", "fra", 1.2107, 3.3634, 0.0, 0.8245, 0.0, 0.6046, _FRA_REF),
    ("FRA-2", "fra", 1.0181, 1.2107, 0.0, 0.8245, 0.0, 0.9308, _FRA_REF),
    ("FRA-3", "fra", 0.6816, 0.4128, 0.0, 0.8245, 0.0, 0.8520, _FRA_REF),
    ("FRA-4", "fra", 0.5376, 0.3027, 0.0, 0.8245, 0.0, 1.1312, _FRA_REF),
    ("FRA-5", "fra", 0.2095, 0.0762, 0.0, 0.8245, 0.0, 0.8209, _FRA_REF),
    ("FRA-6", "fra", 0.0339, 0.0339, 0.0, 0.8245, 0.0, 0.4380, _FRA_REF),
)

#: Names accepted by :func:`track_spectrum`.
SPECTRUM_NAMES = tuple(row[0] for row in _SPECTRA)


def track_spectrum(name: str) -> TrackSpectrum:
    """A standard spectrum by name: ``ERRI-low``, ``ERRI-high``, ``FRA-1`` ... ``FRA-6``.

    ERRI: the ORE/ERRI B176 form (:func:`psd_profile_erri`, :func:`psd_cross_level_erri`,
    :func:`psd_gauge_erri`) with the low and high level coefficients A_v = 4.032e-7 /
    1.080e-6 m rad, A_a = 2.119e-7 / 6.125e-7 m rad, A_g = 5.32e-8 / 1.032e-7 m rad,
    Omega_c = 0.8246, Omega_r = 0.0206, Omega_s = 0.4380 rad/m (Zhai 2020, Sect. 2.4).
    FRA classes 1 (worst) to 6 (best): :func:`psd_profile_fra` and
    :func:`psd_cross_level_fra`, k = 0.25 (Garg & Dukkipati 1984).

    Parameters
    ----------
    name : str
        Case-insensitive.

    Returns
    -------
    TrackSpectrum

    Raises
    ------
    ValueError
        Unknown name (the message lists the names).
    """
    for row in _SPECTRA:
        if row[0].lower() == name.strip().lower():
            family, A_v, A_a, A_g, Omega_c, Omega_r, Omega_s, ref = row[1:]
            return TrackSpectrum(row[0], family, A_v, A_a, A_g, Omega_c, Omega_r, Omega_s, ref)
    raise ValueError(f"unknown spectrum {name!r} (known: {', '.join(SPECTRUM_NAMES)})")
