"""beamid: identify a Timoshenko beam's stiffness, mass and damping from its vibration (Banks & Wang 1993).

The Python face of the beamid program: every function runs the same C++ computation as the command of its name,
with the command's flags as keyword-only arguments of a real signature (``help(beamid.fit)`` lists them with their
types, defaults and meanings, generated from the program's command registry). A flag's dashes become underscores
(``--sensor-x`` is ``sensor_x``, ``--pulse-width`` is ``pulse_width``), a switch is ``True``, a list is a list or
tuple. A keyword the command does not have, or a value of the wrong type, is a ``TypeError``; the values are then
checked by the program's own parser and requests, so a call and the command line validate alike, fail with the same
one-line message (as :class:`InputError`, a ``ValueError``, :class:`NumericalError`, a ``RuntimeError``, or
:class:`OutputError`, an ``OSError``: a report that could not be written) and give
the same numbers bit for bit. Records (``data``) are a file path, as on the command line, or a NumPy array of samples
(or samples x channels) with ``sample_rate`` or ``time``; a beam is a preset, a TOML file or a dict (:func:`beam`).

    >>> import beamid
    >>> y = beamid.simulate(beam="thick-steel", elements=8, dt=1e-4, samples=256, output="acceleration")
    >>> result = beamid.fit(data=y, sample_rate=1e4, beam="thick-steel", elements=8, output="acceleration",
    ...                     estimate=["EI", "rho"], cost="time")
    >>> result.estimates["EI"]

The computations release the GIL: fits on several threads run in parallel.
"""
import atexit
import functools
import inspect
import numbers
import os
import threading
import typing
import warnings

import numpy as np

from . import _core
from ._core import InputError, NumericalError, OutputError
from .results import load_results, read_table
from .values import CostValue, CramerRao, Design, FitResult, Record, Spikes, System

__all__ = ["InputError", "NumericalError", "OutputError", "FitResult", "Spikes", "CostValue", "CramerRao", "Design", "System", "Record", "version", "presets", "beam", "beam_toml", "modes",
           "simulate", "system", "spikes", "cost", "fit", "crb", "design", "modal_id", "read_record", "load_results",
           "read_table"]


def version():
    """The core's version and the git commit it was built from."""
    return _core.version()


def presets():
    """The names of the built-in beams (``beam="banks-aluminium"``, ...)."""
    return list(_core.presets())


# The computations running on the core's worker threads (below), each as the event its worker sets when it ends: one
# interrupted by Ctrl-C finishes in the background. (Not Thread.join: in Python 3.11 a join interrupted by
# KeyboardInterrupt leaves the thread reported as no longer alive while it still runs.)
_running = set()


@atexit.register
def _wait_for_core():
    """Waits for the computations still running on the core's worker threads; at exit, before the process destroys its
    static objects: a fit interrupted by Ctrl-C just before a script ended went on using them, and the interpreter
    crashed with a segmentation fault at exit (issue 30)."""
    for done in list(_running):
        done.wait()
        _running.discard(done)


def _call(function, *args, abandonable=False):
    """Runs a core computation on a worker thread and waits for it there, so that Ctrl-C (or a Jupyter interrupt)
    raises KeyboardInterrupt in the caller at once. The core cannot be stopped part-way: an interrupted computation
    finishes in the background and its result is dropped (the interpreter waits for it at exit). From other threads
    the core is called directly."""
    if threading.current_thread() is not threading.main_thread():
        return function(*args, None) if abandonable else function(*args)
    box = {}
    done = threading.Event()
    # Set when the caller is interrupted: a computation that writes files (fit's report) then writes none.
    abandoned = threading.Event()
    if abandonable:
        args = args + (abandoned,)

    def work():
        try:
            box["value"] = function(*args)
        except BaseException as error:  # handed to the caller below
            box["error"] = error
        finally:
            done.set()

    _running.add(done)
    threading.Thread(target=work, name="beamid-core", daemon=True).start()
    try:
        while not done.wait(0.05):
            pass
    except BaseException:
        abandoned.set()
        raise
    _running.discard(done)
    if "error" in box:
        raise box["error"]
    return box["value"]


def _text(value):
    """A keyword argument's value as the command line would spell it: floats in their shortest round-trip form
    (repr), so that the program's parser reads back the very same double."""
    if isinstance(value, (bool, np.bool_)):
        raise TypeError("a switch is True or left out; it takes no value (a list of booleans is no flag value)")
    if isinstance(value, numbers.Integral):
        return str(int(value))
    if isinstance(value, numbers.Real):
        return repr(float(value))
    return os.fspath(value) if isinstance(value, os.PathLike) else str(value)


def _arguments(flags):
    """The command line after the command's name for these keyword arguments (None and False: left out)."""
    arguments = []
    for key, value in flags.items():
        if value is None or value is False:
            continue
        flag = "--" + key.replace("_", "-")
        if isinstance(value, np.ndarray) and value.ndim == 0:
            value = value.item()  # a NumPy scalar array is its scalar
        if isinstance(value, np.bool_):
            value = bool(value)
        if value is False:
            continue
        if value is True:
            arguments.append(flag)
        elif isinstance(value, (list, tuple, np.ndarray)):
            arguments += [flag, ",".join(_text(v) for v in value)]
        else:
            arguments += [flag, _text(value)]
    return arguments


def beam_toml(parameters):
    """TOML text for a beam file (the [beam] table, then [[attachment]] and [support]) from a dict as :func:`beam`
    returns it: every key of the [beam] table, "attachmentK.x/m/J/c" for bodies on the span and "support.k_theta",
    "support.k_w" for a compliant clamp (infinite or absent: rigid)."""
    if not isinstance(parameters, dict):  # a preset's name gave an AttributeError (the twenty-second pass's P16)
        raise TypeError(f"beam_toml(): {parameters!r}: must be a dict of a beam's parameters, as beam() returns it "
                        "(beam('banks-aluminium') for a preset's)")
    lines, attachments, support = ["[beam]"], {}, {}
    for key, value in parameters.items():
        if not isinstance(key, str):  # {1: 2} failed inside str.partition with an AttributeError
            raise TypeError(f"beam dict: key {key!r}: must be a string, a parameter's name (EI, rho, ...)")
        if not isinstance(value, numbers.Real) or isinstance(value, (bool, np.bool_)):
            raise InputError(f"beam dict: {key} = {value!r}: must be a number")
        head, _, field = key.partition(".")
        if head.startswith("attachment") and field:
            index = head[len("attachment"):]
            # "attachment01" and "attachment1" would both be body 1, one silently replacing the other: refused.
            if not index.isdigit() or int(index) < 1 or index != str(int(index)):
                raise InputError(f"beam dict: key '{key}': an attachment's keys read attachmentK.x, .m, .J, .c with "
                                 f"K = 1, 2, ...")
            attachments.setdefault(int(index), {})[field] = value
        elif head == "support" and field:
            # +inf is the rigid clamp (the key left out); NaN or -inf is no spring, and was silently made rigid.
            if np.isnan(value) or value == -np.inf:
                raise InputError(f"beam dict: {key} = {value!r}: must be a stiffness > 0, or inf for a rigid clamp")
            if np.isfinite(value):
                support[field] = value
        else:
            lines.append(f"{key} = {_toml_number(value)}")
    # Attachments are numbered 1, 2, ... in the file's order: a gap (attachment1 and attachment3) silently made the
    # user's attachment3 the beam's attachment2 (the third pass's P466, P478).
    missing = [k for k in range(1, max(attachments, default=0) + 1) if k not in attachments]
    if missing:
        raise InputError(f"beam dict: attachment{missing[0]} is missing while attachment{max(attachments)} is given: "
                         "attachments are numbered 1, 2, ... without gaps")
    for index in sorted(attachments):
        lines.append("")
        lines.append("[[attachment]]")
        lines += [f"{field} = {_toml_number(value)}" for field, value in attachments[index].items()]
    if support:
        lines += ["", "[support]"] + [f"{field} = {_toml_number(value)}" for field, value in support.items()]
    return "\n".join(lines) + "\n"


def _toml_number(value):
    value = float(value)
    text = repr(value)
    return text if any(c in text for c in ".en") else text + ".0"  # TOML floats need a point or an exponent


def beam(spec=None, *, toml=None):
    """A beam's parameters as a dict: a preset name or a TOML beam file (``spec``), or TOML text (``toml``, as
    :func:`beam_toml` writes it). The dict can be changed and passed as ``beam=`` to every function."""
    if (spec is None) == (toml is None):
        raise TypeError("give a preset or file (spec) or TOML text (toml=), one of them")
    if toml is not None:
        return dict(_core.parse_beam(toml, "<toml>"))
    if isinstance(spec, dict):  # a beam dict, checked as every function checks one (it raised a bare TypeError: Q519)
        return dict(_core.parse_beam(beam_toml(spec), BEAM_DICT))
    if not isinstance(spec, (str, os.PathLike)):
        raise TypeError(f"beam(): spec = {spec!r}: must be a preset name, a beam TOML file's path or a beam dict")
    return dict(_core.beam(os.fspath(spec)))


BEAM_DICT = "<beam dict>"  # how messages and reports name a beam given as a dict


def _beam_argument(flags):
    """``beam=`` as the core takes it: (the flags with --beam as the program spells it, the TOML text of a beam given
    as a dict or None). A dict is read from memory by the core (no file), and its messages name it "<beam dict>"
    with the line of its TOML, as :func:`beam_toml` writes it."""
    value = flags.get("beam")
    if not isinstance(value, dict):
        return flags, None
    return dict(flags, beam=BEAM_DICT), beam_toml(value)


def _record_flags(data, flags):
    """Splits ``data`` into the --data flag (a path) or an array for the core (--data then reads "<array>")."""
    # None is no record: "--data is required" named a command-line flag (the twenty-fourth pass's adv56 P6).
    if data is None:
        raise TypeError("data = None: a record is required, a path (str or os.PathLike) or an array of samples")
    if isinstance(data, (str, os.PathLike)):
        return None, dict(flags, data=data)
    if isinstance(data, (bytes, bytearray)):
        raise TypeError("data: a path (str or os.PathLike) or an array of samples, not bytes")
    if isinstance(data, Record):  # read_record's result was refused as "an array of dtype object" (adv72 P3)
        raise TypeError("data: a Record: pass its file's path, or its samples with their step, "
                        "data=record.values, sample_rate=1 / record.dt_s (and units=record.unit)")
    if _ndim(data) < 0:  # a ragged nesting: NumPy's "inhomogeneous shape" named no argument
        raise TypeError(f"data = {repr(data)[:80]}: a ragged list, no array of samples")
    if np.ma.isMaskedArray(data) and np.ma.is_masked(data):
        raise InputError("data: a masked array: fill or drop the masked samples first (a record is uniformly sampled)")
    array = np.asarray(data)
    if np.iscomplexobj(array):
        raise InputError("data: complex values: a record is the real sensor signal")
    # A bool array is flags, not a signal (it was refused as "clipped"); a structured one has named fields, which
    # NumPy's cast refused without naming the argument; an object array holds no numbers beamid can trust.
    if array.dtype.kind == "b":
        raise InputError("data: a bool array: a record is the sensor's numeric signal, not flags")
    if array.dtype.names is not None:
        raise InputError(f"data: a structured array (fields {', '.join(array.dtype.names)}): pass one field, "
                         "data=array['name'], and its time as time=")
    if array.dtype.kind not in "biuf":
        raise InputError(f"data: an array of dtype {array.dtype}: a record is an array of numbers")
    if array.size == 0:
        raise InputError("data: an empty array: a record needs at least 8 samples")
    return np.asarray(array, dtype=float), dict(flags, data="<array>")


def _warn_lines(r: dict) -> None:
    """The lines the command prints on stderr beside its result ("beamid simulate: ..."), as warnings at the caller."""
    for line in r.get("warnings", []):
        warnings.warn(line, stacklevel=3)


def modes(**flags) -> np.ndarray:
    """``beamid modes``: a structured array (mode, frequency_hz, damping_ratio) of the beam's modes."""
    f, toml = _beam_argument(flags)
    r = _call(_core.modes, _arguments(f), toml)
    _warn_lines(r)
    count = len(r["frequency_hz"])
    if r["note"]:
        warnings.warn("beamid modes: " + r["note"], stacklevel=3)
    fields = [("mode", "i8"), ("frequency_hz", "f8")] + ([("damping_ratio", "f8")] if r["kind"] != "exact" else [])
    table = np.zeros(count, dtype=fields)
    table["mode"] = np.arange(1, count + 1)
    table["frequency_hz"] = r["frequency_hz"]
    if r["kind"] != "exact":
        table["damping_ratio"] = r["damping_ratio"]
    return table


def simulate(**flags) -> np.ndarray:
    """``beamid simulate``: the sampled output as a 1-D array (``y[i]`` at ``t = dt * i``), bit-identical to the
    command's second column; with ``force_column=True`` a 2-D array whose columns are the output and the force
    (``force_N``, with ``force_noise_level`` noise on it), as the command's second and third columns."""
    f, toml = _beam_argument(flags)
    r = _call(_core.simulate, _arguments(f), toml)
    _warn_lines(r)
    if "force" in r:
        return np.column_stack((r["y"], r["force"]))
    return r["y"]


def system(**flags) -> "System":
    """``beamid system``: the Galerkin matrices M, C, K (arrays) with the experiment's load, sensor, initial state and
    sampling, as a :class:`System`."""
    f, toml = _beam_argument(flags)
    r = _call(_core.system, _arguments(f), toml)
    _warn_lines(r)
    return System._from_core(r)


def spikes(data, time=None, **flags) -> "Spikes":
    """``beamid spikes``: a :class:`Spikes` with ``picks`` (the spikes, ascending: bin, frequency_hz, magnitude,
    n_left, n_right, the sub-bin and the measured frequency, a structured array) and ``skipped`` (peaks passed over
    as artefacts, with the reason). What widens a measured frequency's uncertainty, or why none was measured, is a
    warning, as the command's stderr."""
    array, f = _record_flags(data, flags)
    raw = _call(_core.spikes, _arguments(f), array, time)
    for note in raw["notes"]:
        warnings.warn("beamid spikes: " + note, stacklevel=2)
    return Spikes._from_core(raw)


def cost(data, prediction, time=None, **flags) -> "CostValue":
    """``beamid cost``: the value of ``cost=`` for a prediction (a file, or an array at the data's step) against the
    data; returns a :class:`CostValue` with value, residuals, amplitude_scale and the (A4) check."""
    array, f = _record_flags(data, flags)
    if isinstance(prediction, (str, os.PathLike)):
        f["prediction"], predicted = os.fspath(prediction), None
    else:
        # Checked as a record is: a complex prediction was silently cast to its real part, and one of 1e200 gave an
        # infinite cost instead of an error.
        if np.iscomplexobj(prediction):
            raise InputError("prediction: complex values: a prediction is the model's real output")
        predicted = np.asarray(prediction, dtype=float)
        if predicted.size and not np.all(np.abs(predicted) <= 1e150):
            raise InputError("prediction: values beyond 1e150 or not finite: its spectrum would overflow (rescale it)")
        f["prediction"] = "<array>"
    return CostValue._from_core(_call(_core.cost, _arguments(f), array, time, predicted))


def fit(data, time=None, **flags) -> "FitResult":
    """``beamid fit``: fits the record(s) and returns a :class:`FitResult`. ``data`` is a file or an array (with
    ``sample_rate`` or ``time``); a 2-D array with ``channel=[1, 2]`` and ``sensor_x=[...]`` is a joint fit. Unlike
    the command, a failed fit is not an exception: its status says "failed", and a warning says why.

    A record read from a CSV has the step (t_last - t_0)/(n - 1) of its time column: to reproduce the command line's
    fit of that file bit for bit from arrays, pass the file's time column as ``time=``, not ``sample_rate=``.
    ``report=PATH`` writes the command's Markdown report (and PATH.spectra.csv beside it), creating its folder."""
    array, f = _record_flags(data, flags)
    f, toml = _beam_argument(f)
    # (A beam dict's TOML ends the report, written with it by the core.)
    result = FitResult._from_core(_call(_core.fit, _arguments(f), toml, array, time, abandonable=True))
    for message in result.messages:
        warnings.warn("beamid fit: " + message, stacklevel=3)
    return result


def crb(**flags) -> "CramerRao":
    """``beamid crb``: the Cramér-Rao bound, a :class:`CramerRao` with parameters, value, crb_sd, crb_relative_sd
    (arrays in the order of ``estimate``), the noise sd assumed, the covariance of ln q and the method."""
    f, toml = _beam_argument(flags)
    r = _call(_core.crb, _arguments(f), toml)
    _warn_lines(r)
    return CramerRao._from_core(r)


def design(**flags) -> "Design":
    """``beamid design``: the candidate experiments (``sensor_x``, ``sensors``, ``force_x``, ``pulse_width``, ``dt``,
    ``samples``: lists, or ranges "START:STOP:COUNT") ranked by the ``criterion`` (D, A or a key) of the Fisher
    information of ``estimate``: a :class:`Design`, best first."""
    f, toml = _beam_argument(flags)
    r = _call(_core.design, _arguments(f), toml)
    _warn_lines(r)
    return Design._from_core(r)


def modal_id(data, time=None, **flags) -> np.ndarray:
    """``beamid modal-id``: the modes of a free decay by the matrix pencil, a structured array (mode, frequency_hz,
    damping_ratio, amplitude, phase_rad, frequency_sd_hz: the Cramér-Rao bound at the residual's noise level;
    drift_hz, span_low_hz, span_high_hz, frequency_uncertainty_hz: the frequency's change between the record's
    segments, the span of every estimate of it, and the uncertainty that covers them, as every command reports a
    measured frequency; damping_ratio_uncertainty, the decay rate's over |lambda|). What the modes do not say (fewer
    found than asked, a pole more likely the excitation, a growing oscillation, a frequency that changes with the
    amplitude) is a warning, as the command's stderr."""
    array, f = _record_flags(data, flags)
    r = _call(_core.modal_id, _arguments(f), array, time)
    fields = ["frequency_hz", "damping_ratio", "amplitude", "phase_rad", "frequency_sd_hz", "drift_hz",
              "span_low_hz", "span_high_hz", "frequency_uncertainty_hz", "damping_ratio_uncertainty"]
    table = np.zeros(len(r["frequency_hz"]), dtype=[("mode", "i8")] + [(name, "f8") for name in fields])
    table["mode"] = np.arange(1, len(table) + 1)
    for name in fields:
        table[name] = r[name]
    for note in r["notes"]:
        warnings.warn("beamid modal-id: " + note, stacklevel=3)
    return table


def read_record(path, **flags) -> "Record":
    """A record file as beamid reads it (CSV, .lvm, .npy, .mat, UFF 58, with the import flags: channel, units, start,
    duration, sample_rate, variable, time_variable, time_channel, resample, resample_rate): a :class:`Record` with
    values (array), dt_s, t0_s, unit, format, channel and notes."""
    if not isinstance(path, (str, os.PathLike)):  # read_record(123) reached the core untyped (the fourth pass's Q490)
        raise TypeError(f"read_record(): path = {path!r}: must be a file path (str or os.PathLike)")
    try:
        return Record._from_core(_call(_core.read_record, _arguments(dict(flags, data=path))))
    except InputError as error:  # the core reads it with modal-id's import flags: named as read_record's
        message = str(error).replace("beamid modal-id:", "beamid.read_record:")
        message = message.replace("(beamid modal-id --help lists them)", "(read_record takes " + _IMPORT_FLAGS + ")")
        raise InputError(message) from None


_IMPORT_FLAGS = ("channel, units, start, duration, resample, sample_rate, variable, time_variable, time_channel, "
                 "resample_rate")


_KINDS = {"number": float, "integer": int, "text": str, "switch": bool}
# The flags that take a list (comma-separated text on the command line) and the type of their items: here a list or
# tuple of items, a single item, or the comma-separated text. The program's parser checks the items' values.
_LISTS = {"estimate": str, "channel": (str, int), "spike_frequencies": float, "bounds": str}
_FIT_LISTS = {"sensor_x": float}  # a list in fit (one position per channel), one number elsewhere
# design's candidates: lists of values (a text item may be a range "START:STOP:COUNT").
_DESIGN_LISTS = {"sensor_x": float, "force_x": float, "pulse_width": float, "dt": float, "samples": int}
_PATHS = {"data", "prediction", "report", "beam"}


def _list_item(command, name):
    if command == "design" and name in _DESIGN_LISTS:
        return _DESIGN_LISTS[name]
    return _LISTS.get(name) or (_FIT_LISTS.get(name) if command == "fit" else None)


def _annotation(command, name, kind):
    item = _list_item(command, name)
    if name == "beam":
        return typing.Union[str, os.PathLike, dict]
    if item is not None:
        item = typing.Union[item] if isinstance(item, tuple) else item
        return typing.Union[str, item, typing.Sequence[item]]
    if name in _PATHS:
        return typing.Union[str, os.PathLike]
    return _KINDS[kind]


def _is(type_, value):
    """Whether a value is of a flag's type: a bool is no number; NumPy scalars count as their Python kinds."""
    if isinstance(value, np.ndarray) and value.ndim == 0:
        value = value.item()
    if type_ is bool:
        return isinstance(value, (bool, np.bool_))
    if isinstance(value, (bool, np.bool_)):
        return False
    if type_ is float:
        return isinstance(value, numbers.Real)
    if type_ is int:
        return isinstance(value, numbers.Integral)
    if type_ is str:
        return isinstance(value, str)
    return any(_is(t, value) for t in type_)


def _ndim(value):
    """np.ndim, or -1 for a ragged nesting ([[2.46], 26.5]), whose np.ndim is NumPy's ValueError naming no argument
    (the twenty-third pass's P8)."""
    try:
        return np.ndim(value)
    except ValueError:
        return -1


def _check_type(command, name, kind, value):
    """TypeError unless the value has the flag's type (a list only where the flag takes one)."""
    item = _list_item(command, name)
    if item is not None and isinstance(value, (list, tuple, np.ndarray)) and _ndim(value) == 1 and len(value) == 0:
        # An empty list names nothing (it was told "must be a string or a list of them", which it is).
        raise InputError(f"{command}(): {name} = {value!r}: must not be empty")
    if item is not None and isinstance(value, (list, tuple, np.ndarray)) and _ndim(value) == 1:
        ok = all(_is(item, v) for v in value)
    elif item is not None:
        ok = _is(str, value) or _is(item, value)
    elif name == "beam":
        ok = _is(str, value) or isinstance(value, (os.PathLike, dict))
    elif name in _PATHS:  # a file: a string or a path object
        ok = _is(str, value) or isinstance(value, os.PathLike)
    else:
        ok = _is(_KINDS[kind], value)
    # A NUL cannot reach a command line, and the core's file names end at one: report="a\0b.md" wrote the file "a"
    # (the twenty-first pass's P7).
    texts = [value] if isinstance(value, str) else [v for v in value if isinstance(v, str)] \
        if isinstance(value, (list, tuple)) else [os.fspath(value)] if isinstance(value, os.PathLike) else []
    if ok and any("\0" in str(t) for t in texts):
        raise ValueError(f"{command}(): {name} = {value!r}: holds a NUL character, which no flag's value may hold")
    if not ok:
        names = {float: "a number", int: "an integer", str: "a string", bool: "True or False"}
        if isinstance(item, tuple):  # channel: a name or a 1-based index
            expected = " or ".join(names[t] for t in item)
        else:
            expected = names[item if item is not None else _KINDS[kind]]
        if item is not None:
            expected += " or a list of them"
        raise TypeError(f"{command}(): {name} = {value!r}: must be {expected}")


def _typed(function, command, leading, skip=(), label=None):
    """The function with the command's flags as its keyword-only parameters (from the program's registry): a real
    signature for help() and editors, its docstring listing each flag, and every call checked against it (an unknown
    keyword or a value of the wrong type is a TypeError before the core sees it)."""
    flags = [f for f in _core.command_flags(command) if f["name"] not in skip]
    parameters = list(leading)
    kinds = {}
    for f in flags:
        name = f["name"].replace("-", "_")
        kinds[name] = f["kind"]
        default = inspect.Parameter.empty if f["required"] else (False if f["kind"] == "switch" else None)
        annotation = _annotation(command, name, f["kind"])
        if default is None:
            annotation = typing.Optional[annotation]
        parameters.append(inspect.Parameter(name, inspect.Parameter.KEYWORD_ONLY, default=default,
                                            annotation=annotation))
    signature = inspect.Signature(parameters, return_annotation=inspect.signature(function).return_annotation)

    @functools.wraps(function)
    def checked(*args, **kwargs):
        bound = signature.bind(*args, **kwargs)
        for name, value in bound.arguments.items():
            # False means "left out" only for a switch: start=False was dropped without a word (adv72 P2).
            if name in kinds and value is not None and (value is not False or kinds[name] != "switch"):
                try:
                    _check_type(command, name, kinds[name], value)
                except TypeError as error:  # named as the function the caller called
                    if label is None:
                        raise
                    raise TypeError(str(error).replace(f"{command}():", f"{label}():")) from None
        positional = {p.name: bound.arguments.get(p.name, p.default) for p in leading}
        given = {k: v for k, v in bound.arguments.items() if k in kinds}
        return function(**positional, **given)

    checked.__signature__ = signature
    lines = []
    for f in flags:
        ranged = f" ({f['min']}..{f['max']})" if f["kind"] == "integer" and f["max"] < 2**31 - 1 else ""
        lines.append(f"    {f['name'].replace('-', '_')}: {f['help']}{ranged}" + (" [required]" if f["required"] else ""))
    checked.__doc__ = (function.__doc__ or "") + "\n\n    Keyword arguments (the flags of `beamid " + command + \
        "`; None: the command's default):\n\n" + "\n".join(lines)
    return checked


def _positional(name, default=inspect.Parameter.empty, annotation=inspect.Parameter.empty):
    return inspect.Parameter(name, inspect.Parameter.POSITIONAL_OR_KEYWORD, default=default, annotation=annotation)


_RECORD = typing.Union[str, os.PathLike, np.ndarray]
_TIME = _positional("time", None, typing.Optional[np.ndarray])
modes = _typed(modes, "modes", [])
simulate = _typed(simulate, "simulate", [])
system = _typed(system, "system", [])
spikes = _typed(spikes, "spikes", [_positional("data", annotation=_RECORD), _TIME], skip={"data"})
cost = _typed(cost, "cost", [_positional("data", annotation=_RECORD),
                             _positional("prediction", annotation=_RECORD), _TIME], skip={"data", "prediction"})
fit = _typed(fit, "fit", [_positional("data", annotation=_RECORD), _TIME], skip={"data"})
crb = _typed(crb, "crb", [])
design = _typed(design, "design", [])
modal_id = _typed(modal_id, "modal-id", [_positional("data", annotation=_RECORD), _TIME], skip={"data"})
# read_record takes modal-id's import flags, checked as every function's are (channel=True was "--data is required",
# duration=False was dropped: the thirty-second pass's adv72 P2).
_IMPORT_FLAG_NAMES = {name.strip().replace("_", "-") for name in _IMPORT_FLAGS.split(",")}
read_record = _typed(read_record, "modal-id", [_positional("path")],
                     skip={f["name"] for f in _core.command_flags("modal-id") if f["name"] not in _IMPORT_FLAG_NAMES},
                     label="read_record")
