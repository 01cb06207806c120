"""``exudyn-turnout frf``: CSV columns, plot, and one-line errors with exit code 2.

Reference: the CSV format of exudyn_turnout.receptance (frequency_hz,real,imag,magnitude
in m/N) and the active rails of the paper's Table 3 (zone 1: r1 r2 r4).
"""

import csv
import subprocess
import sys

import numpy as np
import pytest

from exudyn_turnout.cli.main import main
from exudyn_turnout.corunning.modal import co_running_receptance

BASE = ["frf", "--layers", "3", "--rail", "r2", "--direction", "vertical"]


def _run(capsys, *argv):
    code = main(list(argv))
    out = capsys.readouterr()
    return code, out.out, out.err


def test_writes_csv_with_the_receptance(capsys, tmp_path, turnout):
    """Columns and values: the CSV holds co_running_receptance of zone 2 (8 significant digits)."""
    out = tmp_path / "h.csv"
    code, stdout, _ = _run(
        capsys, *BASE, "--zone", "2", "--n", "50", "--fmax", "5000", "--out", str(out)
    )
    assert code == 0 and "wrote" in stdout
    with open(out, newline="") as fh:
        rows = list(csv.reader(fh))
    assert rows[0] == ["frequency_hz", "real", "imag", "magnitude"]
    data = np.array(rows[1:], dtype=float)
    assert data.shape == (50, 4)
    assert data[0, 0] == pytest.approx(1.0) and data[-1, 0] == pytest.approx(5000.0)
    expected = co_running_receptance(turnout, 3, "r2", "vertical", zone=2, frequencies=data[:, 0])
    np.testing.assert_allclose(data[:, 1] + 1j * data[:, 2], expected.H, rtol=1e-7)
    np.testing.assert_allclose(data[:, 3], np.abs(expected.H), rtol=1e-7)


def test_plot_is_written(capsys, tmp_path):
    png = tmp_path / "h.png"
    code, _, _ = _run(
        capsys,
        *BASE,
        "--x",
        "47",
        "--source",
        "published",
        "--out",
        str(tmp_path / "h.csv"),
        "--plot",
        str(png),
    )
    assert code == 0
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


@pytest.mark.parametrize(
    "argv,fragment",
    [
        (
            ["frf", "--layers", "2", "--rail", "r3", "--direction", "lateral", "--zone", "1"],
            "rail r3 is not active in zone 1",
        ),
        (
            ["frf", "--layers", "2", "--rail", "r3", "--direction", "lateral", "--x", "55"],
            "rail r3 is not active at x = 55 m",
        ),
        (BASE + ["--zone", "2", "--fmin", "100", "--fmax", "10"], "need 0 < fmin < fmax"),
        (BASE + ["--zone", "2", "--fmin", "0"], "need 0 < fmin < fmax"),
        (BASE + ["--zone", "2", "--n", "1"], "at least 2 frequencies"),
        (BASE + ["--zone", "2", "--fmax", "inf"], "finite"),
        (BASE + ["--x", "80"], "outside the turnout"),
        (BASE + ["--zone", "9"], "zone 9 does not exist"),
    ],
)
def test_bad_input_is_one_line_and_exit_2(capsys, tmp_path, argv, fragment):
    out = tmp_path / "h.csv"
    code, stdout, stderr = _run(capsys, *argv, "--out", str(out))
    assert code == 2
    assert fragment in stderr
    assert len(stderr.strip().splitlines()) == 1 and stdout == ""
    assert not out.exists()


def test_frf_imports_neither_exudyn_nor_matplotlib(tmp_path):
    """The receptance is numpy/scipy only; matplotlib only with --plot (fast start)."""
    code = (
        "import sys; from exudyn_turnout.cli.main import main; "
        "rc = main(['frf', '--layers', '3', '--rail', 'r2', '--direction', 'lateral', "
        f"'--zone', '1', '--out', r'{tmp_path / 'h.csv'}']); "
        "print(rc, 'exudyn' in sys.modules, 'matplotlib' in sys.modules)"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True
    ).stdout
    assert out.strip().splitlines()[-1] == "0 False False"


@pytest.mark.slow
def test_with_fe_overlays_the_fe_receptance(capsys, tmp_path, turnout):
    """--with-fe: the FE receptance at the same x, rail and direction, beside the CSV and in
    the plot; its values are fe_receptance's (the FE reference, exudyn_turnout.fe.frf)."""
    from exudyn_turnout.fe.frf import fe_receptance

    out, plot = tmp_path / "h.csv", tmp_path / "h.png"
    code, stdout, err = _run(
        capsys, *BASE, "--x", "47.2", "--n", "4", "--with-fe", "--out", str(out),
        "--plot", str(plot),
    )  # fmt: skip
    assert code == 0, err
    fe_csv = tmp_path / "h_fe.csv"
    data = np.loadtxt(fe_csv, delimiter=",", skiprows=1)
    assert data.shape == (4, 4)
    expected = fe_receptance(turnout, "r2", "vertical", 47.2, data[:, 0])
    np.testing.assert_allclose(data[:, 1] + 1j * data[:, 2], expected.H, rtol=1e-6)
    assert (tmp_path / "h_fe.meta.json").exists()
    assert plot.read_bytes()[:4] == b"\x89PNG"
    assert "wrote " + str(fe_csv) in stdout and "3-layer/FE = " in stdout
