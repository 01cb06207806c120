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
here.
"""

from __future__ import annotations

import argparse
import json
import math
from pathlib import Path

from exudyn_turnout.inputs.turnout import load_turnout
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
    args = parser.parse_args(argv)
    against = json.loads(Path(args.against).read_text()) if args.against else None
    saved: dict[str, dict[str, float]] = {}
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
