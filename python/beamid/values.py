"""What the package's functions return: one dataclass per computation, with the units in the field names and NumPy
arrays (structured arrays for tables) inside. Each is built from the core's raw values by ``_from_core``; each also
answers ``result["field"]`` and ``to_dict()``, so that scripts written when these were dicts keep working; the tabular
ones have ``to_pandas()`` (pandas is optional: Debian's python3-pandas).
"""
import dataclasses
import typing

import numpy as np


def _pandas():
    try:
        import pandas
    except ImportError as error:
        raise ImportError("to_pandas needs pandas (Debian: apt install python3-pandas); the same table is a NumPy "
                          "structured array in the result") from error
    return pandas


def _table(rows, fields):
    """A structured array from a list of dicts: text fields as wide as their longest value."""
    dtype = []
    for name, kind in fields:
        if kind == "U":
            kind = f"U{max([len(str(r[name])) for r in rows] + [1])}"
        dtype.append((name, kind))
    return np.array([tuple(r[name] for name, _ in dtype) for r in rows], dtype=dtype)


class _Fields:
    """Mapping-style access to a dataclass's fields (``r["value"]``), for scripts written against the dicts."""

    def __getitem__(self, name):
        if name not in self.keys():
            raise KeyError(name)
        return getattr(self, name)

    def keys(self):
        return [f.name for f in dataclasses.fields(self)]

    def to_dict(self):
        return {name: getattr(self, name) for name in self.keys()}

    @classmethod
    def _from_core(cls, raw):
        """The value from the core's dict of the same field names (a class whose fields differ overrides this)."""
        return cls(**{f.name: raw[f.name] for f in dataclasses.fields(cls)})


_SPIKE_FIELDS = [("bin", "i8"), ("frequency_hz", "f8"), ("magnitude", "f8"), ("n_left", "i8"), ("n_right", "i8"),
                 ("subbin_frequency_hz", "f8"), ("decay_rate_1_s", "f8"), ("measured_frequency_hz", "f8"),
                 ("measured_uncertainty_hz", "f8")]


@dataclasses.dataclass(repr=False)
class Spikes(_Fields):
    """``beamid spikes``: the picked spikes and the peaks passed over.

    picks      structured array, ascending in frequency: bin, frequency_hz (the bin's), magnitude, n_left, n_right,
               subbin_frequency_hz and decay_rate_1_s (the three-bin estimate of the peak; NaN on Welch's average),
               measured_frequency_hz and measured_uncertainty_hz (the matrix pencil's mode with its uncertainty, as
               modal_id, fit and real report a measured frequency; NaN where none was measured)
    skipped    the same columns and ``reason``: peaks dropped as artefacts (harmonics, leakage), with why
    requested  how many spikes were asked for
    df_hz      the spectrum's bin width
    """
    picks: np.ndarray
    skipped: np.ndarray
    requested: int
    df_hz: float

    @classmethod
    def _from_core(cls, raw):
        return cls(picks=_table(raw["picks"], _SPIKE_FIELDS), skipped=_table(raw["skipped"], _SPIKE_FIELDS +
                                                                               [("reason", "U")]),
                   requested=raw["requested"], df_hz=raw["df_hz"])

    def to_pandas(self):
        """The picks as a pandas DataFrame."""
        return _pandas().DataFrame(self.picks)

    def __repr__(self):
        found = ", ".join(f"{f:.6g}" for f in self.picks["frequency_hz"])
        return f"Spikes({len(self.picks)} of {self.requested} Hz: [{found}], {len(self.skipped)} skipped)"


@dataclasses.dataclass(repr=False)
class CostValue(_Fields):
    """``beamid cost``: one cost's value for a prediction against the data.

    value            the cost
    residuals        its residual vector (the samples' or the spikes' misfits, as the cost defines them)
    amplitude_scale  the fitted amplitude factor (unknown_amplitude), else 1
    a4               "ok" or the spike costs' (A4) condition in words
    """
    value: float
    residuals: np.ndarray
    amplitude_scale: float
    a4: str

    def __repr__(self):
        return f"CostValue({self.value:.6g}, {len(self.residuals)} residuals, a4={self.a4!r})"


@dataclasses.dataclass(repr=False)
class Design(_Fields):
    """``beamid design``: every candidate experiment, best first, by a criterion of the Fisher information.

    parameters       the parameters of interest, in the order of relative_sd's columns
    criterion_name   "D", "A" or the key ranked by
    noise_model      the noise's colour
    sensors_x_m      per candidate, the positions of its channels (an array each)
    force_x_m, pulse_width_s, dt_s, samples   per candidate, its other choices
    criterion        per candidate, the criterion's value (relative: 0.01 is 1 %; NaN without a bound)
    relative_sd      candidates x parameters: the bound on each relative sd
    status           per candidate, "ok" or why it has no bound (ranked last)
    """
    parameters: list
    criterion_name: str
    noise_model: str
    sensors_x_m: list
    force_x_m: np.ndarray
    pulse_width_s: np.ndarray
    dt_s: np.ndarray
    samples: np.ndarray
    criterion: np.ndarray
    relative_sd: np.ndarray
    status: list

    def to_pandas(self):
        """One row per candidate, the sensors as a tuple, a column per parameter's relative sd."""
        pandas = _pandas()
        frame = pandas.DataFrame({"sensors_x_m": [tuple(s) for s in self.sensors_x_m], "force_x_m": self.force_x_m,
                                  "pulse_width_s": self.pulse_width_s, "dt_s": self.dt_s,
                                  "samples": self.samples.astype(int), "criterion": self.criterion})
        for k, key in enumerate(self.parameters):
            frame["relative_sd_" + key] = self.relative_sd[:, k]
        frame["status"] = self.status
        return frame

    def __repr__(self):
        return (f"Design({len(self.status)} candidates by {self.criterion_name}; best {self.criterion[0]:.4g} with "
                f"sensors at {list(self.sensors_x_m[0])} m)")


@dataclasses.dataclass(repr=False)
class CramerRao(_Fields):
    """``beamid crb``: the Cramér-Rao bound at the given parameters.

    parameters        the estimated keys, in the order of ``estimate``
    value             their values
    crb_sd            the bound on each one's standard deviation, in its unit
    crb_relative_sd   the same relative to the value
    noise_sd          the noise standard deviation assumed
    covariance        the bound's covariance of ln q
    method, rcond     how it was computed and the Fisher matrix's reciprocal condition
    """
    parameters: list
    value: np.ndarray
    crb_sd: np.ndarray
    crb_relative_sd: np.ndarray
    noise_sd: float
    covariance: np.ndarray
    method: str
    rcond: float

    def to_pandas(self):
        """One row per parameter: value, crb_sd, crb_relative_sd."""
        return _pandas().DataFrame({"value": self.value, "crb_sd": self.crb_sd,
                                    "crb_relative_sd": self.crb_relative_sd}, index=list(self.parameters))

    def __repr__(self):
        bounds = ", ".join(f"{k}: {r:.3g}" for k, r in zip(self.parameters, self.crb_relative_sd))
        return f"CramerRao(relative sd {bounds}; noise sd {self.noise_sd:.3g})"


@dataclasses.dataclass(repr=False)
class System(_Fields):
    """``beamid system``: the Galerkin system M w'' + C w' + K w = load f(t), sensor' w, and the experiment.

    M, C, K                       mass, damping and stiffness matrices (symmetric)
    load, sensor, w0              the force's load vector, the sensor's row, the initial displacement
    beam, length_m, elements      the beam's name, its length and the number of elements N
    amplitude_N, pulse_width_s    the excitation; derivative: 0, 1 or 2 for displacement, velocity, acceleration
    dt_s, samples                 the sampling
    """
    M: np.ndarray
    C: np.ndarray
    K: np.ndarray
    load: np.ndarray
    sensor: np.ndarray
    w0: np.ndarray
    beam: str
    length_m: float
    elements: int
    amplitude_N: float
    pulse_width_s: float
    derivative: int
    dt_s: float
    samples: int

    def __repr__(self):
        return f"System({self.beam}, N = {self.elements}, {self.M.shape[0]} unknowns)"


@dataclasses.dataclass(repr=False)
class Record(_Fields):
    """A record as beamid reads it: ``values[i]`` at ``t0_s + i * dt_s``, in ``unit``.

    path, format, channel   where it came from (file, reader, column or variable)
    notes                   what the reader did (resampling, a window, a unit conversion)
    """
    values: np.ndarray
    dt_s: float
    t0_s: float
    unit: str
    format: str
    channel: str
    path: str
    notes: str

    @property
    def time_s(self) -> np.ndarray:
        """The samples' times, s."""
        return self.t0_s + self.dt_s * np.arange(len(self.values))

    @property
    def sample_rate_hz(self) -> float:
        return 1.0 / self.dt_s

    def __repr__(self):
        return (f"Record({self.path}, {len(self.values)} samples at {self.sample_rate_hz:.6g} Hz, {self.unit}, "
                f"channel {self.channel!r})")


_MODE_FIELDS = [("data_hz", "f8"), ("data_damping_ratio", "f8"), ("model_hz", "f8"), ("model_damping_ratio", "f8"),
                ("data_uncertainty_hz", "f8"), ("data_decay_1_s", "f8"), ("data_decay_uncertainty_1_s", "f8"),
                ("model_decay_1_s", "f8")]
_PARAMETER_FIELDS = [("parameter", "U"), ("estimate", "f8"), ("standard_error", "f8"), ("start", "f8"),
                     ("lower", "f8"), ("upper", "f8"), ("status", "U"), ("robust_standard_error", "f8"),
                     ("window_sd", "f8"), ("window_standard_error", "f8")]


@dataclasses.dataclass(repr=False)
class FitResult(_Fields):
    """What ``beamid fit`` prints and reports, as values.

    estimates         {key: estimate}
    parameters        structured array: parameter, estimate, standard_error, start, lower, upper, status,
                      robust_standard_error, window_sd, window_standard_error (as the command's CSV)
    standard_errors   {key: formal standard error} (NaN at a bound)
    status            converged | max-evaluations | failed (with "-at-bound" when an estimate ends on a bound)
    termination, cost, evaluations, wall_time_s, covariance_status, correlation (array), identifiability (dict)
    sandwich_status   "ok", or why robust_standard_error is NaN where standard_error is not (a residual of leverage
                      above 0.5, or an estimate whose sandwich rests on fewer than 10 residuals' worth)
    modes             structured array: data_hz, data_damping_ratio, model_hz, model_damping_ratio at the estimate,
                      data_uncertainty_hz (the measured frequency's uncertainty, as modal-id's), data_decay_1_s,
                      data_decay_uncertainty_1_s and model_decay_1_s (decay rates -Re(lambda), what the damping
                      mismatch note compares)
    modes_status      "ok" when the record's modes could be compared with the model's (the table above is then
                      filled), else why not; whether the estimate reproduces them is said in messages, not here
    beam              the fitted beam's parameters (a dict; pass it as beam= to simulate the fit)
    model_output      the model's output at the estimate (array)
    records           per record of a joint fit: name, cost, status, weight, amplitude_scale
    a4                "ok" or the spike costs' (A4) condition in words (the spike counts of model and data differ)
    profiles          profile=KEYS' profile-likelihood intervals, by key: estimate, standard_error, interval_68 and
                      interval_95 ((lower, upper), NaN on a side the data do not close within the bounds),
                      open_below, open_above, values and statistic (the profile: (S(v) - S_min) / s^2 at each value,
                      chi^2 with one degree of freedom); {} without profile
    posterior         posterior=True's samples (least-squares costs), a dict: keys; parameters by key (mean, sd, median,
                      interval_95, rhat, effective_samples); draws (every kept draw, a column per key); correlation;
                      status ("converged" or why not); acceptance; evaluations; log_evidence_laplace and
                      log_evidence_sampled (value, standard error); None without posterior
    messages          what the command line would say on stderr: a failure, estimates on a bound, (A4), weak
                      identifiability, a record's frequency that changes with the amplitude, modes or damping the
                      estimate does not reproduce (beyond 2 %, or 10 of the record's uncertainties), a window that
                      correlates the DFT bins the standard errors take as independent, a coarsely quantised record;
                      fit() also issues each as a warning
    """
    estimates: dict
    parameters: np.ndarray
    standard_errors: dict
    status: str
    termination: str
    cost: float
    evaluations: int
    wall_time_s: float
    covariance_status: str
    sandwich_status: str
    correlation: np.ndarray
    identifiability: dict
    modes: np.ndarray
    modes_status: str
    beam: dict
    model_output: np.ndarray
    records: list
    a4: str
    profiles: dict
    posterior: typing.Optional[dict]
    messages: list
    commit: str

    @classmethod
    def _from_core(cls, raw):
        rows = raw["parameters"]
        direct = {f.name: raw[f.name] for f in dataclasses.fields(cls)
                  if f.name not in ("parameters", "standard_errors", "modes", "estimates", "messages", "profiles")}
        return cls(parameters=_table(rows, _PARAMETER_FIELDS), estimates=dict(raw["estimates"]),
                   standard_errors={r["parameter"]: r["standard_error"] for r in rows},
                   modes=_table(raw["modes"], _MODE_FIELDS), messages=list(raw["messages"]),
                   profiles={key: dict(q) for key, q in raw["profiles"].items()}, **direct)

    @property
    def ok(self) -> bool:
        """Whether the fit produced estimates (status not "failed")."""
        return self.status != "failed"

    def to_pandas(self):
        """The parameters table as a pandas DataFrame, indexed by parameter. The other tables are structured arrays,
        which pandas.DataFrame takes as they are."""
        return _pandas().DataFrame(self.parameters).set_index("parameter")

    def __repr__(self):
        estimates = ", ".join(f"{k}={v:.6g}" for k, v in self.estimates.items())
        return f"FitResult({self.status}, cost={self.cost:.6g}, evaluations={self.evaluations}, {estimates})"
