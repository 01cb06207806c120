"""Output files of a passage: one layout in CSV, NPZ and ``result.columns``; compressed NPZ,
float32 on request; no column empty from top to bottom (issue 25, "outputs sized for use")."""

from __future__ import annotations

import csv
import io
import json

import numpy as np
import pytest

from exudyn_turnout.passage.output_files import csv_text, keeps_float64, without_empty_columns
from exudyn_turnout.passage.results import PassageResult, write_passage
from exudyn_turnout.passage.settings import DEFAULT_SETTINGS

N = 400


def _result() -> PassageResult:
    """A synthetic result: a rail slot present in the first half only, an unloaded contact
    point's position NaN, a column of a body never met (all NaN)."""
    rng = np.random.default_rng(7)
    t = np.arange(N) * 1e-4 + 1.0
    half = np.where(np.arange(N) < N // 2, 1.0, np.nan)
    normal = np.where(rng.random(N) < 0.5, 0.0, 5e4 + rng.normal(size=N))
    columns = {
        "t_s": t,
        "x_m": 40.0 + 27.7777777 * (t - 1.0),
        "Fz_right_N": 5.45e4 + rng.normal(size=N) * 1e3,
        "Fy_right_N": rng.normal(size=N) * 1e3,
        "Fz_left_N": 5.45e4 + rng.normal(size=N) * 1e3,
        "Fy_left_N": rng.normal(size=N) * 1e3,
        "Fz_right_r3_N": half * 1e3,
        "z_rail_r3_m": half * -1.234567891e-4,
        "cp_right_r2_nose_0_N_N": normal,
        "cp_right_r2_nose_0_y_rail_m": np.where(normal > 0, 0.012345678, np.nan),
        "cp_right_r2_never_0_N_N": np.full(N, np.nan),
    }
    summary = {"static_wheel_load_N": 5.45e4, "static_wheel_load_left_N": 5.45e4}
    return PassageResult(DEFAULT_SETTINGS, columns, summary)


def _read_csv(path) -> tuple[list[str], np.ndarray]:
    with open(path, newline="", encoding="utf-8") as fh:
        rows = list(csv.reader(fh))
    data = np.array([[float(c) if c else np.nan for c in row] for row in rows[1:]])
    return rows[0], data


def test_all_empty_column_is_left_out_of_the_result():
    result = _result()
    assert "cp_right_r2_never_0_N_N" not in result.columns
    assert "z_rail_r3_m" in result.columns  # half empty: kept
    for name, values in result.columns.items():
        assert np.isfinite(np.asarray(values, float)).any(), name


def test_csv_round_trip_same_names_and_values(tmp_path):
    result = _result()
    paths = write_passage(result, tmp_path, "csv")
    names, data = _read_csv(paths["timeseries"])
    assert names == list(result.columns)
    for k, name in enumerate(names):
        ref = np.asarray(result.columns[name], float)
        # 9 significant digits written (CSV_DIGITS): relative 5e-9
        np.testing.assert_allclose(data[:, k], ref, rtol=6e-9, atol=0, equal_nan=True)
    text = (tmp_path / "timeseries.csv").read_text()
    assert "nan" not in text and "inf" not in text


def test_csv_text_empty_cells_for_every_non_finite_neighbour_pattern():
    a = np.array([[np.nan, 1.0, np.nan, np.nan, np.inf], [2.0, -np.inf, np.nan, 3.5, np.nan]])
    text = csv_text({f"c{i}": a[:, i] for i in range(a.shape[1])})
    assert text == "c0,c1,c2,c3,c4\n,1,,,\n2,,,3.5,\n"


def test_npz_round_trip_compressed_same_names(tmp_path):
    result = _result()
    plain = tmp_path / "plain.npz"
    np.savez(plain, **{n: np.asarray(v, float) for n, v in result.columns.items()})
    paths = write_passage(result, tmp_path, "npz")
    with np.load(paths["timeseries"]) as data:
        names = [n for n in data.files if n != "summary"]
        assert names == list(result.columns)
        for name in names:
            assert data[name].dtype == np.float64
            np.testing.assert_array_equal(data[name], result.columns[name])
        assert json.loads(str(data["summary"]))["static_wheel_load_N"] == 5.45e4
    assert (tmp_path / "timeseries.npz").stat().st_size < plain.stat().st_size


def test_npz_float32_on_request_keeps_time_and_position_float64(tmp_path):
    result = _result()
    write_passage(result, tmp_path / "a", "npz", dtype="float32")
    write_passage(result, tmp_path / "b", "npz")
    with np.load(tmp_path / "a" / "timeseries.npz") as data:
        assert data["t_s"].dtype == np.float64 and data["x_m"].dtype == np.float64
        assert data["Fz_right_N"].dtype == np.float32
        np.testing.assert_array_equal(data["t_s"], result.columns["t_s"])
        # float32: 24-bit mantissa, relative 6e-8
        np.testing.assert_allclose(data["Fz_right_N"], result.columns["Fz_right_N"], rtol=6e-8)
    small = (tmp_path / "a" / "timeseries.npz").stat().st_size
    assert small < (tmp_path / "b" / "timeseries.npz").stat().st_size


def test_result_save_passes_dtype(tmp_path):
    _result().save(tmp_path, format="npz", dtype="float32")
    with np.load(tmp_path / "timeseries.npz") as data:
        assert data["Fy_left_N"].dtype == np.float32


@pytest.mark.parametrize(
    "fmt,dtype,message",
    [
        ("xlsx", "float64", "format must be csv or npz"),
        ("npz", "float16", "dtype must be one of float64, float32"),
        ("csv", "float32", "dtype float32 is for the npz format"),
    ],
)
def test_bad_format_or_dtype(tmp_path, fmt, dtype, message):
    with pytest.raises(ValueError, match=message):
        write_passage(_result(), tmp_path, fmt, dtype=dtype)


def test_without_empty_columns_and_float64_rule():
    cols = {"a": np.array([np.nan, 1.0]), "b": np.full(2, np.nan), "c": np.array([1, 2])}
    assert list(without_empty_columns(cols)) == ["a", "c"]
    assert keeps_float64("t_s") and keeps_float64("x_ws3_m") and keeps_float64("x_m")
    assert not keeps_float64("Fz_right_N") and not keeps_float64("y_rail_r1_m")


def test_csv_reads_back_as_text_stream():
    text = csv_text({"t_s": np.array([0.1, 0.2]), "F_N": np.array([1.0, np.nan])})
    rows = list(csv.reader(io.StringIO(text)))
    assert rows == [["t_s", "F_N"], ["0.1", "1"], ["0.2", ""]]


def test_cli_float32_needs_npz(tmp_path, capsys):
    from exudyn_turnout.cli.main import main

    out = tmp_path / "run"
    code = main(["simulate", "--x-start", "20", "--x-end", "20.01", "--float32", "--out", str(out)])
    assert code == 2
    assert capsys.readouterr().err.strip() == (
        "error: --float32: only with --format npz (the CSV writes digits)"
    )
    assert not out.exists()  # refused before --out is touched


def test_cli_float32_npz(tmp_path):
    from exudyn_turnout.cli.main import main

    argv = ["simulate", "--vehicle", "wheelset", "--x-start", "20", "--x-end", "20.01"]
    argv += ["--format", "npz", "--float32"]
    assert main([*argv, "--no-plot", "--out", str(tmp_path)]) == 0
    with np.load(tmp_path / "timeseries.npz") as data:
        assert data["t_s"].dtype == np.float64 and data["Fz_right_N"].dtype == np.float32
        assert json.loads(str(data["summary"]))["provenance"]["settings"]["format"] == "npz"


def test_compiled_formatter_is_pythons_text():
    """The compiled %.9g (csv_format.format_rows) against Python's own formatting, on random
    values of every magnitude the outputs meet, constructed rounding ties, specials."""
    from exudyn_turnout.passage.csv_format import COMPILED_FROM, format_rows, python_rows

    rng = np.random.default_rng(11)
    n = COMPILED_FROM
    values = rng.normal(size=n) * 10.0 ** rng.integers(-13, 15, size=n)
    ties = [(rng.integers(10**8, 10**9) + 0.5) * 10.0**k for k in range(-12, 12) for _ in range(50)]
    special = [0.0, -0.0, 1.0, 1e9, 1e-5, 1e-4, 999999999.5, 12345678.95, 5e-324, 1e300]
    table = np.concatenate([special, ties, values, [np.nan, np.inf, -np.inf]]).reshape(-1, 1)
    text = format_rows(table, 9)
    assert text == "".join(f"{v:.9g}\n" if np.isfinite(v) else "\n" for v in table[:, 0])
    wide = table[: 4 * (len(table) // 4)].reshape(-1, 4)
    assert format_rows(wide, 9) == python_rows(wide, 9)
    with pytest.raises(ValueError, match="digits must be 1 to 10"):
        format_rows(table, 12)


def test_contact_points_of_a_result_without_an_unloaded_points_columns():
    """A contact point whose position never had a value (its column dropped) still lists."""
    result = _result()
    points = result.contact_points("right")
    loaded = result.columns["cp_right_r2_nose_0_N_N"] > 0
    assert len(points["x"]) == int(loaded.sum())
    assert np.all(points["y_rail"] == 0.012345678)
    assert np.all(np.isnan(points["angle"]))  # no angle column: NaN


@pytest.mark.parametrize(
    "rows, block",
    [(N, 1 << 16), (30_000, 1 << 16), (30_000, 4 * 999), (30_001, 7)],  # Python's, compiled
)
def test_write_csv_writes_the_bytes_of_csv_text(tmp_path, rows, block):
    """write_csv (straight from the formatter's buffer) against csv_text written as text."""
    from exudyn_turnout.passage.output_files import write_csv

    rng = np.random.default_rng(5)
    columns = {
        "t_s": np.arange(rows) * 1e-4,
        "F_N": rng.normal(size=rows) * 10.0 ** rng.integers(-6, 6, size=rows),
        "y_m": np.where(rng.random(rows) < 0.3, np.nan, rng.normal(size=rows) * 1e-3),
        "n": np.arange(rows) % 7,  # integers are written as floats, as csv_text does
    }
    write_csv(tmp_path / "a.csv", columns, block=block)  # blocks of 1 to 16,384 rows
    (tmp_path / "b.csv").write_text(csv_text(columns), encoding="utf-8")
    assert (tmp_path / "a.csv").read_bytes() == (tmp_path / "b.csv").read_bytes()
    assert (tmp_path / "a.csv").read_bytes().startswith(b"t_s,F_N,y_m,n\n0,")


def test_png_figures_are_saved_at_the_fast_compression_level(tmp_path):
    """save_figure writes PNG at zlib level 1 (the same pixels as Pillow's default level)."""
    from PIL import Image

    from exudyn_turnout.plotting.backend import PNG_COMPRESS_LEVEL, pyplot, save_options
    from exudyn_turnout.plotting.curves import save_figure

    assert save_options("a/forces.png") == {"pil_kwargs": {"compress_level": PNG_COMPRESS_LEVEL}}
    assert save_options("a/forces.pdf") == {}  # other formats take no Pillow options
    plt = pyplot()
    pixels = []
    for name, options in (("fast.png", None), ("default.png", {})):
        fig, ax = plt.subplots(figsize=(3, 2))
        ax.plot(np.sin(np.linspace(0.0, 20.0, 500)))
        if options is None:
            save_figure(fig, tmp_path / name, dpi=80)
        else:
            fig.savefig(tmp_path / name, dpi=80)
            plt.close(fig)
        with Image.open(tmp_path / name) as image:
            pixels.append(np.asarray(image))
    np.testing.assert_array_equal(pixels[0], pixels[1])
    fig, ax = plt.subplots(figsize=(3, 2))
    save_figure(fig, tmp_path / "vector.pdf")  # no Pillow option passed to the PDF writer
    assert (tmp_path / "vector.pdf").read_bytes().startswith(b"%PDF")
