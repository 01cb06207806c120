"""``exudyn-turnout fit``: co-running parameters fitted to the FE receptance (source ``fitted``).

For every zone (or the zones of ``--positions``), the FE point receptances of the zone's
active rails, vertical and lateral, are computed at the fit positions (sleepers of the
zone, every ``--every``-th, or ``--positions``) with one FE model per zone and direction;
:func:`exudyn_turnout.corunning.fit.fit_zone` fits the co-running model to them; the set
is written as TOML with its provenance (:mod:`exudyn_turnout.corunning.fitted`). Use it
with ``--source fitted --parameters FILE`` on ``params``, ``frf``, ``simulate``, ``draw``.

Imports exudyn and matplotlib nowhere; the FE and fit modules are imported in ``_run``.
"""

from __future__ import annotations

import argparse
import math
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from exudyn_turnout.cli.main import (
    UsageError,
    check_out_file,
    number,
    write_output,
)
from exudyn_turnout.inputs.turnout import RAIL_SLOTS, Turnout, Zone

__all__ = [
    "LATERAL_REFERENCES",
    "build",
    "sleeper_positions",
    "fe_fit_targets",
    "coarse_fe_options",
    "reference_description",
]

#: The lateral FE references a fit can take: ``"torsion"`` the torsion-aware FE (the rail
#: rolls on its pads, the check rail on its L-bracket; force and response at the gauge
#: corner): the FE track of the FE passages, the default; ``"planar"`` the planar lateral
#: FE (no roll, force and response at the rail): the kind of FE the paper had.
LATERAL_REFERENCES = ("torsion", "planar")


def reference_description(lateral: str) -> str:
    """The FE reference of a fit in words (for the fitted file's header).

    Parameters
    ----------
    lateral : {"torsion", "planar"}

    Returns
    -------
    str
    """
    if lateral == "torsion":
        return (
            "vertical: FE vertical plane at the rail; lateral: torsion-aware FE (rails roll "
            "on their pads, check rails on their L-brackets), force and response at the "
            "gauge corner: the FE track of the FE passages"
        )
    return (
        "vertical: FE vertical plane at the rail; lateral: planar FE (no roll), force and "
        "response at the rail: the kind of FE the paper had"
    )


def build(sub: argparse._SubParsersAction) -> None:
    """Register the command on the ``exudyn-turnout`` subcommand parsers.

    Parameters
    ----------
    sub : argparse._SubParsersAction
        The subcommand parsers of ``exudyn-turnout``; ``fit`` is added to them.
    """
    p = sub.add_parser(
        "fit",
        help="co-running parameters fitted to the FE receptance (writes a fitted file)",
        description="Fit the co-running parameters (same springs, dampers and masses as "
        "the derived set) so that the model's point receptance matches the FE receptance, "
        "vertical and lateral, of the active rails at the fit positions: band RMS of "
        "20 log10(|H|/|H_FE|) over 1/3-octave bands, pinned-pinned bands down-weighted. "
        "Writes a TOML file for --source fitted --parameters FILE.",
    )
    p.add_argument(
        "--turnout", metavar="FILE", help="turnout file (default: packaged UIC60-760-1:15)"
    )
    p.add_argument(
        "--layers", type=int, choices=(2, 3), default=3, help="track model layers (default 3)"
    )
    p.add_argument("--out", required=True, metavar="FILE.toml", help="fitted file to write")
    p.add_argument(
        "--positions",
        type=number,
        nargs="+",
        metavar="X",
        help="fit positions (m from the switch toe); only their zones are fitted "
        "(default: the sleepers of every zone, see --every)",
    )
    p.add_argument(
        "--every",
        type=int,
        default=4,
        metavar="N",
        help="without --positions: every N-th sleeper of each zone (default 4, 2.4 m)",
    )
    p.add_argument(
        "--rails",
        nargs="+",
        choices=RAIL_SLOTS,
        metavar="SLOT",
        help="rail slots to fit (default: every active rail of the zone)",
    )
    p.add_argument(
        "--route", default="through", help="route whose FE rail slots are used (default through)"
    )
    p.add_argument(
        "--lateral-fe",
        choices=LATERAL_REFERENCES,
        default="torsion",
        help="lateral FE reference: torsion (rails roll, gauge corner; the FE passages' "
        "track; default) or planar (no roll, at the rail; the paper's kind of FE)",
    )
    p.add_argument("--fmin", type=number, default=1.0, metavar="HZ", help="default 1 Hz")
    p.add_argument("--fmax", type=number, default=2000.0, metavar="HZ", help="default 2000 Hz")
    p.add_argument("--n", type=int, default=400, help="log-spaced FE frequencies (default 400)")
    p.add_argument(
        "--coarse",
        action="store_true",
        help="coarse FE mesh (quadratic elements, 0.6 m, short model ends): fast, for tests",
    )
    p.set_defaults(run=_run)


def coarse_fe_options() -> Any:
    """The coarse FE options of ``--coarse`` (those of the quick validation report).

    Returns
    -------
    exudyn_turnout.fe.mesh.FEOptions
        Quadratic elements of 0.6 m, 1 m sleeper elements, 6 m extension and absorbing end.
    """
    from exudyn_turnout.fe.mesh import FEOptions

    return FEOptions(
        element_order=2,
        element_length=0.6,
        sleeper_element_length=1.0,
        extension=6.0,
        absorbing_length=6.0,
    )


def sleeper_positions(turnout: Turnout, zone: Zone, every: int = 1) -> list[float]:
    """x of every ``every``-th sleeper strictly inside a zone (``[layout] sleeper_x0`` grid).

    Parameters
    ----------
    turnout : Turnout
        Sleepers at ``sleeper_x0 + i * sleeper.spacing``.
    zone : Zone
        The zone.
    every : int
        Stride (>= 1); the zone's first and last sleeper are always included.

    Returns
    -------
    list of float
        m, increasing.
    """
    x0 = float(turnout.raw.get("layout", {}).get("sleeper_x0", 0.0))
    s = turnout.sleeper.spacing
    i0 = math.floor((zone.x_start - x0) / s) + 1
    xs = [x0 + i * s for i in range(i0, i0 + 10000)]
    xs = [round(x, 9) for x in xs if zone.x_start < x < zone.x_end]
    if not xs:
        return [0.5 * (zone.x_start + zone.x_end)]
    picked = xs[::every]
    if picked[-1] != xs[-1]:
        picked.append(xs[-1])
    return picked


def _pinned_pinned_hz(turnout: Turnout, rail_type: str, x: float, direction: str) -> float:
    """First mode of a simply supported Timoshenko beam over one sleeper bay (Hz)."""
    import numpy as np

    from exudyn_turnout.fe.analytic import simply_supported_timoshenko_frequency
    from exudyn_turnout.fe.model import rail_section

    section = {
        k: float(np.ravel(v)[0])
        for k, v in rail_section(turnout, rail_type, np.array([x]), direction).items()
    }
    return simply_supported_timoshenko_frequency(
        turnout.sleeper.spacing, section["EI"], section["kGA"], section["rhoA"], section["rhoI"]
    )


def fe_fit_targets(
    turnout: Turnout,
    zone: Zone,
    positions: Sequence[float],
    frequencies: Any,
    options: Any = None,
    route: str = "through",
    rails: Sequence[str] | None = None,
    lateral: str = "torsion",
) -> tuple[list[list[Any]], tuple[str, ...]]:
    """FE point receptances of a zone's rails at the fit positions, as fit targets.

    One FE mesh (all positions as rail nodes) and one sweep per direction.

    Parameters
    ----------
    turnout : Turnout
        With a ``[layout]``.
    zone : Zone
        The zone the positions lie in.
    positions : sequence of float
        m, fit positions.
    frequencies : array_like
        Hz.
    options : FEOptions, optional
        FE discretisation (default ``FEOptions()``).
    route : str
        Route of the slot-to-rail table.
    rails : sequence of str, optional
        Rail slots to fit (default: the zone's active rails); a slot without an FE rail
        at a position (the switch rail ahead of the toe) has no target there.
    lateral : {"torsion", "planar"}
        Lateral FE reference (:data:`LATERAL_REFERENCES`): torsion-aware at the gauge
        corner (the FE passages' track, default) or planar at the rail (the paper's kind).

    Returns
    -------
    targets : list of list of FitTarget
        Per position, one target per rail and direction.
    rails : tuple of str
        The rail slots used.
    """
    import numpy as np

    from exudyn_turnout.corunning.fit import FitTarget
    from exudyn_turnout.fe.frf import load_height, resolve_rail, sweep_vectors
    from exudyn_turnout.fe.layout import load_layout
    from exudyn_turnout.fe.mesh import FEOptions, build_mesh
    from exudyn_turnout.fe.model import assemble
    from exudyn_turnout.fe.torsion import UIC60_SECTION
    from exudyn_turnout.receptance import Receptance

    if lateral not in LATERAL_REFERENCES:
        raise ValueError(f"lateral must be one of {', '.join(LATERAL_REFERENCES)}, got {lateral!r}")
    options = options or FEOptions()
    layout = load_layout(turnout)
    f = np.asarray(frequencies, float)
    wanted = tuple(rails) if rails else tuple(r for r in RAIL_SLOTS if r in zone.active_rails)
    for rail in wanted:
        if rail not in zone.active_rails:
            raise ValueError(
                f"rail {rail} is not active in zone {zone.index} "
                f"(active rails: {' '.join(zone.active_rails)})"
            )
    ids: dict[tuple[str, float], str] = {}
    for rail in wanted:
        for x in positions:
            try:
                ids[(rail, x)] = resolve_rail(layout, rail, float(x), route)
            except ValueError:  # no FE rail in this slot here (switch rail ahead of the toe)
                continue
    used = [rail for rail in wanted if any(key[0] == rail for key in ids)]
    missing = [x for x in positions if not any(key[1] == x for key in ids)]
    if missing:
        raise ValueError(f"no rail of zone {zone.index} has an FE rail at x = {missing[0]:g} m")
    points: dict[str, list[float]] = {}
    for (_, x), rail_id in ids.items():
        points.setdefault(rail_id, []).append(float(x))
    mesh = build_mesh(turnout, layout, options, points=points)
    keys = list(ids)
    targets: list[list[Any]] = [[] for _ in positions]
    for direction in ("vertical", "lateral"):
        torsion = UIC60_SECTION if direction == "lateral" and lateral == "torsion" else None
        model = assemble(turnout, mesh, direction, torsion=torsion)
        z = load_height(torsion, "head") if torsion is not None else 0.0
        B = np.column_stack([model.head_vector(ids[k], float(k[1]), z) for k in keys])
        H = sweep_vectors(model, B, f)
        for j, (rail, x) in enumerate(keys):
            i = list(positions).index(x)
            meta = {"rail_id": ids[(rail, x)], "lateral_reference": lateral}
            reference = Receptance(f, H[:, j], rail, direction, float(x), "FE", meta)
            f_pp = _pinned_pinned_hz(turnout, zone.rail_types[rail], float(x), direction)
            targets[i].append(FitTarget(rail, direction, reference, f_pp))
    return targets, tuple(used)


def _zones_and_positions(
    turnout: Turnout, positions: Sequence[float] | None, every: int
) -> list[tuple[Zone, list[float]]]:
    if positions is None:
        return [(zone, sleeper_positions(turnout, zone, every)) for zone in turnout.zones]
    out: dict[int, list[float]] = {}
    for x in sorted(set(positions)):
        try:
            zone = turnout.zone_at(float(x))
        except ValueError as err:
            raise UsageError(f"--positions: {err}") from None
        out.setdefault(zone.index, []).append(float(x))
    return [(turnout.zone(i), xs) for i, xs in sorted(out.items())]


def _check_route_and_rails(
    turnout: Turnout, route: str, rails: Sequence[str] | None, zones: Sequence[Zone]
) -> None:
    """``--route`` names a slot table of ``[layout.slots]`` and ``--rails`` are active in
    every zone to fit: bad input is refused before any FE work (one line, exit 2)."""
    from exudyn_turnout.inputs.toml_fields import did_you_mean

    slots = turnout.raw["layout"].get("slots", {})
    names = tuple(slots) if isinstance(slots, dict) else ()
    if names and route not in names:
        raise UsageError(
            f"fit: --route {route}: {Path(turnout.source).name} has no [layout.slots.{route}]"
            f"{did_you_mean(route, names)}"
        )
    for zone in zones:
        for rail in rails or ():
            if rail not in zone.active_rails:
                raise UsageError(
                    f"fit: --rails {rail}: not active in zone {zone.index} ({zone.name}; "
                    f"active rails: {' '.join(zone.active_rails)})"
                )


def _run(args: argparse.Namespace) -> int:
    from exudyn_turnout.corunning.fit import FitOptions, fit_zone, fitted_set
    from exudyn_turnout.corunning.fitted import file_sha256, turnout_model_sha256, write_fitted
    from exudyn_turnout.corunning.parameters import co_running_parameters
    from exudyn_turnout.fe.mesh import FEOptions
    from exudyn_turnout.inputs.turnout import load_turnout
    from exudyn_turnout.provenance import provenance
    from exudyn_turnout.receptance import log_frequencies

    check_out_file(args.out)
    if args.every < 1:
        raise UsageError(f"--every must be >= 1, got {args.every}")
    try:
        frequencies = log_frequencies(args.fmin, args.fmax, args.n)
    except ValueError as err:
        raise UsageError(f"fit: {err}") from None
    turnout = load_turnout(args.turnout)
    if "layout" not in turnout.raw:
        raise UsageError(f"fit: {turnout.source} has no [layout] section (the FE model needs it)")
    work = _zones_and_positions(turnout, args.positions, args.every)
    _check_route_and_rails(turnout, args.route, args.rails, [zone for zone, _ in work])
    options = coarse_fe_options() if args.coarse else FEOptions()
    fit_options = FitOptions(f_min=args.fmin, f_max=args.fmax)
    zone_fits, rails_used = [], {}
    for zone, xs in work:
        params = co_running_parameters(turnout, zone=zone.index, layers=args.layers)
        print(
            f"zone {zone.index}: FE receptances at {len(xs)} position(s)",
            file=sys.stderr,
            flush=True,
        )
        try:
            targets, rails = fe_fit_targets(
                turnout,
                zone,
                xs,
                frequencies,
                options,
                route=args.route,
                rails=args.rails,
                lateral=args.lateral_fe,
            )
        except ValueError as err:
            raise UsageError(f"fit: zone {zone.index}: {err}") from None
        print(f"zone {zone.index}: fitting rails {' '.join(rails)}", file=sys.stderr, flush=True)
        zone_fits.append(fit_zone(params, xs, targets, fit_options, progress=_progress))
        rails_used[f"zone{zone.index}"] = list(rails)
    record = provenance(
        {"layers": args.layers, "route": args.route},
        turnout=turnout,
        argv=getattr(args, "argv", None),
    )
    info = {
        "turnout": turnout.name,
        "turnout_file": record["inputs"]["turnout"]["name"],
        "turnout_sha256": file_sha256(turnout.source),
        "turnout_model_sha256": turnout_model_sha256(turnout),
        "route": args.route,
        "fe_reference": reference_description(args.lateral_fe),
        "lateral_fe": args.lateral_fe,
        "f_min_hz": args.fmin,
        "f_max_hz": args.fmax,
        "n_frequencies": args.n,
        "positions": "given" if args.positions else f"every {args.every} sleeper(s)",
        "rails_option": " ".join(args.rails) if args.rails else "all active",
        "package_version": record.get("package_version", ""),
        "command_line": record.get("command_line", ""),
        "date_utc": record.get("date_utc", ""),
        "fe_options": {k: v for k, v in vars(options).items()},
        "rails": rails_used,
    }
    fitted = fitted_set(zone_fits, args.layers, info, fit_options)
    write_output(args.out, lambda tmp: write_fitted(tmp, fitted))
    for zf in zone_fits:
        print(_zone_line(zf))
    print(f"wrote {args.out}: use --source fitted --parameters {args.out}")
    return 0


def _progress(message: str) -> None:
    print(message, file=sys.stderr, flush=True)


def _zone_line(zf: Any) -> str:
    """One summary line per zone: worst range band RMS derived -> fitted, static ratios."""
    ranges = ((1.0, 125.0), (125.0, 500.0), (500.0, 2000.0))
    worst = {True: 0.0, False: 0.0}
    statics = []
    for p in zf.positions:
        for r in p.residuals:
            for fitted in (True, False):
                values = [r.range_rms(lo, hi, fitted) for lo, hi in ranges]
                finite = [v for v in values if math.isfinite(v)]
                worst[fitted] = max([worst[fitted]] + finite)
            statics.append(r.static_ratio_fitted)
    return (
        f"zone {zf.zone}: {len(zf.positions)} position(s); worst range band RMS vs FE "
        f"(excl. pinned-pinned) derived {worst[False]:.1f} dB -> fitted {worst[True]:.1f} dB; "
        f"static stiffness / FE {min(statics):.3f}-{max(statics):.3f}"
    )
