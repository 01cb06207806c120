"""``exudyn-turnout validate``: the validation report (2-layer vs 3-layer vs FE, every claim of the paper)."""
from __future__ import annotations

import argparse

from .cli import UsageError

__all__ = ["build"]


def _run(args: argparse.Namespace) -> int:
    """Write the report into ``--out``; print a one-line summary of the verdicts."""
    from .report import report_config, write_report
    from .turnout import load_turnout

    turnout = load_turnout(args.turnout)
    if args.no_cache and args.cache:
        raise UsageError("validate: give --cache DIR or --no-cache, not both")
    cache = None if args.no_cache else (args.cache or "default")
    try:
        report = write_report(args.out, report_config(quick=args.quick, cache_dir=cache), turnout)
    except OSError as err:
        raise UsageError(f"validate: cannot write the report: {err}") from None
    verdicts = {}
    for c in report.claims:
        verdicts[c.verdict] = verdicts.get(c.verdict, 0) + 1
    print(f"wrote {args.out}/report.md, metrics.json and figures in {report.metrics['report_wall_time_s']:.0f} s; "
          "claims: " + ", ".join(f"{n} {v}" for v, n in verdicts.items()))
    return 0


def build(sub: argparse._SubParsersAction) -> None:
    """Register ``validate`` on the ``exudyn-turnout`` subcommand parsers."""
    p = sub.add_parser("validate", help="validation report: 2-layer vs 3-layer vs FE reference",
                       description="Write DIR/report.md, its PNG figures and DIR/metrics.json: parameters vs Table 2, "
                                   "track stiffness, receptance, contact forces, computing cost and checks, with a "
                                   "verdict on every claim of the paper.")
    p.add_argument("--turnout", metavar="FILE", help="turnout file (default: packaged UIC60-760-1:15)")
    p.add_argument("--out", required=True, metavar="DIR", help="output directory")
    p.add_argument("--quick", action="store_true",
                   help="reduced report for CI (coarse FE, few frequencies, short runs)")
    p.add_argument("--cache", metavar="DIR", help="FE result cache (default: ~/.cache/exudyn_turnout)")
    p.add_argument("--no-cache", action="store_true", help="compute every FE result in this run")
    p.set_defaults(run=_run)
