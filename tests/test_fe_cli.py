"""``exudyn-turnout fe frf`` and ``fe stiffness``: CSV columns, bad input -> one line, exit 2.

Reference: the receptance CSV columns are those of the co-running receptance
(exudyn_turnout.receptance.CSV_COLUMNS).
"""

import csv

import pytest

from exudyn_turnout.cli.main import main


def _run(capsys, *argv):
    code = main(list(argv))
    out = capsys.readouterr()
    return code, out.out, out.err


def test_frf_csv(capsys, tmp_path):
    out = tmp_path / "h.csv"
    code, text, _ = _run(
        capsys,
        "fe",
        "frf",
        "--rail",
        "r2",
        "--direction",
        "lateral",
        "--x",
        "46",
        "--n",
        "4",
        "--out",
        str(out),
    )
    rows = list(csv.reader(open(out)))
    assert code == 0 and "straight" in text
    assert rows[0] == ["frequency_hz", "real", "imag", "magnitude"] and len(rows) == 5


def test_stiffness_csv_and_plot(capsys, tmp_path):
    out, png = tmp_path / "k.csv", tmp_path / "k.png"
    code, text, _ = _run(capsys, "fe", "stiffness", "--out", str(out), "--plot", str(png))
    assert code == 0 and "K_sw" in text and "R^2" in text
    assert next(csv.reader(open(out))) == ["x_m", "rail", "K_z_N_per_m", "K_y_N_per_m"]
    assert png.stat().st_size > 10000


@pytest.mark.parametrize(
    "argv,fragment",
    [
        (
            ["--rail", "r2", "--direction", "vertical", "--x", "-2"],
            "rail r2 is not present at x = -2 m",
        ),
        (
            ["--rail", "r3", "--direction", "vertical", "--x", "20"],
            "rail r3 is not present at x = 20 m",
        ),
        (["--rail", "r1", "--direction", "vertical", "--x", "70"], "outside the FE model"),
        (
            ["--rail", "r7", "--direction", "vertical", "--x", "2"],
            "rail must be one of r1, r2, r3, r4",
        ),
        (["--rail", "r1", "--direction", "up", "--x", "2"], "invalid choice: 'up'"),
        (
            ["--rail", "r1", "--direction", "vertical", "--x", "2", "--fmin", "10", "--fmax", "5"],
            "need 0 < fmin < fmax",
        ),
    ],
)
def test_bad_input_is_one_line_exit_2(capsys, tmp_path, argv, fragment):
    code, _, err = _run(capsys, "fe", "frf", *argv, "--out", str(tmp_path / "h.csv"))
    assert code == 2 and fragment in err and err.count("\n") == 1
    assert not (tmp_path / "h.csv").exists()
