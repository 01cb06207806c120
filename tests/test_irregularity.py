"""Track irregularities (exudyn_turnout.inputs.irregularity): PSD, seeds, defects, specs, CSV.

Reference values: the spectra's closed forms (Zhai 2020 Sect. 2.4; Garg & Dukkipati 1984)
evaluated here, the statistics of a Gaussian sample (stated at each tolerance) and the
geometry of a V-shaped dipped joint (depth = alpha * length / 2 with 2 alpha its angle).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.signal import welch

from exudyn_turnout.inputs.irregularity import (
    CHANNELS,
    Irregularity,
    dipped_joint,
    irregularity_from_csv,
    irregularity_from_psd,
    irregularity_from_spec,
    local_defect,
    psd_profile_erri,
    sum_irregularities,
    track_spectrum,
)

STEP = 0.25  # m
LENGTH = 20_000.0  # m: ~140 Welch segments of 280 m


@pytest.fixture(scope="module")
def erri_low():
    return irregularity_from_psd(
        "ERRI-low", 7, band=(1.0, 70.0), x_start=0.0, x_end=LENGTH - STEP, step=STEP
    )


def _components(ir: Irregularity) -> dict[str, np.ndarray]:
    """Vertical, alignment, cross-level and gauge back from the rail channels."""
    return {
        "vertical": 0.5 * (ir.vertical_left + ir.vertical_right),
        "lateral": 0.5 * (ir.lateral_left + ir.lateral_right),
        "cross-level": ir.vertical_left - ir.vertical_right,
        "gauge": ir.lateral_left - ir.lateral_right,
    }


@pytest.mark.parametrize("component", ["vertical", "lateral", "cross-level", "gauge"])
def test_psd_of_generated_profile_matches_the_spectrum(erri_low, component):
    # Welch estimate (Hann, 50 % overlap) of the generated profile against the one-sided
    # spectrum, averaged over octaves well inside the 1-70 m band (2-32 m: Hann leakage and
    # the band's sharp edges stay out). Statistics: K ~ 140 segments, M bins per octave;
    # counting only every second segment and bin as independent (overlap, Hann main lobe),
    # the relative standard error of an octave mean is at most 1/sqrt(K M / 4); allowed: 5 of
    # them (a false alarm has probability < 1e-6 per octave for a Gaussian mean).
    spectrum = track_spectrum("ERRI-low")
    nperseg = int(280.0 / STEP)
    f, P = welch(_components(erri_low)[component], fs=1.0 / STEP, nperseg=nperseg)
    Omega, S = 2.0 * math.pi * f, P / (2.0 * math.pi)  # cycles/m -> rad/m, one-sided
    K = 2 * int(LENGTH / (nperseg * STEP)) - 1
    for lam_long in (32.0, 16.0, 8.0, 4.0):
        sel = (Omega >= 2 * math.pi / lam_long) & (Omega < 2 * math.pi / (lam_long / 2))
        ratio = np.mean(S[sel] / spectrum.psd(component, Omega[sel]))
        tol = 5.0 / math.sqrt(K * sel.sum() / 4.0)
        assert abs(ratio - 1.0) < tol, (component, lam_long, ratio, tol)


def test_variance_is_the_integral_of_the_spectrum_over_the_band(erri_low):
    # Over one period the sample variance is sum_k (a_k^2 + b_k^2)/2 with a_k, b_k ~
    # N(0, s_k), s_k = S(Omega_k) dOmega: mean sum s_k, standard deviation sqrt(sum s_k^2)
    # (closed form for the spectral representation with Gaussian amplitudes).
    spectrum = track_spectrum("ERRI-low")
    n = erri_low.x.size
    dOmega = 2 * math.pi / (n * STEP)
    Omega = dOmega * np.arange(1, n // 2)
    Omega = Omega[(Omega >= 2 * math.pi / 70.0) & (Omega <= 2 * math.pi / 1.0)]
    s = spectrum.psd("vertical", Omega) * dOmega
    var = np.var(_components(erri_low)["vertical"])
    assert abs(var - s.sum()) < 5.0 * math.sqrt(np.sum(s**2))
    # and the level: ERRI low, 1-70 m, a vertical standard deviation of a few millimetres
    assert 1e-3 < math.sqrt(s.sum()) < 5e-3


def test_same_seed_same_profile_other_seed_other_profile():
    a = irregularity_from_spec("psd:ERRI-high,seed=3,band=1-70,from=0,to=200")
    b = irregularity_from_spec("psd:ERRI-high,seed=3,band=1-70,from=0,to=200")
    c = irregularity_from_spec("psd:ERRI-high,seed=4,band=1-70,from=0,to=200")
    for name in CHANNELS:
        np.testing.assert_array_equal(getattr(a, name), getattr(b, name))
        assert not np.allclose(getattr(a, name), getattr(c, name))
    # leaving a component out does not change the others (one random stream each)
    v = irregularity_from_spec("psd:ERRI-high,seed=3,band=1-70,from=0,to=200,components=vertical")
    np.testing.assert_allclose(
        v.vertical_left, 0.5 * (a.vertical_left + a.vertical_right), rtol=0, atol=1e-15
    )
    np.testing.assert_array_equal(v.lateral_left, 0.0)


def test_fra_class_6_is_smoother_than_class_1():
    # Garg & Dukkipati 1984: class 6 (best track) has the lowest A_v, A_a
    for component in ("vertical", "lateral", "cross-level"):
        Omega = np.array([0.1, 1.0, 3.0])
        assert np.all(
            track_spectrum("FRA-6").psd(component, Omega)
            < track_spectrum("FRA-1").psd(component, Omega)
        )
    # the ERRI form at Omega = Omega_c: A / (2 (Omega_c^2 + Omega_r^2)), by hand
    A, Oc, Or = 4.032e-7, 0.8246, 0.0206
    assert psd_profile_erri(np.array([Oc]), A, Oc, Or)[0] == pytest.approx(
        A / (2 * (Oc**2 + Or**2)), rel=1e-12
    )


def test_dipped_joint_depth_and_shape():
    # a V of total angle 2 alpha over length l: depth alpha l / 2 at the joint, linear sides
    two_alpha, length = 0.009, 1.0
    joint = dipped_joint(47.0, two_alpha, length, rail="right")
    depth = 0.5 * two_alpha * 0.5 * length
    assert joint.at(47.0) == pytest.approx((0.0, -depth, 0.0, 0.0), abs=1e-15)
    assert joint.at(47.25)[1] == pytest.approx(-depth / 2, rel=1e-12)
    slope = (joint.at(47.1)[1] - joint.at(47.0)[1]) / 0.1
    assert slope == pytest.approx(two_alpha / 2, rel=1e-12)
    assert joint.at(46.4) == (0.0, 0.0, 0.0, 0.0) and joint.at(47.6) == (0.0, 0.0, 0.0, 0.0)


def test_dip_and_bump_and_exact_sum():
    dip = local_defect(10.0, 0.002, 1.0)
    bump = irregularity_from_spec("bump:x=10.3,depth=0.001,length=2,rail=left")
    assert dip.at(10.0)[0] == pytest.approx(-0.002, rel=1e-12)
    assert bump.at(10.3)[0] == pytest.approx(0.001, rel=1e-12)
    assert bump.at(10.3)[1] == 0.0
    total = sum_irregularities([dip, bump])
    xs = np.random.default_rng(0).uniform(8.0, 12.5, 500)
    np.testing.assert_allclose(
        total.at_array(xs), dip.at_array(xs) + bump.at_array(xs), rtol=0, atol=1e-15
    )
    both = irregularity_from_spec(
        "dip:x=10,depth=0.002,length=1; bump:x=10.3,depth=0.001,length=2,rail=left"
    )
    np.testing.assert_allclose(both.at_array(xs), total.at_array(xs), rtol=0, atol=1e-15)


def test_csv_measured_irregularity(tmp_path):
    path = tmp_path / "measured.csv"
    path.write_text(
        "# measured, m\nx_m,vertical_left_m,lateral_right\n0,0,0\n1,-0.001,0.0005\n2,0,0\n",
        encoding="utf-8",
    )
    ir = irregularity_from_spec(str(path))
    assert ir.at(0.5) == pytest.approx((-0.0005, 0.0, 0.0, 0.00025))
    assert ir.at(2.5) == (0.0, 0.0, 0.0, 0.0)
    assert irregularity_from_spec("measured.csv", base_dir=tmp_path).at(1.0)[0] == -0.001
    bad = tmp_path / "bad.csv"
    bad.write_text("x_m,vertical_left_m\n0,0\n1,oops\n", encoding="utf-8")
    with pytest.raises(ValueError, match="line 3, column vertical_left_m"):
        irregularity_from_csv(bad)
    bad.write_text("x_m,up\n0,0\n", encoding="utf-8")
    with pytest.raises(ValueError, match="unknown column 'up'"):
        irregularity_from_csv(bad)
    bad.write_text("x_m,vertical_left_m\n0,0\n0,0\n", encoding="utf-8")
    with pytest.raises(ValueError, match="strictly increasing"):
        irregularity_from_csv(bad)


@pytest.mark.parametrize(
    ("spec", "field"),
    [
        ("psd:ERRI-low", "seed is missing"),
        ("psd:ERRI-medium,seed=1", "unknown spectrum"),
        ("psd:ERRI-low,seed=1,band=70-1", "band"),
        ("psd:ERRI-low,seed=1,band=1", "band="),
        ("psd:ERRI-low,seed=1,step=0.5", "step"),
        ("psd:ERRI-low,seed=-1", "seed="),
        ("psd:ERRI-low,seed=1,colour=red", "unknown field 'colour'"),
        ("dip:x=47,length=1", "depth is missing"),
        ("dip:x=47,depth=abc,length=1", "depth='abc' is not a number"),
        ("dip:x=47,depth=0.002,length=1,rail=middle", "rail"),
        ("joint:x=47,angle=0,length=1", "angle"),
        ("nothing-like-a-spec", "not a CSV file nor a spec"),
        ("missing.csv", "no such file"),
    ],
)
def test_bad_specs_give_one_line_naming_the_field(spec, field):
    with pytest.raises(ValueError, match=field) as info:
        irregularity_from_spec(spec)
    assert "\n" not in str(info.value)
