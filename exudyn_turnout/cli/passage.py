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
    turnout_from_args,
)
from exudyn_turnout.passage.check_rail_steps import refined_line
from exudyn_turnout.passage.events import event_line
from exudyn_turnout.passage.run import DEFAULT_VEHICLE, simulate_passage
from exudyn_turnout.passage.settings import TRACKS

__all__ = [
    "build",
    "run_passage_command",
    "start_out_dir",
    "safety_text",
    "RUNNING_MARKER",
    "add_passage_options",
    "route_from_args",
    "settings_from_args",
    "track_list",
    "StatusLine",
    "COMPARISON_FILE",
]

#: File of a run on several tracks (``--track 2-layer,3-layer``): peaks per track and the
#: differences in %, beside the overlaid ``forces.png``.
COMPARISON_FILE = "comparison.json"


def track_list(text: str) -> tuple[str, ...]:
    """argparse type of ``--track``: one track, or several separated by commas.

    Parameters
    ----------
    text : str
        E.g. ``"3-layer"`` or ``"2-layer,3-layer,fe"``.

    Returns
    -------
    tuple of str
        The tracks, in the given order.
    """
    names = tuple(name.strip() for name in text.split(","))
    for name in names:
        if name not in TRACKS:
            raise argparse.ArgumentTypeError(
                f"unknown track {name!r} in {text!r} (tracks: {', '.join(TRACKS)}; several "
                "separated by commas)"
            )
    if len(set(names)) != len(names):
        raise argparse.ArgumentTypeError(f"a track is named twice in {text!r}")
    return names


class StatusLine:
    """What a passage command is doing, on stderr: stages, then the run with an ETA.

    On a terminal one line is rewritten (carriage return) and removed when the command's
    own output or an error follows. Elsewhere (a log file, a pipe) plain lines are printed:
    the set-up when it has ended (with its time, so that bad input or a failed set-up is
    still the one line of the error), the run at 0, 25, 50, 75 and 100 %, and the end.
    ``quiet`` prints nothing.

    Parameters
    ----------
    stream : text stream
        Usually ``sys.stderr``.
    quiet : bool
        ``--quiet``.
    """

    def __init__(self, stream, quiet: bool = False) -> None:
        self.stream = stream
        self.quiet = quiet
        self.tty = bool(getattr(stream, "isatty", lambda: False)())
        self._open = False  # a terminal line waiting for its end
        self._next = 0.0  # the next fraction a plain line is printed at
        self._label: str | None = None  # the run under way
        self._start = 0.0  # s, its perf_counter at start
        self._setup: str | None = None  # a set-up stage, printed in a log when it has ended

    def _line(self, text: str, final: bool = True) -> None:
        if self.quiet:
            return
        if self.tty:
            self.stream.write(f"\r\x1b[K{text}" + ("\n" if final else ""))
            self._open = not final
        else:
            self.stream.write(text + "\n")
        self.stream.flush()

    def stage(self, text: str) -> None:
        """Say what is being done now (one line).

        Parameters
        ----------
        text : str
        """
        self._line(text, final=not self.tty)

    def notice(self, text: str) -> None:
        """Say at once what a long set-up step does (a plain line, also on a terminal).

        Parameters
        ----------
        text : str
        """
        self._line(text, final=True)

    def setup(self, label: str, text: str) -> None:
        """Say what a run's set-up does (:meth:`run` follows).

        On a terminal at once ("preparing the <label>: <text>"); in a log when the run's
        first progress arrives, with the time it took ("<label>: set up in 2.1 s (<text>)").

        Parameters
        ----------
        label : str
            What runs, e.g. "3-layer track".
        text : str
            What the set-up does.
        """
        if self.tty:
            self._line(f"preparing the {label}: {text}", final=False)
        else:
            self._setup = text

    def run(self, label: str):
        """A progress callback for a passage, ``callback(fraction, x)``.

        Parameters
        ----------
        label : str
            What runs, e.g. "3-layer track".

        Returns
        -------
        callable(fraction, x)
        """
        import time

        start: list[tuple[float, float]] = []  # s and fraction of the first report
        self._next = 0.0
        self._label, self._start = label, time.perf_counter()

        def show(fraction: float, x: float) -> None:
            now = time.perf_counter()
            if not start:
                start.append((now, fraction))
                if self._setup is not None:
                    self._line(f"{label}: set up in {now - self._start:.1f} s ({self._setup})")
                    self._setup = None
            t0, f0 = start[0]
            eta = ""
            if fraction > f0 + 0.02 and fraction < 1.0:
                left = (now - t0) * (1.0 - fraction) / (fraction - f0)
                eta = f", about {left:.1f} s left" if left < 10 else f", about {left:.0f} s left"
            if self.tty:
                n = int(30 * fraction)
                bar = f"[{'#' * n}{'.' * (30 - n)}]"
                text = f"{label}: {bar} {100 * fraction:5.1f} %  x = {x:7.2f} m{eta}"
                self._line(text, final=False)
            elif fraction >= self._next - 1e-9:
                self._line(f"{label}: {100 * fraction:3.0f} %, x = {x:.2f} m{eta}")
                self._next = 0.25 * (int(fraction / 0.25 + 1e-9) + 1)

        return show

    def end(self) -> None:
        """The run has ended: its wall time (a plain line; on a terminal, the line's end)."""
        import time

        if self.quiet or self._label is None:
            return
        self._line(f"{self._label}: set up and ran in {time.perf_counter() - self._start:.1f} s")
        self._label = None

    def clear(self) -> None:
        """Remove a terminal line left open and forget a set-up not yet printed (the
        command's own output, or an error, follows)."""
        self._setup, self._label = None, None
        if self._open and not self.quiet:
            self.stream.write("\r\x1b[K")
            self.stream.flush()
            self._open = False


def settings_from_args(args: argparse.Namespace, **track_options):
    """The scenario of ``--route``, ``--speed``, ``--x-start/--x-end`` and the steps.

    Shared by ``simulate``, ``fe simulate`` and ``draw passage``; options a command does not
    have (``--time-step``, ``--output-step``) keep the defaults.

    Parameters
    ----------
    args : argparse.Namespace
        Parsed options; ``args.route`` already checked (:func:`route_from_args`).
    **track_options
        Further :class:`~exudyn_turnout.passage.settings.PassageSettings` fields (``layers``,
        ``source``).

    Returns
    -------
    PassageSettings
    """
    from exudyn_turnout.passage.settings import DEFAULT_SETTINGS, PassageSettings

    for name in ("contact", "irregularity", "solver", "creep_reduction", "normal_stiffness_factor"):
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
        # a step given is the user's everywhere: no finer check-rail windows (it warns)
        check_rail_time_step=(
            DEFAULT_SETTINGS.check_rail_time_step
            if getattr(args, "time_step", None) is None
            else None
        ),
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

    tracks = args.track or (None,)  # None: --layers names the co-running track
    base = settings_from_args(args, layers=args.layers, source=args.source)
    runs = []
    for name in tracks:
        track, settings = track_of(base, name)  # the track is the one source of truth
        if track == "fe" and (
            settings.contact != "profile" or getattr(args, "parameters", None) is not None
        ):
            raise UsageError(
                "--track fe: the FE track takes Table 1 directly (no --parameters) and runs "
                "with the profile contact (the height-table contact is the single wheelset's "
                "co-running baseline)"
            )
        runs.append((track, settings))
    if model is not None and base.contact != "profile":
        raise UsageError(
            "--contact height-table: the full vehicle has the profile contact only (the "
            "height-table contact is the single wheelset's: add --vehicle wheelset)"
        )
    _check_runs(runs, turnout, vehicle, model)
    if base.contact == "profile":  # the rail geometry, checked before anything runs
        from exudyn_turnout.wheel_rail.turnout_design import rail_geometry
        from exudyn_turnout.wheel_rail.turnout_sections import route_segments

        rail_geometry(turnout)
        route_segments(turnout, args.route)
    # what a first run builds, the creep table started beside the contact tables
    notice = _start_cold_builds(args.route) if base.contact == "profile" else None

    def simulate_on(track: str, settings):
        def simulate(bar):
            if model is None:
                return simulate_passage(
                    turnout, settings, vehicle=vehicle, progress=bar, track=track
                )
            return simulate_passage(turnout, settings, model, progress=bar, track=track)

        return simulate

    title = f"{turnout.name}, {args.route} route, {args.speed:g} km/h" + (
        "" if model is None else f", {model.name} (front wheelset)"
    )

    def what(track: str) -> str:
        return ("FE track, " if track == "fe" else "") + (
            "" if model is None else "full vehicle, front wheelset: "
        )

    def extra(track: str) -> dict:
        return {
            "model": "FE" if track == "fe" else "co-running",
            "profiles": args.profiles,
            "parameters": file_record(getattr(args, "parameters", None)),
        }

    vehicle_record = vehicle if model is None else _vehicle_file(args.vehicle)
    if len(runs) == 1:
        track, settings = runs[0]
        return run_passage_command(
            args,
            simulate_on(track, settings),
            title,
            what(track),
            turnout=turnout,
            vehicle=vehicle_record,
            extra_settings=extra(track),
            label=f"{track} track",
            notice=notice,
        )
    out = start_out_dir(args.out)
    try:
        results: dict = {}
        for track, settings in runs:
            results[track] = _run_and_write(
                args,
                out / track,
                simulate_on(track, settings),
                title,
                what(track),
                turnout,
                vehicle_record,
                extra(track),
                label=f"{track} track ({len(results) + 1} of {len(runs)})",
                forces=False,
                notice=None if results else notice,
            )
        _write_comparison(args, out, results, title)
    except (UsageError, RunFailure):
        _end_running(out)
        raise
    _end_running(out)
    return 0


def _check_runs(runs, turnout, vehicle, model) -> None:
    """Check every run's settings before anything is printed (bad input: one line, exit 2)."""
    from exudyn_turnout.inputs.vehicle import load_vehicle
    from exudyn_turnout.passage.common import check_settings, check_vehicle_settings
    from exudyn_turnout.passage.settings import PassageError

    try:
        for _, settings in runs:
            if model is None:
                check_settings(settings, turnout, vehicle)
            else:
                check_vehicle_settings(settings, turnout, model, load_vehicle())
    except PassageError as err:
        raise UsageError(str(err)) from None


def _write_comparison(args: argparse.Namespace, out: Path, results: dict, title: str) -> None:
    """The overlaid forces.png and comparison.json of a run on several tracks; the table."""
    from exudyn_turnout.cli.main import write_output
    from exudyn_turnout.passage.comparison import PassageComparison
    from exudyn_turnout.provenance import round_floats, write_json

    comparison = PassageComparison(results)
    record = dict(comparison.record(), route=args.route, speed_kmh=args.speed)
    record["files"] = {track: f"{track}/summary.json" for track in results}
    try:
        write_json(out / COMPARISON_FILE, round_floats(record))
    except OSError as err:
        raise UsageError(f"--out {args.out}: cannot write: {err.strerror or err}") from None
    written = [str(out / COMPARISON_FILE)]
    if not args.no_plot:
        from exudyn_turnout.plotting.curves import save_figure

        fig, _ = comparison.plot(title=title)
        write_output(str(out / "forces.png"), lambda tmp: save_figure(fig, tmp, dpi=120))
        written.append(str(out / "forces.png"))
    print(comparison.table())
    print(f"wrote {', '.join(written)}")


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
    """Remove the files an earlier run left in ``out`` (so a failure leaves nothing stale).

    Also the files of an earlier run on several tracks: ``comparison.json`` and the files in
    each track's folder (``out/3-layer/summary.json``...).
    """
    from exudyn_turnout.passage.output_files import OUTPUT_FILES

    if not out.is_dir():
        return
    names = list(OUTPUT_FILES) + [COMPARISON_FILE]  # a run on several tracks: one folder each
    names += [f"{track}/{name}" for track in TRACKS for name in OUTPUT_FILES]
    for name in names:
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
    label: str = "passage",
    notice: str | None = None,
) -> int:
    """Run a passage with a progress line; write its files and print one summary line.

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
    label : str
        What runs, in the progress line (e.g. "3-layer track").
    notice : str, optional
        A line printed before the set-up (what a first run builds).

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
        _run_and_write(
            args,
            out,
            simulate,
            title,
            what,
            turnout,
            vehicle,
            extra_settings,
            label=label,
            notice=notice,
        )
    except (UsageError, RunFailure):
        _end_running(out)
        raise
    _end_running(out)
    return 0


def _run_and_write(
    args,
    out,
    simulate,
    title,
    what,
    turnout,
    vehicle,
    extra_settings,
    label: str = "passage",
    forces: bool = True,
    notice: str | None = None,
):
    """Run one passage and write its files into ``out``; print its lines; the result.

    ``forces``: draw forces.png (a run on several tracks draws one overlaid figure instead);
    ``notice``: a line printed before the set-up (what a first run builds).
    """
    from exudyn_turnout.passage.results import write_passage
    from exudyn_turnout.passage.settings import PassageError, PassageFailure, settings_record
    from exudyn_turnout.provenance import provenance

    status = StatusLine(sys.stderr, quiet=getattr(args, "quiet", False))
    if notice:
        status.notice(notice)
    status.setup(
        label,
        f"contact tables of the {args.route} route (built on the first run only, cached in "
        f"{_cache_place()}), the Exudyn model, the static state",
    )
    try:
        result = simulate(status.run(label))
    except PassageFailure as err:
        status.clear()
        raise RunFailure(str(err)) from None
    except PassageError as err:
        status.clear()
        raise UsageError(str(err)) from None
    except BaseException:
        status.clear()
        raise
    status.end()
    status.stage(f"writing {out}")
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
        vehicle = "az_car_centre_mps2" in result.columns  # a full vehicle: wheelsets, bodies

        def forces_figures(directory: Path) -> None:
            from exudyn_turnout.plotting.curves import plot_passage_forces, save_figure

            if forces:
                fig, _ = plot_passage_forces([result], wheel="right", title=title)
                save_figure(fig, str(directory / "forces.png"), dpi=120)
            if len(result.contact_points("right")["x"]):  # profile contact
                result.plot_contact_band(
                    directory / "contact_band.png", "right", title=f"{title}, right wheel"
                )
            if vehicle:
                fig = result.plot_wheelsets(title=title)[0]
                save_figure(fig, str(directory / "wheelsets.png"), dpi=100)

        def safety_figures(directory: Path) -> None:
            from exudyn_turnout.plotting.curves import save_figure
            from exudyn_turnout.plotting.safety import plot_passage_safety

            fig, _ = plot_passage_safety(result, title=title)
            save_figure(fig, str(directory / "safety.png"), dpi=110)
            if vehicle:
                save_figure(
                    result.plot_bodies(title=title)[0], str(directory / "bodies.png"), dpi=100
                )

        # two groups of about equal cost, drawn beside the time series (write_passage)
        figure = [forces_figures, safety_figures]

    try:
        dtype = "float32" if getattr(args, "float32", False) else "float64"
        paths = write_passage(
            result, out, fmt=args.format, provenance=record, figure=figure, dtype=dtype
        )
    except OSError as err:
        raise UsageError(f"--out {args.out}: cannot write: {err.strerror or err}") from None
    status.clear()
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
    refined = refined_line(summary)
    if refined is not None:
        print(refined)
    print(safety_text(summary))
    return result


def _start_cold_builds(route: str) -> str | None:
    """Start the creep table's build in a background thread if it is not cached; say what a
    first run builds.

    The contact tables are named when the cache holds none at all (a first run: their keys
    need the rail sections, which are only made when the route's contact is set up).

    Parameters
    ----------
    route : str
        The route, named in the line.

    Returns
    -------
    str or None
        The line, or None if nothing is known to be built.
    """
    from exudyn_turnout.wheel_rail.creep_table import start_creep_table
    from exudyn_turnout.wheel_rail.tables import default_cache_dir

    parts = []
    if not any(default_cache_dir().glob("contact_table_*.npz")):
        parts.append(f"the contact tables of the {route} route")
    if start_creep_table():  # the kernel's creep law, the default settings
        parts.append("the creep table (FASTSIM, in a second thread)")
    if not parts:
        return None
    return f"building {' and '.join(parts)}: first run only, cached in {_cache_place()}"


def _cache_place() -> str:
    """The contact-table cache directory, ``~`` for the home directory."""
    from exudyn_turnout.wheel_rail.tables import default_cache_dir

    place = str(default_cache_dir())
    home = str(Path.home())
    return "~" + place[len(home) :] if home != "/" and place.startswith(home) else place


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


def add_passage_options(p: argparse.ArgumentParser, full_vehicle: bool = False) -> None:
    """Options shared by ``simulate`` and ``fe simulate``: vehicle, x range, steps, output.

    Parameters
    ----------
    p : argparse.ArgumentParser
        The command's parser; the options are added to it.
    full_vehicle : bool
        The command runs full vehicles, and without ``--vehicle`` the full Manchester
        vehicle (``simulate``); else the single wheelset (``fe simulate``).
    """
    if full_vehicle:
        p.add_argument(
            "--vehicle",
            metavar="NAME|FILE",
            default=DEFAULT_VEHICLE,
            help=f"vehicle: {DEFAULT_VEHICLE} (default: the full Manchester benchmark vehicle, "
            "car body on two bogies, four wheelsets each on its own track; figures and the "
            "plain columns show its front wheelset, as the paper's Figs 7, 8, and "
            "wheelsets.png every wheelset), wheelset (the packaged Manchester benchmark "
            "wheelset with its sprung share, about half the cost; also the "
            "height-table contact), or a vehicle file of either kind",
        )
    else:
        p.add_argument(
            "--vehicle",
            metavar="NAME|FILE",
            help="vehicle: wheelset (default: the packaged Manchester benchmark wheelset with "
            "its sprung share) or a single-wheelset vehicle file (the full vehicle on the FE "
            "track: simulate --track fe)",
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
    p.add_argument(
        "--no-plot", action="store_true", help="skip the figures (forces, safety, contact band)"
    )
    p.add_argument(
        "--quiet",
        action="store_true",
        help="no progress on stderr (what is being done, the run with an ETA); warnings stay",
    )


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
        description="Run the vehicle (default the full Manchester benchmark vehicle, its "
        "front wheelset in the figures; --vehicle wheelset the single wheelset with its "
        "sprung share) through the turnout on a 2- or 3-layer co-running track, or on the "
        "FE track (--track fe), with penalty wheel/rail contact; write timeseries.csv, "
        "summary.json, forces.png, safety.png, (full vehicle) wheelsets.png and bodies.png, "
        "and (profile contact) contact_band.png into --out.",
    )
    add_turnout_options(parser)
    parser.add_argument("--layers", type=int, choices=(2, 3), default=3)
    parser.add_argument(
        "--track",
        type=track_list,
        metavar="2-layer|3-layer|fe[,...]",
        help="track model: a co-running track (same as --layers) or fe, the FE turnout "
        "(vertical and lateral planes, rail torsion) under the same vehicle and contact "
        "(default: --layers). Several separated by commas (e.g. 2-layer,3-layer) run one "
        "after the other: each track's files in its own folder of --out, the overlaid "
        "forces.png (the paper's Figs 7, 8) and comparison.json (peaks, differences in %%) "
        "in --out",
    )
    parser.add_argument(
        "--route",
        metavar="NAME",
        help="route of the turnout file (default: through, or the file's first route)",
    )
    parser.add_argument(
        "--time-step",
        type=number,
        default=None,
        metavar="S",
        help="s (default 1e-4, and where a check rail carries load 2.5e-5 on the co-running "
        "track: the run says where; given, it is used everywhere and a loaded check rail at "
        "a coarser step than 2.5e-5 warns; its convergence: the validation report, section "
        "5, validation/vehicle_step_convergence.md)",
    )
    parser.add_argument(
        "--solver",
        choices=("exudyn", "compiled"),
        default="compiled",
        help="time integration of the full vehicle on a co-running track: compiled (default: "
        "Exudyn's generalized-alpha scheme and Newton method in one compiled loop, equal to "
        "exudyn's within the Newton tolerance, about 0.6 x its CPU time; a segment it does "
        "not model steps in Exudyn, the summary's 'stepping' says why) or exudyn (Exudyn's "
        "own integrator); the single wheelset and the FE track always step in Exudyn",
    )
    parser.add_argument(
        "--contact",
        choices=("profile", "height-table"),
        default="profile",
        help="wheel/rail contact: profile (S1002 on the turnout's rail sections, multi-point "
        "Hertz or Kik-Piotrowski, FASTSIM creep with spin; default) or height-table (rail "
        "height tables on a conical tread with flange springs: a simplification kept for "
        "comparison)",
    )
    parser.add_argument(
        "--creep-reduction",
        type=number,
        default=None,
        metavar="F",
        help="creep force reduction factor: Kalker's coefficients of every contact times F "
        "(initial slopes scale, saturation at mu N does not; default 1: none)",
    )
    parser.add_argument(
        "--normal-stiffness-factor",
        type=number,
        default=None,
        metavar="F",
        help="the normal contact law's force at a given penetration times F (a sensitivity "
        "knob: validation/contact_law_sensitivity.md; default 1)",
    )
    parser.add_argument(
        "--irregularity",
        metavar="SPEC",
        help="track irregularity on the rails: a CSV file, psd:LEVEL,seed=N[,band=A-B], "
        "dip:x=X,depth=D,length=L or joint:x=X,angle=TWO_ALPHA,length=L, several joined by "
        "';' (see the README); default none",
    )
    add_passage_options(parser, full_vehicle=True)
    parser.set_defaults(run=_run)
