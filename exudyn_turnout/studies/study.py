"""A study file: a base scenario and the factors varied around it, expanded into cases.

A study is data (TOML)::

    [study]
    name = "pad stiffness"          # optional
    description = "..."             # optional
    history_step = 0.001            # s, optional: keep each case's time histories, decimated

    [base]                          # the scenario every case starts from
    turnout = "my_turnout.toml"     # optional, relative to the study file (default: packaged)
    vehicle = "my_vehicle.toml"     # optional (default: packaged wheelset); or a packaged
                                    # name: "wheelset", "manchester" (the full vehicle)
    track = "3-layer"               # "2-layer", "3-layer" or "fe"
    route = "through"
    speed_kmh = 100.0               # any field of PassageSettings
    irregularity = "dip:x=47,depth=0.002,length=1"   # optional (see inputs.irregularity)

    [factors]                       # full factorial: every combination of these lists
    speed_kmh = [50.0, 80.0, 100.0]
    "turnout.rail_types.stock.pad.k_z" = [96e6, 120e6, 144e6]

    [paired]                        # lists of one length, varied together (row by row)
    route = ["through", "diverging"]
    "turnout.regions.crossing" = [[44.29, 51.0], [44.0, 51.0]]

    [latin_hypercube]               # a Latin-hypercube sample of ranges (scipy.stats.qmc)
    samples = 8
    seed = 1
    ranges = { "vehicle.primary_suspension.k_z" = [0.8e6, 1.2e6] }

    [repetitions]                   # repetitions over the seeds of a random irregularity
    irregularity = "psd:ERRI-low,band=1-70"    # seed=N is added to each psd: part
    seeds = 20                      # seeds 1..20, or a list [3, 7, 11]

    [output]                        # optional
    keep_timeseries = true          # every case's whole time series, cases/<key>/timeseries.npz

A factor is any field of :class:`~exudyn_turnout.passage.settings.PassageSettings`,
``track``, ``turnout`` / ``vehicle`` (a file; a vehicle also by a packaged name, a file with
a car body runs the full vehicle), ``irregularity`` (a spec), or a field of the
turnout or vehicle file by dotted path (``turnout.<path>``, ``vehicle.<path>``; an integer
selects an item of an array: ``turnout.zones.0.x_end``). The cases are the product of the
full-factorial lists, the paired rows, the Latin-hypercube samples and the seeds.
"""

from __future__ import annotations

import dataclasses
import hashlib
import itertools
import json
import math
import tomllib
from collections.abc import Mapping
from dataclasses import dataclass, field
from importlib import metadata
from pathlib import Path
from typing import Any

from exudyn_turnout.inputs.irregularity import Irregularity, irregularity_from_spec
from exudyn_turnout.inputs.turnout import default_turnout_path
from exudyn_turnout.inputs.vehicle import Vehicle, default_vehicle_path, load_vehicle
from exudyn_turnout.inputs.vehicle_data import VehicleModel
from exudyn_turnout.inputs.vehicle_model import load_vehicle_model
from exudyn_turnout.inputs.vehicle_names import PACKAGED_VEHICLES, packaged_vehicle_path
from exudyn_turnout.passage.settings import TRACKS
from exudyn_turnout.studies.toml_writer import dumps, set_dotted

__all__ = [
    "StudyError",
    "Case",
    "Study",
    "load_study",
    "study_from_dict",
    "load_study_vehicle",
    "checked_turnout",
    "FILE_FACTORS",
]

#: Factors that are not PassageSettings fields nor dotted file fields.
FILE_FACTORS = ("turnout", "vehicle", "track", "irregularity", "parameters")


#: The turnouts this process loaded to check a study's cases (:meth:`Study.cases`), by file
#: name and content: the last few, for the cases' runs in this process or its forked workers.
_CHECKED_TURNOUTS: dict[tuple[str, str], Any] = {}
_CHECKED_KEPT = 16


def checked_turnout(name: str, text: str) -> Any:
    """The turnout file ``name`` with content ``text`` as :meth:`Study.cases` loaded it here.

    :meth:`Study.cases` loads each distinct turnout file with the package's loader (from a
    temporary copy named ``name``) to check it; a case's run (in this process, or in a
    worker forked from it) takes that turnout instead of loading the same text again.

    Parameters
    ----------
    name : str
        The file's name.
    text : str
        Its content.

    Returns
    -------
    Turnout or None
        None when this process has not loaded it (or no longer keeps it).
    """
    return _CHECKED_TURNOUTS.get((name, text))


def _remember_turnout(name: str, text: str, turnout: Any) -> None:
    _CHECKED_TURNOUTS.pop((name, text), None)
    _CHECKED_TURNOUTS[name, text] = turnout
    while len(_CHECKED_TURNOUTS) > _CHECKED_KEPT:
        del _CHECKED_TURNOUTS[next(iter(_CHECKED_TURNOUTS))]


class StudyError(ValueError):
    """A bad study file or factor; the message is one line naming the file and field."""


@dataclass(frozen=True, eq=False)
class Case:
    """One passage of a study: its inputs, everything needed to run it, and its key.

    Parameters
    ----------
    index : int
        0-based position in the study.
    inputs : dict
        The factor values of this case (name -> value), as in the results table.
    settings : dict
        PassageSettings fields (the irregularity apart).
    track : str or None
        ``"2-layer"``, ``"3-layer"``, ``"fe"`` or None (``settings["layers"]``).
    turnout_text, vehicle_text : str
        The content of the case's turnout and vehicle files (modified by dotted factors).
    turnout_name, vehicle_name : str
        File names.
    turnout_modified, vehicle_modified : bool
        Whether a dotted factor changed the file (then it is written to the case folder).
    parameters_text, parameters_name : str
        A fitted parameter file (``--parameters``, for ``source = "fitted"``): its content
        and name ("" for none).
    irregularity_spec : str
        The spec ("" for none).
    irregularity : Irregularity or None
        Built from the spec.
    history_step : float or None
        s, decimation of the stored time histories (None: not stored).
    turnout_dir, vehicle_dir : str
        Folders of the study's turnout and vehicle files: the design files they name
        (rail profiles, slice files, a wheel profile) are found beside them, as for the files
        themselves ("" : beside the case's own copy, i.e. packaged data only).
    key : str
        Hash of all of the above and the package version: the case's folder name.
    keep_timeseries : bool
        Store the case's whole time series (not part of the key: the same passage).
    """

    index: int
    inputs: dict[str, Any]
    settings: dict[str, Any]
    track: str | None
    turnout_text: str
    turnout_name: str
    vehicle_text: str
    vehicle_name: str
    turnout_modified: bool = False
    vehicle_modified: bool = False
    parameters_text: str = ""
    parameters_name: str = ""
    irregularity_spec: str = ""
    irregularity: Irregularity | None = None
    history_step: float | None = None  #: s
    turnout_dir: str = ""
    vehicle_dir: str = ""
    key: str = ""
    keep_timeseries: bool = False


def _local_files(data: Any, directory: str) -> list[str]:
    """Name and SHA-256 of every file a parsed turnout or vehicle file names (string values
    of ``profile``, ``file`` and ``wheel_profile`` keys) that exists in ``directory``."""
    names: list[str] = []

    def walk(node: Any) -> None:
        if isinstance(node, Mapping):
            for key, value in node.items():
                if key in ("profile", "file", "wheel_profile") and isinstance(value, str):
                    names.append(value)
                else:
                    walk(value)
        elif isinstance(node, (list, tuple)):
            for item in node:
                walk(item)

    walk(data)
    out = []
    for name in sorted(set(names)):
        path = Path(directory) / name
        if path.is_file():
            out.append(f"{name}:{hashlib.sha256(path.read_bytes()).hexdigest()}")
    return out


def load_study_vehicle(path: str | Path) -> Vehicle | VehicleModel:
    """A study's vehicle file, read by the loader of its kind.

    A file with a ``[vehicle]`` table and no ``[contact]`` table is a vehicle-model file (the
    full vehicle, car body on bogies), read by
    :func:`~exudyn_turnout.inputs.vehicle_model.load_vehicle_model`; any other file is a
    single-wheelset file, read by :func:`~exudyn_turnout.inputs.vehicle.load_vehicle` (which
    says what is wrong with a bad one).

    Parameters
    ----------
    path : str or Path
        The TOML vehicle file.

    Returns
    -------
    Vehicle or VehicleModel

    Raises
    ------
    ValueError
        The loader's one-line error (unreadable file, missing or bad field).
    """
    path = Path(path)
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError):
        data = {}  # load_vehicle says what is wrong with it
    if isinstance(data.get("vehicle"), Mapping) and "contact" not in data:
        return load_vehicle_model(path)
    return load_vehicle(path)


def _settings_fields() -> dict[str, str]:
    """PassageSettings field name -> its annotation (as text)."""
    from exudyn_turnout.passage.settings import PassageSettings

    return {f.name: str(f.type) for f in dataclasses.fields(PassageSettings)}


def _resolved(settings: Mapping[str, Any]) -> dict[str, Any]:
    """Every PassageSettings field of a case (given or default), the irregularity apart."""
    from exudyn_turnout.passage.settings import PassageSettings

    defaults = PassageSettings()
    out = {name: getattr(defaults, name) for name in _settings_fields() if name != "irregularity"}
    out.update(settings)
    return out


def _versions() -> dict[str, str]:
    from exudyn_turnout import __version__

    try:
        exudyn_version = metadata.version("exudyn")
    except metadata.PackageNotFoundError:
        exudyn_version = "not installed"
    return {"package_version": __version__, "exudyn_version": exudyn_version}


def _sha(text: str) -> str:
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


@dataclass(frozen=True, eq=False)
class Study:
    """A study read from its file (see the module docstring for the format).

    Parameters
    ----------
    name : str
        From ``[study] name`` (default: the file's stem).
    source : str
        Path of the study file ("" if made from a dict).
    base : dict
        The ``[base]`` scenario.
    factors : dict
        Full-factorial lists, in file order.
    paired : dict
        Paired lists (one length).
    lhs_ranges : dict
        Latin-hypercube ranges name -> (low, high).
    lhs_samples, lhs_seed : int
        Latin-hypercube sample count and seed.
    seeds : tuple of int
        Irregularity seeds of ``[repetitions]`` (empty: none).
    repetition_irregularity : str
        The spec the seeds are put into.
    history_step : float or None
        s, decimation of stored histories.
    description : str
        Free text.
    keep_timeseries : bool
        From ``[output] keep_timeseries``: store every case's whole time series.
    """

    name: str
    source: str
    base: dict[str, Any]
    factors: dict[str, list[Any]] = field(default_factory=dict)
    paired: dict[str, list[Any]] = field(default_factory=dict)
    lhs_ranges: dict[str, tuple[float, float]] = field(default_factory=dict)
    lhs_samples: int = 0
    lhs_seed: int = 0
    seeds: tuple[int, ...] = ()
    repetition_irregularity: str = ""
    history_step: float | None = None  #: s
    description: str = ""
    keep_timeseries: bool = False

    @property
    def directory(self) -> Path:
        """Directory relative paths of the study file are taken from."""
        return Path(self.source).parent if self.source else Path.cwd()

    @property
    def varied(self) -> tuple[str, ...]:
        """Names of the factors varied, in order (``seed`` last if repeated)."""
        names = list(self.factors) + list(self.paired) + list(self.lhs_ranges)
        return tuple(names + (["seed"] if self.seeds else []))

    def _error(self, text: str) -> StudyError:
        return StudyError(f"{Path(self.source).name or 'study'}: {text}")

    def _lhs_rows(self) -> list[dict[str, float]]:
        if not self.lhs_ranges:
            return [{}]
        from scipy.stats import qmc

        names = list(self.lhs_ranges)
        sampler = qmc.LatinHypercube(d=len(names), seed=self.lhs_seed)
        unit = sampler.random(self.lhs_samples)
        low = [self.lhs_ranges[n][0] for n in names]
        high = [self.lhs_ranges[n][1] for n in names]
        scaled = qmc.scale(unit, low, high)
        return [{n: float(row[i]) for i, n in enumerate(names)} for row in scaled]

    def combinations(self) -> list[dict[str, Any]]:
        """The factor values of every case (no files read).

        Returns
        -------
        list of dict
            Name -> value, in case order: full factorial x paired rows x Latin-hypercube
            samples x seeds.
        """
        full = [dict(zip(self.factors, c)) for c in itertools.product(*self.factors.values())]
        n_paired = len(next(iter(self.paired.values()))) if self.paired else 1
        paired = [{k: v[i] for k, v in self.paired.items()} for i in range(n_paired)]
        seeds: list[dict[str, Any]] = [{"seed": s} for s in self.seeds] or [{}]
        out = []
        for a, b, c, d in itertools.product(full, paired, self._lhs_rows(), seeds):
            out.append({**a, **b, **c, **d})
        return out

    def cases(self) -> list[Case]:
        """Every case, with its files' content, irregularity and key.

        Each distinct turnout and vehicle file (as modified by the factors) is loaded once
        by the package's loader here, so a bad factor value stops the study before it runs.

        Returns
        -------
        list of Case

        Raises
        ------
        StudyError
            A file or value the loaders reject, a bad irregularity spec (one line).
        """
        texts: dict[str, tuple[str, dict]] = {}
        edited_texts: dict[tuple[str, str], tuple[str, Any]] = {}
        checked: set[str] = set()
        checked_parameters: set[tuple[str, str]] = set()
        irregularities: dict[str, Irregularity] = {}
        routes: dict[str, tuple[str, ...]] = {}
        # (text hash, folder) -> the design files beside it that the text names, hashed
        local: dict[tuple[str, str], list[str]] = {}
        versions = _versions()
        out = []
        for index, values in enumerate(self.combinations()):
            merged = {**self.base, **values}
            files = {}
            for kind in ("turnout", "vehicle"):
                path = self._file(kind, merged.get(kind))
                if str(path) not in texts:
                    texts[str(path)] = self._read(kind, path)
                text, data = texts[str(path)]
                edits = {
                    k[len(kind) + 1 :]: v for k, v in merged.items() if k.startswith(kind + ".")
                }
                edited = (str(path), json.dumps(edits, sort_keys=True, default=str))
                if edits and edited in edited_texts:
                    text, data = edited_texts[edited]  # the same edits of the same file
                elif edits:
                    data = json.loads(json.dumps(data))  # a deep copy of plain data
                    for dotted, value in edits.items():
                        try:
                            set_dotted(data, dotted, value)
                        except (KeyError, TypeError) as err:
                            raise self._error(f"factor {kind}.{dotted}: {err.args[0]}") from None
                    text = dumps(data)
                    edited_texts[edited] = (text, data)
                if _sha(text) not in checked:
                    loaded = self._check_file(kind, path.name, text, edits)
                    checked.add(_sha(text))
                    if kind == "turnout":
                        routes[_sha(text)] = loaded
                folder = str(path.resolve().parent)
                if (_sha(text), folder) not in local:  # once per text and folder, not per case
                    # ``data`` is what ``text`` reads back into (toml_writer.dumps's promise):
                    # not parsed again (~3 ms a turnout file, in the study's serial start)
                    local[_sha(text), folder] = _local_files(data, folder)
                files[kind] = (text, path.name, bool(edits), folder, local[_sha(text), folder])
            settings = {k: v for k, v in merged.items() if k in _settings_fields()}
            settings.pop("irregularity", None)
            route = settings.get("route")
            known = routes[_sha(files["turnout"][0])]
            if route is not None and route not in known:
                raise self._error(
                    f"route {route!r}: {files['turnout'][1]} has no such route "
                    f"(routes: {', '.join(known) or 'none'})"
                )
            parameters = ("", "")
            if merged.get("parameters"):
                path = self._file("parameters", merged["parameters"])
                try:
                    parameters = (path.read_text(encoding="utf-8"), path.name)
                except OSError as err:
                    raise self._error(
                        f"parameters {path.name}: cannot read ({err.strerror or err})"
                    ) from None
            pair = (_sha(parameters[0]), _sha(files["turnout"][0]))
            if parameters[0] and pair not in checked_parameters:
                self._check_parameters(parameters, files["turnout"])
                checked_parameters.add(pair)
            if (settings.get("source") == "fitted") != bool(parameters[0]):
                raise self._error(
                    "source = 'fitted' and a parameters file go together (the fitted set "
                    "of exudyn-turnout fit)"
                )
            spec = self._irregularity_spec(merged)
            if spec and spec not in irregularities:
                try:
                    irregularities[spec] = irregularity_from_spec(spec, self.directory)
                except ValueError as err:
                    raise self._error(f"irregularity: {err}") from None
            history = self.history_step
            key_data = {
                "settings": _resolved(settings),  # defaults too: a changed default, a new key
                "track": merged.get("track"),
                "turnout_sha256": _sha(files["turnout"][0]),
                "vehicle_sha256": _sha(files["vehicle"][0]),
                "parameters_sha256": _sha(parameters[0]) if parameters[0] else "",
                "irregularity": spec,
                "irregularity_files": self._spec_files(spec),
                "history_step": history,
                # the design files the turnout and vehicle name beside them, by content: a
                # changed rail profile is a new case
                "local_files": [files[k][4] for k in ("turnout", "vehicle")],
                **versions,
            }
            key = _sha(json.dumps(key_data, sort_keys=True, default=str))[:20]
            out.append(
                Case(
                    index=index,
                    inputs=dict(values),
                    settings=settings,
                    track=merged.get("track"),
                    turnout_text=files["turnout"][0],
                    turnout_name=files["turnout"][1],
                    turnout_modified=files["turnout"][2],
                    vehicle_text=files["vehicle"][0],
                    vehicle_name=files["vehicle"][1],
                    vehicle_modified=files["vehicle"][2],
                    parameters_text=parameters[0],
                    parameters_name=parameters[1],
                    irregularity_spec=spec,
                    irregularity=irregularities.get(spec),
                    history_step=history,
                    turnout_dir=files["turnout"][3],
                    vehicle_dir=files["vehicle"][3],
                    key=key,
                    keep_timeseries=self.keep_timeseries,
                )
            )
        return out

    def _irregularity_spec(self, merged: Mapping[str, Any]) -> str:
        parts = [str(merged["irregularity"])] if merged.get("irregularity") else []
        if "seed" in merged:
            for part in self.repetition_irregularity.split(";"):
                part = part.strip()
                if part.lower().startswith("psd:") and "seed=" not in part:
                    part += f",seed={int(merged['seed'])}"
                if part:
                    parts.append(part)
        return ";".join(parts)

    def _spec_files(self, spec: str) -> dict[str, str]:
        """SHA-256 of the CSV files a spec names (their content is part of the key)."""
        out = {}
        for part in spec.split(";"):
            part = part.strip()
            if ":" in part.split(",")[0] and not part.lower().endswith(".csv"):
                continue
            path = Path(part)
            path = path if path.is_absolute() else self.directory / path
            if path.is_file():
                out[part] = hashlib.sha256(path.read_bytes()).hexdigest()
        return out

    def _file(self, kind: str, value: Any) -> Path:
        if value is None:
            return default_turnout_path() if kind == "turnout" else default_vehicle_path()
        path = Path(str(value))
        if path.is_absolute():
            return path
        by_name = kind == "vehicle" and value in PACKAGED_VEHICLES
        if by_name and not (self.directory / path).exists():
            return packaged_vehicle_path(str(value))  # a packaged vehicle by name
        if kind == "parameters" and not (self.directory / path).exists():
            packaged = default_turnout_path().parent / path  # a packaged fitted file
            if packaged.exists():
                return packaged
        return self.directory / path

    def _check_parameters(self, parameters: tuple[str, str], turnout: tuple) -> None:
        """Read the fitted file against the case's turnout with the package's reader."""
        import tempfile

        from exudyn_turnout.corunning.fitted import read_fitted
        from exudyn_turnout.inputs.turnout import load_turnout

        with tempfile.TemporaryDirectory() as tmp:
            turnout_path = Path(tmp) / turnout[1]
            turnout_path.write_text(turnout[0], encoding="utf-8")
            path = Path(tmp) / parameters[1]
            path.write_text(parameters[0], encoding="utf-8")
            try:
                read_fitted(path, load_turnout(turnout_path))
            except ValueError as err:
                raise self._error(f"parameters {parameters[1]}: {err}") from None

    def _read(self, kind: str, path: Path) -> tuple[str, dict]:
        try:
            text = path.read_text(encoding="utf-8")
            return text, tomllib.loads(text)
        except OSError as err:
            raise self._error(f"{kind} {path.name}: cannot read ({err.strerror or err})") from None
        except tomllib.TOMLDecodeError as err:
            raise self._error(f"{kind} {path.name}: not valid TOML ({err})") from None

    def _check_file(self, kind: str, name: str, text: str, edits: Mapping[str, Any]) -> Any:
        """Load the (modified) file with the package's loader; the turnout's route names."""
        import tempfile

        from exudyn_turnout.inputs.routes import route_names
        from exudyn_turnout.inputs.turnout import load_turnout

        with tempfile.TemporaryDirectory() as tmp:
            path = Path(tmp) / name
            path.write_text(text, encoding="utf-8")
            try:
                if kind == "turnout":
                    turnout = load_turnout(path)
                    _remember_turnout(name, text, turnout)
                    return tuple(route_names(turnout))
                load_study_vehicle(path)
                return None
            except ValueError as err:  # TurnoutFileError and the vehicle loader's errors
                what = ", ".join(f"{kind}.{k} = {v!r}" for k, v in edits.items())
                message = str(err).replace(str(path), name)
                raise self._error(f"{what + ': ' if what else ''}{message}") from None


def _check_name(name: str, where: str, error) -> None:
    fields = _settings_fields()
    if name in fields or name in FILE_FACTORS:
        return
    if name.startswith(("turnout.", "vehicle.")) and len(name.split(".", 1)[1]) > 0:
        return
    raise error(
        f"{where}: unknown factor {name!r} (settings: {', '.join(fields)}; or track, "
        "turnout, vehicle, irregularity, parameters, turnout.<dotted.path>, "
        "vehicle.<dotted.path>)"
    )


def _check_value(name: str, value: Any, where: str, error) -> None:
    """A value's kind must fit its factor (numbers for numbers, text for text)."""
    fields = _settings_fields()
    text = f"{where}: {name} = {value!r}"
    if name == "track":
        if value not in TRACKS:
            raise error(f"{text}: must be one of {', '.join(TRACKS)}")
    elif name in ("turnout", "vehicle", "irregularity", "parameters") or "str" in fields.get(
        name, ""
    ):
        if not isinstance(value, str):
            raise error(f"{text}: must be a string")
    elif name in fields:
        annotation = fields[name]
        if value is None and "None" in annotation:
            return
        number = isinstance(value, (int, float)) and not isinstance(value, bool)
        if "int" in annotation and "float" not in annotation:
            if not (number and float(value) == int(value)):
                raise error(f"{text}: must be an integer")
        elif not number or not math.isfinite(float(value)):
            raise error(f"{text}: must be a finite number")


def _list(value: Any, name: str, where: str, error) -> list[Any]:
    if not isinstance(value, list) or not value:
        raise error(f"{where}: {name} must be a non-empty list of values")
    return value


def study_from_dict(data: Mapping[str, Any], source: str = "") -> Study:
    """A study from the parsed content of a study file, validated.

    Parameters
    ----------
    data : mapping
        As :func:`tomllib.loads` returns it.
    source : str
        The file's path (relative paths in the study are taken from its directory).

    Returns
    -------
    Study

    Raises
    ------
    StudyError
        One line naming the section and field.
    """
    label = Path(source).name or "study"

    def error(text: str) -> StudyError:
        return StudyError(f"{label}: {text}")

    sections = ("study", "base", "factors", "paired", "latin_hypercube", "repetitions", "output")
    for key in data:
        if key not in sections:
            raise error(f"unknown section [{key}] (sections: {', '.join(sections)})")
    for key in sections:
        if key in data and not isinstance(data[key], Mapping):
            raise error(f"{key} must be a table [{key}]")
    head = dict(data.get("study", {}))
    for key in head:
        if key not in ("name", "description", "history_step"):
            raise error(f"[study]: unknown field {key!r} (fields: name, description, history_step)")
    history = head.get("history_step")
    if history is not None and not (
        isinstance(history, (int, float)) and not isinstance(history, bool) and history > 0
    ):
        raise error(f"[study]: history_step = {history!r} must be a time step > 0 (s)")
    output = dict(data.get("output", {}))
    for key in output:
        if key != "keep_timeseries":
            raise error(f"[output]: unknown field {key!r} (fields: keep_timeseries)")
    keep = output.get("keep_timeseries", False)
    if not isinstance(keep, bool):
        raise error(f"[output]: keep_timeseries = {keep!r} must be true or false")
    base = dict(data.get("base", {}))
    for name, value in base.items():
        _check_name(name, "[base]", error)
        if not name.startswith(("turnout.", "vehicle.")):
            _check_value(name, value, "[base]", error)
    factors: dict[str, list[Any]] = {}
    for name, values in dict(data.get("factors", {})).items():
        _check_name(name, "[factors]", error)
        factors[name] = _list(values, name, "[factors]", error)
    paired: dict[str, list[Any]] = {}
    for name, values in dict(data.get("paired", {})).items():
        _check_name(name, "[paired]", error)
        paired[name] = _list(values, name, "[paired]", error)
    if len({len(v) for v in paired.values()}) > 1:
        lengths = ", ".join(f"{k}: {len(v)}" for k, v in paired.items())
        raise error(f"[paired]: the lists must have one length ({lengths})")
    lhs = dict(data.get("latin_hypercube", {}))
    for key in lhs:
        if key not in ("samples", "seed", "ranges"):
            raise error(f"[latin_hypercube]: unknown field {key!r} (fields: samples, seed, ranges)")
    ranges: dict[str, tuple[float, float]] = {}
    samples: Any = 0
    lhs_seed: Any = 0
    if lhs:
        samples, lhs_seed = lhs.get("samples"), lhs.get("seed", 0)
        if not (isinstance(samples, int) and not isinstance(samples, bool) and samples >= 1):
            raise error(f"[latin_hypercube]: samples = {samples!r} must be an integer >= 1")
        if not (isinstance(lhs_seed, int) and not isinstance(lhs_seed, bool) and lhs_seed >= 0):
            raise error(f"[latin_hypercube]: seed = {lhs_seed!r} must be an integer >= 0")
        if not isinstance(lhs.get("ranges"), Mapping) or not lhs["ranges"]:
            raise error("[latin_hypercube]: ranges = { name = [low, high], ... } is missing")
        for name, pair in lhs["ranges"].items():
            _check_name(name, "[latin_hypercube]", error)
            ok = (
                isinstance(pair, list)
                and len(pair) == 2
                and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in pair)
                and all(math.isfinite(v) for v in pair)
                and pair[0] < pair[1]
            )
            if not ok:
                raise error(f"[latin_hypercube]: {name} = {pair!r} must be [low, high], low < high")
            ranges[name] = (float(pair[0]), float(pair[1]))
    rep = dict(data.get("repetitions", {}))
    for key in rep:
        if key not in ("irregularity", "seeds"):
            raise error(f"[repetitions]: unknown field {key!r} (fields: irregularity, seeds)")
    seeds: tuple[int, ...] = ()
    rep_spec = ""
    if rep:
        raw = rep.get("seeds")
        if isinstance(raw, int) and not isinstance(raw, bool) and raw >= 1:
            seeds = tuple(range(1, raw + 1))
        elif (
            isinstance(raw, list)
            and raw
            and all(isinstance(s, int) and not isinstance(s, bool) and s >= 0 for s in raw)
        ):
            seeds = tuple(raw)
        else:
            raise error(f"[repetitions]: seeds = {raw!r} must be a count >= 1 or a list of seeds")
        rep_spec = rep.get("irregularity", "")
        if not isinstance(rep_spec, str) or "psd:" not in rep_spec.lower():
            raise error(
                "[repetitions]: irregularity must be a spec with a psd: part "
                '(e.g. "psd:ERRI-low,band=1-70"), its seed is set per case'
            )
    groups: dict[str, Mapping[str, Any]] = {
        "[factors]": factors,
        "[paired]": paired,
        "[latin_hypercube]": ranges,
    }
    seen: dict[str, str] = {}
    for where, names in groups.items():
        for name in names:
            if name in seen:
                raise error(f"{where}: factor {name!r} is also in {seen[name]}")
            seen[name] = where
            if name not in ranges and not name.startswith(("turnout.", "vehicle.")):
                for value in names[name]:
                    _check_value(name, value, where, error)
    if ranges:
        for name in ranges:
            if not (name.startswith(("turnout.", "vehicle.")) or name in _settings_fields()):
                raise error(f"[latin_hypercube]: {name} is not a number to sample")
    if seeds and "seed" in seen:
        raise error("factor 'seed' is set by [repetitions]")
    return Study(
        name=str(head.get("name") or Path(source).stem or "study"),
        source=str(source),
        base=base,
        factors=factors,
        paired=paired,
        lhs_ranges=ranges,
        lhs_samples=int(samples or 0),
        lhs_seed=int(lhs_seed or 0),
        seeds=seeds,
        repetition_irregularity=rep_spec,
        history_step=None if history is None else float(history),
        description=str(head.get("description", "")),
        keep_timeseries=keep,
    )


def load_study(path: str | Path) -> Study:
    """Read and validate a study file.

    Parameters
    ----------
    path : str or Path
        The TOML study file.

    Returns
    -------
    Study

    Raises
    ------
    StudyError
        Unreadable file, invalid TOML, unknown section or factor, a value of the wrong kind
        (one line naming the file and field). Files and values the loaders check are
        checked by :meth:`Study.cases`.
    """
    p = Path(path)
    try:
        text = p.read_text(encoding="utf-8")
    except OSError as err:
        raise StudyError(f"{p.name}: cannot read ({err.strerror or err})") from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise StudyError(f"{p.name}: not valid TOML ({err})") from None
    return study_from_dict(data, str(p))
