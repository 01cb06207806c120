"""``exudyn-turnout validate``: the validation report.

2-layer vs 3-layer co-running track vs the FE reference, and a verdict on every claim of the
paper.
"""

from __future__ import annotations

import argparse

from exudyn_turnout.cli.main import UsageError, check_out_dir

__all__ = ["build"]


def _run(args: argparse.Namespace) -> int:
    """Write the report into ``--out``; print a one-line summary of the verdicts."""
    from exudyn_turnout.inputs.turnout import load_turnout
    from exudyn_turnout.report.metrics import report_config, write_report

    check_out_dir(args.out)
    if args.cache:
        check_out_dir(args.cache, "--cache")
    turnout = load_turnout(args.turnout)
    if args.no_cache and args.cache:
        raise UsageError("validate: give --cache DIR or --no-cache, not both")
    cache = None if args.no_cache else (args.cache or "default")
    try:
        report = write_report(args.out, report_config(quick=args.quick, cache_dir=cache), turnout)
    except OSError as err:
        raise UsageError(f"validate: cannot write the report: {err}") from None
    _add_provenance(args, turnout, cache)
    verdicts: dict[str, int] = {}  # verdict -> number of claims
    for claim in report.claims:
        verdicts[claim.verdict] = verdicts.get(claim.verdict, 0) + 1
    wall_time = report.metrics["report_wall_time_s"]
    print(
        f"wrote {args.out}/report.md, metrics.json and figures in {wall_time:.0f} s; "
        "claims: " + ", ".join(f"{count} {verdict}" for verdict, count in verdicts.items())
    )
    return 0


def _add_provenance(args: argparse.Namespace, turnout, cache) -> None:
    """Put the provenance record into DIR/metrics.json unless the report code already did."""
    import json
    import os
    from pathlib import Path

    from exudyn_turnout.provenance import provenance

    path = Path(args.out) / "metrics.json"
    try:
        metrics = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return
    if not isinstance(metrics, dict) or "provenance" in metrics:
        return
    settings = {
        "quick": args.quick,
        "cache": "none"
        if cache is None
        else ("default" if cache == "default" else Path(cache).name),
    }
    metrics["provenance"] = provenance(settings, turnout=turnout, argv=getattr(args, "argv", None))
    tmp = path.with_name(f".metrics.partial-{os.getpid()}.json")
    try:
        # the report's numbers as they are (no rounding here)
        tmp.write_text(json.dumps(metrics, indent=1) + "\n", encoding="utf-8")
        os.replace(tmp, path)
    except OSError as err:
        raise UsageError(f"validate: cannot write {path.name}: {err.strerror or err}") from None
    finally:
        if tmp.exists():
            tmp.unlink()


def build(sub: argparse._SubParsersAction) -> None:
    """Register the command on the ``exudyn-turnout`` subcommand parsers.

    Parameters
    ----------
    sub : argparse._SubParsersAction
        The subcommand parsers of ``exudyn-turnout``; ``validate`` is added to them.
    """
    parser = sub.add_parser(
        "validate",
        help="validation report: 2-layer vs 3-layer vs FE reference",
        description="Write DIR/report.md, its PNG figures and DIR/metrics.json: "
        "parameters vs Table 2, track stiffness, receptance, contact forces, computing cost "
        "and checks, with a verdict on every claim of the paper.",
    )
    parser.add_argument(
        "--turnout", metavar="FILE", help="turnout file (default: packaged UIC60-760-1:15)"
    )
    parser.add_argument("--out", required=True, metavar="DIR", help="output directory")
    parser.add_argument(
        "--quick",
        action="store_true",
        help="reduced report for CI (coarse FE, few frequencies, short runs)",
    )
    parser.add_argument(
        "--cache", metavar="DIR", help="FE result cache (default: ~/.cache/exudyn_turnout)"
    )
    parser.add_argument(
        "--no-cache", action="store_true", help="compute every FE result in this run"
    )
    parser.set_defaults(run=_run)
