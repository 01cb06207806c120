"""Re-run the validation reports' co-running passages and compare with their committed metrics.

Run: ``python validation/passage_peaks_unchanged.py [--tracks 2-layer 3-layer]`` (about 2 min
per turnout on a quiet 2-core machine). For the packaged turnout (``validation/report``)
and the second turnout (``validation/second_turnout``) it runs every report route with the
report's own settings (full Manchester vehicle, profile contact, the whole turnout, the
report's speeds and time step: ``exudyn_turnout.report.passages.run_passage``), takes the
report's numbers of each run (``passage_model_metrics``: the front right wheel's peaks at
the switch and the crossing, vertical and lateral, their dynamic RMS, the static wheel
load, contact losses) and prints the largest relative difference from the committed
``metrics.json``. A refactor that keeps the physics keeps these within round-off (issue 21:
1e-9). ``--save FILE`` stores the numbers of this run; ``--against FILE`` compares with such
a file (run the script at the commit before a refactor with ``--save``, after it with
``--against``: the differences are then the refactor's alone, free of whatever separates
the committed reports from the code). The FE passages (about 1000 s each) are not re-run
here; ``--windows`` runs instead short windows of every vehicle x track (FE included) and
of the height-table contact, and compares every number of their summaries and the largest
absolute value of every column (use it with ``--save`` / ``--against``).
"""

from __future__ import annotations

import argparse
import json
import math
from pathlib import Path

from exudyn_turnout.inputs.turnout import load_turnout
from exudyn_turnout.passage import simulate_passage
from exudyn_turnout.passage.settings import PassageSettings
from exudyn_turnout.report.config import report_config, resolve_config
from exudyn_turnout.report.passages import (
    passage_model_metrics,
    run_passage,
    vehicle_static_load,
)
from exudyn_turnout.report.settings import FORCES, REGIONS, report_settings

HERE = Path(__file__).resolve().parent
DATA = HERE.parent / "exudyn_turnout" / "data"
#: (name, turnout file, committed metrics)
REPORTS = (
    ("UIC60-760-1:15", None, HERE / "report" / "metrics.json"),
    ("EW54-190-1:9", DATA / "ew54_190_1_9.toml", HERE / "second_turnout" / "metrics.json"),
)


def _numbers(record: dict, prefix: str = "") -> dict[str, float]:
    """The numbers of a model's record that do not depend on the machine (no wall times)."""
    out: dict[str, float] = {}
    for key, value in record.items():
        if "wall_time" in key or key == "vs_FE":
            continue
        if isinstance(value, dict):
            out.update(_numbers(value, f"{prefix}{key}/"))
        elif isinstance(value, (int, float)) and not isinstance(value, bool):
            out[f"{prefix}{key}"] = float(value)
    return out


#: Short windows: (case, vehicle, track, settings).
WINDOWS = (
    ("wheelset 2-layer through crossing", "wheelset", "2-layer", dict(x_start=43.0, x_end=49.0)),
    ("wheelset 3-layer through crossing", "wheelset", "3-layer", dict(x_start=43.0, x_end=49.0)),
    ("wheelset 3-layer through switch", "wheelset", "3-layer", dict(x_start=-2.0, x_end=6.0)),
    (
        "wheelset 2-layer diverging 60",
        "wheelset",
        "2-layer",
        dict(route="diverging", speed_kmh=60.0, x_start=42.0, x_end=50.0),
    ),
    (
        "wheelset 3-layer height-table",
        "wheelset",
        "3-layer",
        dict(x_start=43.0, x_end=49.0, contact="height-table"),
    ),
    ("wheelset FE through", "wheelset", "fe", dict(x_start=46.6, x_end=47.2)),
    ("manchester 2-layer through", "manchester", "2-layer", dict(x_start=42.0, x_end=50.0)),
    ("manchester 3-layer through", "manchester", "3-layer", dict(x_start=42.0, x_end=50.0)),
    (
        "manchester 3-layer diverging 80",
        "manchester",
        "3-layer",
        dict(route="diverging", speed_kmh=80.0, x_start=40.0, x_end=47.0),
    ),
    ("manchester FE through", "manchester", "fe", dict(x_start=46.6, x_end=47.0)),
)


def _window_numbers(result) -> dict[str, float]:
    """Every number of a window's summary (no wall times) and max |column|."""
    out = {}
    for key, value in result.summary.items():
        if isinstance(value, (int, float)) and not isinstance(value, bool) and "wall" not in key:
            out[f"summary:{key}"] = float(value)
    for key, column in result.columns.items():
        values = [abs(float(v)) for v in column if math.isfinite(float(v))]
        if values:
            out[f"max|{key}|"] = max(values)
    return out


def _run_window(turnout, settings, vehicle: str, track: str):
    """One window through the door; before issue 21 (commit 8bb37b5) through the two old
    doors, so that ``--save`` works on the code before the refactor too."""
    from importlib import import_module
    from importlib.util import find_spec

    if find_spec("exudyn_turnout.passage.run") is not None:
        return simulate_passage(turnout, settings, vehicle, track=track)
    if vehicle == "wheelset":
        return simulate_passage(turnout, settings, track=track)
    from exudyn_turnout.inputs.vehicle_model import load_vehicle_model

    old = import_module("exudyn_turnout.passage.full_vehicle_passage")
    return old.simulate_vehicle_passage(turnout, settings, load_vehicle_model(), track=track)


def _windows(against: dict | None, saved: dict) -> float:
    """Run :data:`WINDOWS`; print each case's largest difference from ``against``."""
    turnout = load_turnout()
    worst_all = 0.0
    print(f"{'case':<36}{'numbers':>8}{'max rel diff':>14}  worst")
    for case, vehicle, track, kw in WINDOWS:
        settings = PassageSettings(**kw)
        now = _window_numbers(_run_window(turnout, settings, vehicle, track))
        saved[case] = now
        if against is None:
            print(f"{case:<36}{len(now):>8}")
            continue
        then = against[case]
        keys = sorted(set(now) & set(then))
        diffs = {k: _relative(now[k], then[k]) for k in keys}
        worst = max(diffs, key=lambda k: diffs[k])
        worst_all = max(worst_all, diffs[worst])
        print(f"{case:<36}{len(keys):>8}{diffs[worst]:>14.2e}  {worst}")
    return worst_all


def _relative(a: float, b: float) -> float:
    if a == b or (math.isnan(a) and math.isnan(b)):
        return 0.0
    return abs(a - b) / max(abs(a), abs(b))


def main(argv: list[str] | None = None) -> int:
    """Print the table; exit 1 when a difference exceeds 1e-9."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--tracks", nargs="+", default=["2-layer", "3-layer"])
    parser.add_argument("--save", metavar="FILE", help="store this run's numbers (JSON)")
    parser.add_argument("--against", metavar="FILE", help="compare with a --save file")
    parser.add_argument(
        "--windows", action="store_true", help="short windows of every vehicle x track instead"
    )
    args = parser.parse_args(argv)
    against = json.loads(Path(args.against).read_text()) if args.against else None
    saved: dict[str, dict[str, float]] = {}
    if args.windows:
        worst_all = _windows(against, saved)
        if args.save:
            Path(args.save).write_text(json.dumps(saved, indent=1))
        if against is not None:
            print(f"largest relative difference from {args.against}: {worst_all:.2e}")
        return 0 if worst_all <= 1e-9 else 1
    worst_all = 0.0
    print(f"{'turnout':<16}{'route':<11}{'track':<9}{'numbers':>8}{'max rel diff':>14}  worst")
    for name, path, committed in REPORTS:
        turnout = load_turnout(path)
        settings = report_settings(turnout)
        config = resolve_config(report_config(), settings, turnout)
        stored = json.loads(committed.read_text())["passage"]
        reference = "committed metrics.json" if against is None else args.against
        static = vehicle_static_load(config.vehicle)
        every = tuple((q, r) for q in FORCES for r in REGIONS)
        for rr in settings.routes:
            for track in args.tracks:
                result = run_passage(turnout, config, rr.name, track)
                record = passage_model_metrics(
                    result, every, dict(settings.regions), config.criteria, static, None, rr.wheel
                )
                now = _numbers(record)
                case = f"{name} {rr.name} {track}"
                saved[case] = now
                if against is None:
                    then = _numbers(stored["routes"][rr.name]["models"][track])
                else:
                    then = against[case]
                keys = sorted(set(now) & set(then))
                diffs = {k: _relative(now[k], then[k]) for k in keys}
                worst = max(diffs, key=lambda k: diffs[k])
                worst_all = max(worst_all, diffs[worst])
                print(
                    f"{name:<16}{rr.name:<11}{track:<9}{len(keys):>8}{diffs[worst]:>14.2e}  "
                    f"{worst} ({then[worst]:.6g} -> {now[worst]:.6g})"
                )
    print(f"largest relative difference from the {reference}: {worst_all:.2e}")
    if args.save:
        Path(args.save).write_text(json.dumps(saved, indent=1))
    return 0 if worst_all <= 1e-9 else 1


if __name__ == "__main__":
    raise SystemExit(main())
