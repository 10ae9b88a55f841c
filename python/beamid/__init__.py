"""beamid: identify a Timoshenko beam's stiffness, mass and damping from its vibration (Banks & Wang 1993).

The Python face of the beamid program: every function runs the same C++ computation as the command of its name,
with the command's flags as keyword arguments. A flag's dashes become underscores (``--sensor-x`` is ``sensor_x``,
``--pulse-width`` is ``pulse_width``), a switch is ``True``, a list is a list or tuple. The flags are parsed by the
program's own parser, so a call and the command line validate alike, fail with the same one-line message (as
:class:`InputError`, a ``ValueError``, or :class:`NumericalError`, a ``RuntimeError``) and give the same numbers bit
for bit. Records (``data``) are a file path, as on the command line, or a NumPy array of samples (or samples x
channels) with ``sample_rate`` or ``time``. ``beamid <command> --help`` lists every flag.

    >>> import beamid
    >>> y = beamid.simulate(beam="thick-steel", elements=8, dt=1e-4, samples=256, output="acceleration")
    >>> result = beamid.fit(data=y, sample_rate=1e4, beam="thick-steel", elements=8, output="acceleration",
    ...                     estimate=["EI", "rho"], cost="time")
    >>> result.estimates["EI"]

The computations release the GIL: fits on several threads run in parallel.
"""
import contextlib
import numbers
import os
import tempfile

import numpy as np

from . import _core
from ._core import InputError, NumericalError
from .results import load_results, read_table

__all__ = ["InputError", "NumericalError", "FitResult", "version", "presets", "beam", "beam_toml", "modes",
           "simulate", "system", "spikes", "cost", "fit", "crb", "modal_id", "read_record", "load_results",
           "read_table"]


def version():
    """The core's version and the git commit it was built from."""
    return _core.version()


def presets():
    """The names of the built-in beams (``beam="banks-aluminium"``, ...)."""
    return list(_core.presets())


def _text(value):
    """A keyword argument's value as the command line would spell it: floats in their shortest round-trip form
    (repr), so that the program's parser reads back the very same double."""
    if isinstance(value, (bool, np.bool_)):
        raise TypeError("a switch is True or left out; it takes no value")
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
    lines, attachments, support = ["[beam]"], {}, {}
    for key, value in parameters.items():
        head, _, field = key.partition(".")
        if head.startswith("attachment") and field:
            attachments.setdefault(int(head[len("attachment"):]), {})[field] = value
        elif head == "support" and field:
            if np.isfinite(value):
                support[field] = value
        else:
            lines.append(f"{key} = {_toml_number(value)}")
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
    return dict(_core.beam(os.fspath(spec)))


@contextlib.contextmanager
def _beam_flag(flags):
    """``beam=`` as the program takes it: a dict becomes a temporary beam file for the duration of the call."""
    value = flags.get("beam")
    if not isinstance(value, dict):
        yield flags
        return
    with tempfile.TemporaryDirectory(prefix="beamid-") as folder:
        path = os.path.join(folder, "beam.toml")
        with open(path, "w", encoding="utf-8") as out:
            out.write(beam_toml(value))
        yield dict(flags, beam=path)


def _record_flags(data, flags):
    """Splits ``data`` into the --data flag (a path) or an array for the core (--data then reads "<array>")."""
    if data is None or isinstance(data, (str, os.PathLike)):
        return None, dict(flags, data=data)
    return np.asarray(data, dtype=float), dict(flags, data="<array>")


def modes(**flags):
    """``beamid modes``: a structured array (mode, frequency_hz, damping_ratio) of the beam's modes."""
    with _beam_flag(flags) as f:
        r = _core.modes(_arguments(f))
    count = len(r["frequency_hz"])
    fields = [("mode", "i8"), ("frequency_hz", "f8")] + ([("damping_ratio", "f8")] if r["kind"] != "exact" else [])
    table = np.zeros(count, dtype=fields)
    table["mode"] = np.arange(1, count + 1)
    table["frequency_hz"] = r["frequency_hz"]
    if r["kind"] != "exact":
        table["damping_ratio"] = r["damping_ratio"]
    return table


def simulate(**flags):
    """``beamid simulate``: the sampled output as a 1-D array (``y[i]`` at ``t = dt * i``), bit-identical to the
    command's second column."""
    with _beam_flag(flags) as f:
        return _core.simulate(_arguments(f))["y"]


def system(**flags):
    """``beamid system``: the Galerkin matrices M, C, K (arrays) with the experiment's load, sensor, initial state and
    sampling, as a dict."""
    with _beam_flag(flags) as f:
        return dict(_core.system(_arguments(f)))


def spikes(data, time=None, **flags):
    """``beamid spikes``: a dict with ``picks`` (the spikes, ascending: bin, frequency_hz, magnitude, n_left,
    n_right) and ``skipped`` (peaks passed over as artefacts, with the reason)."""
    array, f = _record_flags(data, flags)
    return dict(_core.spikes(_arguments(f), array, time))


def cost(data, prediction, time=None, **flags):
    """``beamid cost``: the value of ``cost=`` for a prediction (a file, or an array at the data's step) against the
    data; returns a dict with value, residuals, amplitude_scale and the (A4) check."""
    array, f = _record_flags(data, flags)
    if isinstance(prediction, (str, os.PathLike)):
        f["prediction"], predicted = os.fspath(prediction), None
    else:
        f["prediction"], predicted = "<array>", np.asarray(prediction, dtype=float)
    return dict(_core.cost(_arguments(f), array, time, predicted))


class FitResult:
    """What ``beamid fit`` prints and reports, as values.

    estimates         {key: estimate}
    parameters        structured array: parameter, estimate, standard_error, start, lower, upper, status,
                      robust_standard_error, window_sd, window_standard_error (as the command's CSV)
    standard_errors   {key: formal standard error} (NaN at a bound)
    status            converged | max-evaluations | failed (with "-at-bound" when an estimate ends on a bound)
    termination, cost, evaluations, wall_time_s, covariance_status, correlation (array), identifiability (dict)
    modes             structured array: data_hz, data_damping_ratio, model_hz, model_damping_ratio at the estimate
    beam              the fitted beam's parameters (a dict; pass it as beam= to simulate the fit)
    model_output      the model's output at the estimate (array)
    records           per record of a joint fit: name, cost, status, weight, amplitude_scale
    """

    def __init__(self, raw):
        self._raw = raw
        rows = raw["parameters"]
        width = max([len(r["parameter"]) for r in rows] + [1])
        status_width = max([len(r["status"]) for r in rows] + [1])
        dtype = [("parameter", f"U{width}"), ("estimate", "f8"), ("standard_error", "f8"), ("start", "f8"),
                 ("lower", "f8"), ("upper", "f8"), ("status", f"U{status_width}"), ("robust_standard_error", "f8"),
                 ("window_sd", "f8"), ("window_standard_error", "f8")]
        self.parameters = np.array([tuple(r[name] for name, _ in dtype) for r in rows], dtype=dtype)
        self.estimates = dict(raw["estimates"])
        self.standard_errors = {r["parameter"]: r["standard_error"] for r in rows}
        for key in ("status", "termination", "cost", "evaluations", "wall_time_s", "covariance_status",
                    "correlation", "identifiability", "beam", "model_output", "records", "commit"):
            setattr(self, key, raw[key])
        mode_fields = [("data_hz", "f8"), ("data_damping_ratio", "f8"), ("model_hz", "f8"),
                       ("model_damping_ratio", "f8")]
        self.modes = np.array([tuple(m[name] for name, _ in mode_fields) for m in raw["modes"]], dtype=mode_fields)
        self.modes_status = raw["modes_status"]

    @property
    def ok(self):
        """Whether the fit produced estimates (status not "failed")."""
        return self.status != "failed"

    def __repr__(self):
        estimates = ", ".join(f"{k}={v:.6g}" for k, v in self.estimates.items())
        return f"FitResult({self.status}, cost={self.cost:.6g}, evaluations={self.evaluations}, {estimates})"


def fit(data, time=None, **flags):
    """``beamid fit``: fits the record(s) and returns a :class:`FitResult`. ``data`` is a file or an array (with
    ``sample_rate`` or ``time``); a 2-D array with ``channel=[1, 2]`` and ``sensor_x=[...]`` is a joint fit. Unlike
    the command, a failed fit is not an exception: its status says "failed"."""
    array, f = _record_flags(data, flags)
    with _beam_flag(f) as f:
        return FitResult(_core.fit(_arguments(f), array, time))


def crb(**flags):
    """``beamid crb``: the Cramér-Rao bound; a dict with parameters, value, crb_sd, crb_relative_sd (arrays in the
    order of ``estimate``), the noise sd assumed, the covariance of ln q and the method."""
    with _beam_flag(flags) as f:
        return dict(_core.crb(_arguments(f)))


def modal_id(data, time=None, **flags):
    """``beamid modal-id``: the modes of a free decay by the matrix pencil, a structured array (mode, frequency_hz,
    damping_ratio, amplitude, phase_rad)."""
    array, f = _record_flags(data, flags)
    r = _core.modal_id(_arguments(f), array, time)
    fields = ["frequency_hz", "damping_ratio", "amplitude", "phase_rad"]
    table = np.zeros(len(r["frequency_hz"]), dtype=[("mode", "i8")] + [(name, "f8") for name in fields])
    table["mode"] = np.arange(1, len(table) + 1)
    for name in fields:
        table[name] = r[name]
    return table


def read_record(path, **flags):
    """A record file as beamid reads it (CSV, .lvm, .npy, .mat, UFF 58, with the import flags: channel, units, start,
    duration, sample_rate, variable, time_variable, resample, resample_rate): a dict with values (array), dt_s, t0_s,
    unit, format, channel and notes."""
    return dict(_core.read_record(_arguments(dict(flags, data=path))))
