"""``exudyn-turnout simulate``: a wheelset passage through the turnout (paper Section 4)."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from exudyn_turnout.cli.main import (
    RunFailure,
    UsageError,
    add_turnout_options,
    check_out_dir,
    kilonewtons,
    number,
    progress_bar,
    turnout_from_args,
)
from exudyn_turnout.passage.events import event_line
from exudyn_turnout.passage.run import simulate_passage

__all__ = [
    "build",
    "run_passage_command",
    "start_out_dir",
    "safety_text",
    "RUNNING_MARKER",
    "add_passage_options",
    "route_from_args",
    "settings_from_args",
]


def settings_from_args(args: argparse.Namespace, **track_options):
    """The scenario of ``--route``, ``--speed``, ``--x-start/--x-end`` and the steps.

    Shared by ``simulate``, ``fe simulate`` and ``draw passage``; options a command does not
    have (``--time-step``, ``--output-step``) keep the defaults.

    Parameters
    ----------
    args : argparse.Namespace
        Parsed options; ``args.route`` already checked (:func:`route_from_args`).
    **track_options
        Further :class:`~exudyn_turnout.passage.results.PassageSettings` fields (``layers``,
        ``source``).

    Returns
    -------
    PassageSettings
    """
    from exudyn_turnout.passage.results import DEFAULT_SETTINGS, PassageSettings

    for name in ("contact", "irregularity"):
        if getattr(args, name, None) is not None and name not in track_options:
            track_options[name] = getattr(args, name)
    if isinstance(track_options.get("irregularity"), str):
        from exudyn_turnout.inputs.irregularity import irregularity_from_spec

        try:
            track_options["irregularity"] = irregularity_from_spec(track_options["irregularity"])
        except (ValueError, OSError) as err:
            raise UsageError(f"--irregularity: {err}") from None
    return PassageSettings(
        route=args.route,
        speed_kmh=args.speed,
        x_start=args.x_start,
        x_end=args.x_end,
        time_step=(
            DEFAULT_SETTINGS.time_step
            if getattr(args, "time_step", None) is None
            else args.time_step
        ),
        output_step=getattr(args, "output_step", None),
        **track_options,
    )


def _run(args: argparse.Namespace) -> int:
    out = start_out_dir(args.out)  # first: an earlier run's files never outlive a killed start
    try:
        return _simulate_command(args)
    except (UsageError, RunFailure):
        _end_running(out)
        raise


def _simulate_command(args: argparse.Namespace) -> int:
    from exudyn_turnout.inputs.vehicle import load_vehicle
    from exudyn_turnout.provenance import file_record

    turnout = turnout_from_args(args)
    model = _full_vehicle(args.vehicle)
    vehicle = load_vehicle(args.vehicle) if model is None else None
    args.route = route_from_args(args, turnout)
    from exudyn_turnout.passage.run import track_of

    settings = settings_from_args(args, layers=args.layers, source=args.source)
    track, settings = track_of(settings, args.track)  # the track is the one source of truth
    if track == "fe" and (
        settings.contact != "profile" or getattr(args, "parameters", None) is not None
    ):
        raise UsageError(
            "--track fe: the FE track takes Table 1 directly (no --parameters) and runs with "
            "the profile contact (the height-table contact is the single wheelset's "
            "co-running baseline)"
        )
    if model is not None and settings.contact != "profile":
        raise UsageError("--contact height-table: the full vehicle has the profile contact only")
    if settings.contact == "profile":  # the rail geometry, checked before anything runs
        from exudyn_turnout.wheel_rail.turnout_design import rail_geometry
        from exudyn_turnout.wheel_rail.turnout_sections import route_segments

        rail_geometry(turnout)
        route_segments(turnout, args.route)

    def simulate(bar):
        if model is None:
            return simulate_passage(turnout, settings, vehicle=vehicle, progress=bar, track=track)

        return simulate_passage(turnout, settings, model, progress=bar, track=track)

    return run_passage_command(
        args,
        simulate,
        f"{turnout.name}, {args.route} route, {args.speed:g} km/h"
        + ("" if model is None else f", {model.name} (front wheelset)"),
        ("FE track, " if track == "fe" else "")
        + ("" if model is None else "full vehicle, front wheelset: "),
        turnout=turnout,
        vehicle=vehicle if model is None else _vehicle_file(args.vehicle),
        extra_settings={
            "model": "FE" if track == "fe" else "co-running",
            "profiles": args.profiles,
            "parameters": file_record(getattr(args, "parameters", None)),
        },
    )


def _vehicle_file(name_or_path: str) -> str:
    """The file of ``--vehicle``: a packaged vehicle's file for its name, else the path."""
    from exudyn_turnout.inputs.vehicle_names import PACKAGED_VEHICLES, packaged_vehicle_path

    if name_or_path in PACKAGED_VEHICLES:
        return str(packaged_vehicle_path(name_or_path))
    return name_or_path


def _full_vehicle(path: str | None):
    """The full vehicle model of a vehicle file with a car body, or None (single wheelset).

    Parameters
    ----------
    path : str or None
        ``--vehicle``: a file or a packaged name (None: the packaged single wheelset).

    Returns
    -------
    VehicleModel or None
    """
    if path is None:
        return None
    from exudyn_turnout.inputs.vehicle_names import (
        FULL_VEHICLE,
        PACKAGED_VEHICLES,
        packaged_vehicle_kind,
        packaged_vehicle_path,
    )

    if path in PACKAGED_VEHICLES:  # a packaged vehicle by name: its kind is known
        if packaged_vehicle_kind(path) != FULL_VEHICLE:
            return None  # load_vehicle reads it by name
        path = str(packaged_vehicle_path(path))
    import tomllib

    try:
        data = tomllib.loads(Path(path).read_text(encoding="utf-8"))
    except (OSError, ValueError):  # unreadable, not UTF-8, not TOML
        return None  # load_vehicle says what is wrong with it
    if "car_body" not in data:
        return None
    from exudyn_turnout.inputs.vehicle_model import VehicleModelError, load_vehicle_model

    try:
        return load_vehicle_model(path)
    except VehicleModelError as err:
        raise UsageError(f"--vehicle: {err}") from None


def route_from_args(args: argparse.Namespace, turnout) -> str:
    """``--route``, checked against the file's routes; default through (or the first route).

    Parameters
    ----------
    args : argparse.Namespace
        Parsed options; ``route`` (None: not given) is used.
    turnout : Turnout
        The turnout whose ``[routes.<name>]`` sections are the choices.

    Returns
    -------
    str
        The route name.
    """
    from exudyn_turnout.inputs.routes import route_names

    names = route_names(turnout)
    if args.route is None:
        if not names:
            raise UsageError(
                f"{Path(turnout.source).name}: has no [routes.<name>] section to run on"
            )
        return _checked_route(turnout, "through" if "through" in names else names[0])
    if args.route not in names:
        raise UsageError(
            f"--route {args.route}: {Path(turnout.source).name} has no such route "
            f"(routes: {', '.join(names) or 'none'})"
        )
    return _checked_route(turnout, args.route)


def _checked_route(turnout, name: str) -> str:
    """Load the route once (its plan positions resolved): a bad route is exit 2 here."""
    from exudyn_turnout.inputs.routes import load_route

    try:
        load_route(turnout, name)
    except ValueError as err:  # TurnoutFileError, or a plan position that cannot be resolved
        message = str(err)
        filename = Path(turnout.source).name
        if not message.startswith(filename):
            message = f"{filename}: routes.{name}: {message}"
        raise UsageError(message) from None
    return name


#: File a passage command writes into an existing ``--out`` before anything else and removes
#: when the run has ended (written, or failed with exit 2 or 3): left behind, it says that
#: the run was killed, and that the directory holds no finished result.
RUNNING_MARKER = "RUNNING"


def start_out_dir(path: str) -> Path:
    """Check ``--out``, remove an earlier run's files and mark the directory as running.

    Called first thing by a passage command, before any file is read, so that a run killed
    in its first seconds leaves no finished-looking earlier ``summary.json``: the earlier
    files are gone and :data:`RUNNING_MARKER` says that a run was started and did not end.
    A directory that does not exist is not created here (a bad input leaves nothing).

    Parameters
    ----------
    path : str
        ``--out``.

    Returns
    -------
    Path
        The directory.

    Raises
    ------
    UsageError
        ``--out`` is a file or not writable, or an earlier file cannot be removed.
    """
    import os
    import time

    out = check_out_dir(path)
    _clear_outputs(out)
    if out.is_dir():
        try:
            (out / RUNNING_MARKER).write_text(
                f"exudyn-turnout run started {time.strftime('%Y-%m-%d %H:%M:%S')} (pid "
                f"{os.getpid()}); this file is removed when the run ends. If it is here, the "
                "run was killed and this directory holds no finished result.\n",
                encoding="utf-8",
            )
        except OSError as err:
            raise UsageError(f"--out {path}: cannot write: {err.strerror or err}") from None
    return out


def _end_running(out: Path) -> None:
    """Remove the running marker (the run ended: written, or failed with a message)."""
    try:
        (out / RUNNING_MARKER).unlink(missing_ok=True)
    except OSError:
        pass


def _clear_outputs(out: Path) -> None:
    """Remove the files an earlier run left in ``out`` (so a failure leaves nothing stale)."""
    from exudyn_turnout.passage.results import OUTPUT_FILES

    if not out.is_dir():
        return
    for name in OUTPUT_FILES:
        try:
            (out / name).unlink(missing_ok=True)
        except OSError as err:
            raise UsageError(f"--out {out}: cannot replace {name}: {err.strerror or err}") from None


def _peak_text(summary: dict, where: str) -> str:
    """ "140.2 kN at the crossing (left wheel on r2, x = 45.79 m)" from the summary's max_* keys."""
    value = summary.get(f"max_Fz_{where}_N", summary.get(f"peak_Fz_{where}_N"))
    value = float("nan") if value is None else value
    text = f"{kilonewtons(value)} at the {where}"
    wheel, rail, x = (summary.get(f"max_Fz_{where}_{key}") for key in ("wheel", "rail", "x_m"))
    if wheel and rail and x is not None:
        text += f" ({wheel} wheel on {rail}, x = {x:.2f} m)"
    return text


def run_passage_command(
    args: argparse.Namespace,
    simulate,
    title: str,
    what: str = "",
    *,
    turnout=None,
    vehicle=None,
    extra_settings: dict | None = None,
) -> int:
    """Run a passage with a progress bar; write its files and print one summary line.

    Shared by ``simulate`` and ``fe simulate``. Before the run the files of an earlier run
    are removed from ``--out`` and :data:`RUNNING_MARKER` is written there (removed when the
    run ends; :func:`start_out_dir`); the new ones are written into a temporary directory and
    moved into place. Bad settings (PassageError) are exit 2, a failed, diverged or
    implausible run (PassageFailure) exit 3; neither leaves output.

    Parameters
    ----------
    args : argparse.Namespace
        ``out``, ``format``, ``no_plot`` and ``argv`` are used.
    simulate : callable(progress) -> PassageResult
        Runs the passage; ``progress`` is the progress bar's callback (or None).
    title : str
        Title of forces.png.
    what : str
        Prefix of the summary line's model description (e.g. "FE track, ").
    turnout, vehicle : Turnout, Vehicle, optional
        Recorded (file name and SHA-256) in the summary's provenance.
    extra_settings : dict, optional
        Settings recorded besides the PassageSettings (model, profiles, FE options).

    Returns
    -------
    int
        Exit code 0. A second console line lists the safety limits exceeded
        (:func:`safety_text`).
    """
    if getattr(args, "float32", False) and args.format != "npz":
        raise UsageError("--float32: only with --format npz (the CSV writes digits)")
    out = start_out_dir(args.out)
    try:
        return _run_and_write(args, out, simulate, title, what, turnout, vehicle, extra_settings)
    except (UsageError, RunFailure):
        _end_running(out)
        raise


def _run_and_write(args, out, simulate, title, what, turnout, vehicle, extra_settings) -> int:
    """The body of :func:`run_passage_command` after ``--out`` was prepared."""
    from exudyn_turnout.passage.results import (
        PassageError,
        PassageFailure,
        settings_record,
        write_passage,
    )
    from exudyn_turnout.provenance import provenance

    bar = progress_bar(sys.stderr)
    try:
        result = simulate(bar)
    except PassageFailure as err:
        raise RunFailure(str(err)) from None
    except PassageError as err:
        raise UsageError(str(err)) from None
    finally:
        if bar:
            sys.stderr.write("\n")
    settings = dict(
        extra_settings or {},
        **settings_record(result.settings),
        format=args.format,
        plot=not args.no_plot,
    )
    if settings.get("model") == "FE":  # no layers, parameter source or track mechanism there
        not_fe = ("layers", "source", "track_mechanism")
        settings = {k: v for k, v in settings.items() if k not in not_fe}
    argv = getattr(args, "argv", None)
    record = provenance(settings, turnout=turnout, vehicle=vehicle, argv=argv)
    figure = None
    if not args.no_plot:

        def figure(directory: Path) -> None:
            from exudyn_turnout.plotting.curves import plot_passage_forces, save_figure
            from exudyn_turnout.plotting.safety import plot_passage_safety

            fig, _ = plot_passage_forces([result], wheel="right", title=title)
            save_figure(fig, str(directory / "forces.png"), dpi=120)
            fig, _ = plot_passage_safety(result, title=title)
            save_figure(fig, str(directory / "safety.png"), dpi=110)
            if "az_car_centre_mps2" in result.columns:  # a full vehicle: wheelsets, bodies
                for name, draw in (
                    ("wheelsets", result.plot_wheelsets),
                    ("bodies", result.plot_bodies),
                ):
                    save_figure(draw(title=title)[0], str(directory / f"{name}.png"), dpi=100)
            if len(result.contact_points("right")["x"]):  # profile contact
                result.plot_contact_band(
                    directory / "contact_band.png", "right", title=f"{title}, right wheel"
                )

    try:
        dtype = "float32" if getattr(args, "float32", False) else "float64"
        paths = write_passage(
            result, out, fmt=args.format, provenance=record, figure=figure, dtype=dtype
        )
    except OSError as err:
        raise UsageError(f"--out {args.out}: cannot write: {err.strerror or err}") from None
    summary = result.summary
    if "n_dof" in summary:
        what = f"{what.rstrip(', ')} ({summary['n_dof']} DOFs), "
    print(
        f"wrote {paths['timeseries']}, {paths['summary']}: "
        f"{what}peak Fz {_peak_text(summary, 'switch')}, "
        f"{_peak_text(summary, 'crossing')}; "
        f"static {kilonewtons(summary['static_wheel_load_N'])} right, "
        f"{kilonewtons(summary['static_wheel_load_left_N'])} left; "
        f"{summary['simulated_time_s']:.2f} s simulated "
        f"in {summary['wall_time_s']:.1f} s"
    )
    event = event_line(summary)
    if event is not None:
        print(event)
    print(safety_text(summary))
    _end_running(out)
    return 0


def safety_text(summary: dict, most: int = 6) -> str:
    """The console line of the safety limits exceeded (``summary["safety_exceeded"]``).

    Parameters
    ----------
    summary : dict
        A passage's summary.
    most : int
        At most this many entries are named, largest value over limit first; the rest
        counted.

    Returns
    -------
    str
        ``"safety limits: none exceeded"``, or ``"safety limits exceeded: right wheel,
        crossing, Delta Q/Q0 0.92 > 0.6 at x = 47.43 m; ..."``.
    """
    exceeded = [e for e in summary.get("safety_exceeded") or [] if isinstance(e, dict)]
    if not exceeded:
        return "safety limits: none exceeded"

    def number(value: object) -> float:
        return float(value) if isinstance(value, (int, float)) else float("nan")

    def over(e: dict) -> float:
        limit = number(e.get("limit"))
        ratio = abs(number(e.get("value"))) / limit if limit else float("nan")
        return ratio if ratio == ratio else 0.0  # NaN last

    parts = []
    for e in sorted(exceeded, key=over, reverse=True)[:most]:
        quantity, value, limit = (
            e.get("quantity", "?"),
            number(e.get("value")),
            number(e.get("limit")),
        )
        text = f"{e.get('wheel', '?')}, {e.get('region', '?')}, {quantity} "
        if str(quantity).endswith(", N"):  # a force: in kN
            text = text.replace(", N ", " ")
            text += f"{kilonewtons(value)} > {kilonewtons(limit)}"
        else:
            text += f"{value:.3g} > {limit:.3g}"
        x = e.get("x_m")
        parts.append(text + (f" at x = {x:.2f} m" if isinstance(x, (int, float)) else ""))
    rest = len(exceeded) - len(parts)
    return "safety limits exceeded: " + "; ".join(parts) + (f"; {rest} more" if rest > 0 else "")


def add_passage_options(p: argparse.ArgumentParser) -> None:
    """Options shared by ``simulate`` and ``fe simulate``: vehicle, x range, steps, output.

    Parameters
    ----------
    p : argparse.ArgumentParser
        The command's parser; the options are added to it.
    """
    p.add_argument(
        "--vehicle",
        metavar="NAME|FILE",
        help="vehicle: wheelset (default: the packaged Manchester benchmark wheelset with its "
        "sprung share), manchester (the full Manchester benchmark vehicle, car body on two "
        "bogies; simulate only, profile contact), or a vehicle file of either kind",
    )
    p.add_argument("--speed", type=number, default=100.0, metavar="KMH", help="km/h (default 100)")
    p.add_argument(
        "--x-start", type=number, metavar="M", help="start position (m), default: turnout start"
    )
    p.add_argument(
        "--x-end", type=number, metavar="M", help="end position (m), default: turnout end"
    )
    p.add_argument(
        "--output-step",
        type=number,
        metavar="S",
        help="s between stored samples (default: every time step)",
    )
    p.add_argument(
        "--format",
        choices=("csv", "npz"),
        default="csv",
        help="time series as timeseries.csv (default) or timeseries.npz (compressed)",
    )
    p.add_argument(
        "--float32",
        action="store_true",
        help="with --format npz: arrays in float32 (time and x stay float64), half the size",
    )
    p.add_argument("--out", required=True, metavar="DIR", help="output directory")
    p.add_argument("--no-plot", action="store_true", help="skip forces.png (and contact_band.png)")


def build(sub: argparse._SubParsersAction) -> None:
    """Register the command on the ``exudyn-turnout`` subcommand parsers.

    Parameters
    ----------
    sub : argparse._SubParsersAction
        The subcommand parsers of ``exudyn-turnout``; ``simulate`` is added to them.
    """
    parser = sub.add_parser(
        "simulate",
        help="vehicle passage on the co-running or the FE track",
        description="Run the vehicle (default the Manchester benchmark wheelset with its "
        "sprung share; --vehicle a full vehicle file) through the turnout on a 2- or "
        "3-layer co-running track, or on the FE track (--track fe), with penalty "
        "wheel/rail contact; write timeseries.csv, summary.json, forces.png and (profile "
        "contact) contact_band.png into --out.",
    )
    add_turnout_options(parser)
    parser.add_argument("--layers", type=int, choices=(2, 3), default=3)
    parser.add_argument(
        "--track",
        choices=("2-layer", "3-layer", "fe"),
        help="track model: a co-running track (same as --layers) or fe, the FE turnout "
        "(vertical and lateral planes, rail torsion) under the same vehicle and contact "
        "(default: --layers)",
    )
    parser.add_argument(
        "--route",
        metavar="NAME",
        help="route of the turnout file (default: through, or the file's first route)",
    )
    parser.add_argument(
        "--time-step", type=number, default=1e-4, metavar="S", help="s (default 1e-4, converged)"
    )
    parser.add_argument(
        "--contact",
        choices=("profile", "height-table"),
        default="profile",
        help="wheel/rail contact: profile (S1002 on the turnout's rail sections, multi-point "
        "Hertz, Polach creep with spin; default) or height-table (rail height tables on a "
        "conical tread with flange springs: a simplification kept for comparison)",
    )
    parser.add_argument(
        "--irregularity",
        metavar="SPEC",
        help="track irregularity on the rails: a CSV file, psd:LEVEL,seed=N[,band=A-B], "
        "dip:x=X,depth=D,length=L or joint:x=X,angle=TWO_ALPHA,length=L, several joined by "
        "';' (see the README); default none",
    )
    add_passage_options(parser)
    parser.set_defaults(run=_run)
