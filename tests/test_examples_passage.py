"""The passage examples run (short x range), tell the truth about time, and keep to the
route's permitted speed.

Reference: the paper's Section 4 finding that the two-layer model overestimates the
crossing impact; here checked as a property of our models (3-layer peak < 2-layer peak at
the crossing nose), not as a number from the paper. The diverging route's permitted speed,
80 km/h, is the packaged turnout file's (data/uic60_760_1_15.toml,
``routes.diverging.permitted_speed_kmh``).
"""

import importlib.util
import warnings
from pathlib import Path

import pytest

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def _load(name):
    spec = importlib.util.spec_from_file_location(name, EXAMPLES / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.mark.slow
def test_through_example(tmp_path, capsys, monkeypatch):
    example = _load("passage_through")
    order = []
    warm = example.warm_up
    monkeypatch.setattr(example, "warm_up", lambda *a: order.append("warm-up") or warm(*a))
    compare = example.compare_tracks
    monkeypatch.setattr(
        example, "compare_tracks", lambda *a, **k: order.append("models") or compare(*a, **k)
    )
    comparison = example.run(tmp_path, x_start=46.4, x_end=48.4)
    assert order == ["warm-up", "models"]  # the models are timed after the warm-up
    assert (tmp_path / "through_2_vs_3_layers.png").exists()
    two, three = comparison["2-layer"], comparison["3-layer"]
    assert three.summary["peak_Fz_crossing_N"] < two.summary["peak_Fz_crossing_N"]
    assert three.settings.speed_kmh == 100.0  # no permitted speed on the through route
    assert "x_ws4_m" in three.columns  # the package's default: the full vehicle
    out = capsys.readouterr().out
    assert out.index("warm-up") < out.index("3-layer vs 2-layer")
    assert "after the warm-up" in out and "peaks of the right wheel" in out


def test_diverging_example_within_the_permitted_speed(tmp_path, capsys):
    example = _load("passage_diverging")
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # a speed warning would fail here
        # the single wheelset: the test is about the route's speed and the wheel named
        comparison = example.run(
            tmp_path, x_start=20.0, x_end=21.0, wheel="left", vehicle="wheelset"
        )
    assert (tmp_path / "diverging_2_vs_3_layers.png").exists()
    assert set(comparison) == {"2-layer", "3-layer"}
    assert all(r.settings.route == "diverging" for r in comparison.values())
    assert all(r.settings.speed_kmh == 80.0 for r in comparison.values())
    out = capsys.readouterr().out
    # the wheel the console names is the wheel plotted
    assert "peaks of the left wheel" in out and "(left wheel)" in out
    assert "left wheel" in out.splitlines()[-1]


@pytest.mark.parametrize(
    ("name", "route"), [("passage_through", "Through route"), ("passage_diverging", "Diverging")]
)
def test_example_help_names_its_own_route(name, route, capsys, monkeypatch):
    """Each example's --help starts with its own docstring's first paragraph (the diverging
    example reuses the through example's command line and once printed "Through route")."""
    import runpy

    path = Path(__file__).resolve().parents[1] / "examples" / f"{name}.py"
    monkeypatch.setattr("sys.argv", [path.name, "--help"])
    monkeypatch.syspath_prepend(str(path.parent))
    with pytest.raises(SystemExit) as stop:
        runpy.run_path(str(path), run_name="__main__")
    assert stop.value.code == 0
    assert capsys.readouterr().out.split("\n\n")[1].startswith(route)


def test_creep_reduction_example(tmp_path):
    """Factor 1 is the default passage to the bit (the knob leaves the tables themselves);
    a lower factor changes the check rail's force; the table names every factor."""
    from exudyn_turnout.inputs.turnout import load_turnout
    from exudyn_turnout.passage import simulate_passage
    from exudyn_turnout.passage.settings import PassageSettings

    example = _load("creep_reduction")
    window = {"x_start": 40.0, "x_end": 46.0}
    results = example.run((1.0, 0.6), vehicle="wheelset", **window)
    plain = simulate_passage(
        load_turnout(),
        PassageSettings(route="diverging", speed_kmh=80.0, **window),
        "wheelset",
    )
    key = "peak_Fy_check_rail_N"
    assert results[1.0].summary[key] == plain.summary[key] > 1e3
    assert results[0.6].summary[key] != results[1.0].summary[key]
    text = example.table(results)
    assert "check rail Fy" in text and "0.6" in text
