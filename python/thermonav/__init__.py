"""thermonav on NumPy arrays: the stochastic error models of MEMS inertial sensors.

The functions call the same Rust library code as the ``thermonav`` command line, with the
same defaults, so their results equal the CLI's JSON: the Allan family of deviations and the
IEEE 952 noise terms, AR models, the three Gauss-Markov families, the Kaiser low-pass, zero-phase
filtering and decimation, and the temperature model bank of ``thermonav characterize``.

Units are SI (rad/s, m/s^2, s, Hz, degrees Celsius) and every name carries its unit, as in the
CLI's JSON: ``tau_s``, ``adev``, ``coefficients``, ``correlation_time_s``, ``cutoff_hz``. Results
are :class:`Record` objects: dictionaries whose keys are also attributes (``r.tau_s`` is
``r["tau_s"]``), with NumPy arrays for the curves and series.

Bad data or settings raise :class:`ThermonavError` (a ``ValueError``) with the library's message
(for a file: its name, the line and what was expected); an array of another dtype than float64
raises ``TypeError``. Long calls release the GIL, so threads can run them in parallel.

Example::

    import thermonav
    imu = thermonav.read_imu("imu_20C.csv")
    curve = thermonav.allan(imu["gx_rad_s"], rate_hz=200.0)
    bank = thermonav.characterize(["imu_0C.csv", "imu_20C.csv"])
    run = thermonav.integrate("imu.csv", "gnss.csv", bank="bank.json", outages="60+20")
    print(run.final.sd_position_ned_m, run.solution.lat_deg[-1])
"""

from __future__ import annotations

import json
import os
from typing import Any

import numpy as np

from . import _native
from ._native import ThermonavError, __version__

__all__ = [
    "AllanResult",
    "ArModel",
    "Bank",
    "Decimated",
    "FirDesign",
    "GaussMarkovModel",
    "GmwmFit",
    "GnssRecord",
    "Evaluation",
    "ImuRecord",
    "Integration",
    "NoiseTerms",
    "Record",
    "ThermonavError",
    "__version__",
    "allan",
    "ar",
    "characterize",
    "decimate",
    "evaluate",
    "filtfilt",
    "gauss_markov",
    "gmwm",
    "integrate",
    "kaiser_fir",
    "load_bank",
    "noise_terms",
    "read_gnss",
    "read_imu",
    "zero_phase",
]


class Record(dict):
    """A result: a ``dict`` whose keys are also attributes; nested dictionaries are Records."""

    __slots__ = ()

    def __getattr__(self, name: str) -> Any:
        try:
            return self[name]
        except KeyError:
            raise AttributeError(f"{type(self).__name__} has no {name!r}") from None

    def __dir__(self) -> list[str]:
        return sorted(set(self.keys()) | set(dir(dict)))

    def to_dict(self) -> dict:
        """A plain ``dict`` (nested Records too); arrays stay NumPy arrays."""
        return {k: v.to_dict() if isinstance(v, Record) else v for k, v in self.items()}


class AllanResult(Record):
    """An Allan-family curve (see :func:`allan`)."""

    __slots__ = ()


class NoiseTerms(Record):
    """IEEE 952 noise terms (see :func:`noise_terms`)."""

    __slots__ = ()


class ArModel(Record):
    """An AR model (see :func:`ar`)."""

    __slots__ = ()


class GaussMarkovModel(Record):
    """A first-order Gauss-Markov model, or why there is none (see :func:`gauss_markov`)."""

    __slots__ = ()


class FirDesign(Record):
    """A Kaiser low-pass design (see :func:`kaiser_fir`)."""

    __slots__ = ()


class Decimated(Record):
    """A filtered, decimated series (see :func:`decimate`)."""

    __slots__ = ()


class GmwmFit(Record):
    """A GMWM fit of one channel (see :func:`gmwm`)."""

    __slots__ = ()


class Integration(Record):
    """A GNSS/INS run (see :func:`integrate`)."""

    __slots__ = ()


class Evaluation(Record):
    """A model tournament (see :func:`evaluate`)."""

    __slots__ = ()


class ImuRecord(Record):
    """An IMU record's columns (see :func:`read_imu`)."""

    __slots__ = ()


class GnssRecord(Record):
    """A GNSS record's columns (see :func:`read_gnss`)."""

    __slots__ = ()


def _wrap(value: Any, kind: type = Record) -> Any:
    """``value`` with every dict turned into a Record (the outermost into ``kind``)."""
    if isinstance(value, dict):
        return kind({k: _wrap(v) for k, v in value.items()})
    if isinstance(value, list):
        return [_wrap(v) for v in value]
    return value


def _samples(name: str, x: Any) -> np.ndarray:
    """``x`` as a 1-D float64 array; another dtype is a TypeError, not a silent cast."""
    array = x if isinstance(x, np.ndarray) else np.asarray(x)
    if array.dtype != np.float64:
        raise TypeError(f"{name}: expected a float64 array, got dtype {array.dtype}")
    if array.ndim != 1:
        raise ThermonavError(f"{name}: expected a 1-D array, got {array.ndim} dimensions")
    return array


def _given(**settings: Any) -> dict[str, Any]:
    """The settings that were given (None leaves the library's default)."""
    return {k: v for k, v in settings.items() if v is not None}


def allan(x, rate_hz, taus="octave", kind="adev", confidence=None, limits=True) -> AllanResult:
    """The Allan deviation (or another member of the family) of rate samples, as ``thermonav allan``."""
    settings = _given(taus=taus, kind=kind, confidence=confidence)
    result = _native.allan(_samples("x", x), float(rate_hz), limits=bool(limits), **settings)
    return AllanResult(result)


def noise_terms(x, rate_hz, sensor, taus="octave", confidence=None) -> NoiseTerms:
    """The IEEE 952 noise terms read off the overlapping Allan curve, as ``allan --json``'s ``terms``."""
    result = _native.noise_terms(
        _samples("x", x), float(rate_hz), sensor, **_given(taus=taus, confidence=confidence)
    )
    return _wrap(result, NoiseTerms)


def ar(x, method="burg", order="auto", max_order=None, dt_s=None) -> ArModel:
    """An AR(p) model, as ``thermonav ar``; with ``dt_s`` also the AR(1)-based Gauss-Markov model."""
    result = _native.ar(
        _samples("x", x), method, order, **_given(max_order=max_order, dt_s=dt_s)
    )
    return _wrap(result, ArModel)


def gauss_markov(t_s, x, family="irregular_ml", method="burg") -> GaussMarkovModel:
    """A first-order Gauss-Markov model of one channel, by one of the bank's three families."""
    result = _native.gauss_markov(_samples("t_s", t_s), _samples("x", x), family, method)
    return _wrap(result, GaussMarkovModel)


def kaiser_fir(fs_hz, cutoff_hz, transition_hz=None, ripple_db=None) -> FirDesign:
    """A Kaiser-window low-pass design, tap for tap SciPy's ``kaiserord`` + ``firwin``."""
    result = _native.kaiser_fir(
        float(fs_hz), float(cutoff_hz), **_given(transition_hz=transition_hz, ripple_db=ripple_db)
    )
    return FirDesign(result)


def zero_phase(x, rate_hz, cutoff_hz, transition_hz=None, ripple_db=None, mode="zero-phase"):
    """``x`` low-passed by the Kaiser filter without phase shift (same length)."""
    settings = _given(transition_hz=transition_hz, ripple_db=ripple_db, mode=mode)
    return _native.zero_phase(_samples("x", x), float(rate_hz), float(cutoff_hz), **settings)


def filtfilt(x, rate_hz, cutoff_hz, transition_hz=None, ripple_db=None):
    """:func:`zero_phase` with ``mode="filtfilt"``: SciPy's ``filtfilt`` with the Kaiser taps."""
    return zero_phase(x, rate_hz, cutoff_hz, transition_hz, ripple_db, mode="filtfilt")


def decimate(
    x, rate_hz, to_hz, cutoff_hz, transition_hz=None, ripple_db=None, mode="zero-phase"
) -> Decimated:
    """``x`` low-passed and decimated to ``to_hz``, as ``thermonav filter --decimate-to-hz``."""
    settings = _given(transition_hz=transition_hz, ripple_db=ripple_db, mode=mode)
    result = _native.decimate(
        _samples("x", x), float(rate_hz), float(to_hz), float(cutoff_hz), **settings
    )
    return Decimated(result)


def read_imu(path, strict=True) -> ImuRecord:
    """A canonical IMU CSV as arrays named like its columns, in SI."""
    return ImuRecord(_native.read_imu(os.fspath(path), strict))


def read_gnss(path, strict=True) -> GnssRecord:
    """A canonical GNSS CSV as arrays named like its columns."""
    return GnssRecord(_native.read_gnss(os.fspath(path), strict))


def gmwm(x, rate_hz, model="auto", sensor="gyro", replicates=None, seed=None) -> GmwmFit:
    """A composite noise model fitted to the Haar wavelet variance, as one channel of ``thermonav gmwm --json``.

    ``replicates``: parametric-bootstrap replicates (10 to 1000) for intervals and the WIC; by
    default none, as ``thermonav gmwm`` (the asymptotic WIC, no intervals). ``seed``: the
    bootstrap's seed (default: thermonav's). Both defaults are the library's own."""
    given = {k: int(v) for k, v in (("replicates", replicates), ("seed", seed)) if v is not None}
    result = _wrap(
        _native.gmwm(_samples("x", x), float(rate_hz), model, sensor, **given),
        GmwmFit,
    )
    wv = result["wavelet_variance"]
    for key in list(wv):
        wv[key] = np.asarray(wv[key], dtype=float)
    return result


def _path(path):
    return None if path is None else os.fspath(path)


def _triple(name, value):
    if value is None:
        return None
    values = [float(v) for v in value]
    if len(values) != 3:
        raise ThermonavError(f"{name}: expected three values, got {len(values)}")
    return values


def integrate(imu, gnss, bank=None, profile=None, **options) -> Integration:
    """The GNSS/INS filter on an IMU and a GNSS CSV with a bank's or a profile's noise model, as ``thermonav integrate``."""
    for key in ("lever_arm_m", "baseline"):
        options[key] = _triple(key, options.get(key))
    if options.get("velocity_sd_m_s") is not None:
        options["velocity_sd_m_s"] = [float(v) for v in np.atleast_1d(options["velocity_sd_m_s"])]
    if options.get("initial_from") is not None:
        options["initial_from"] = os.fspath(options["initial_from"])
    result = _native.integrate(os.fspath(imu), os.fspath(gnss), _path(bank), _path(profile), **options)
    return _wrap(result, Integration)


def evaluate(imu, gnss, reference, bank=None, profile=None, **options) -> Evaluation:
    """The temperature-model tournament on one data set, as ``thermonav evaluate`` (its ``evaluation.json``)."""
    for key in ("lever_arm_m", "baseline"):
        options[key] = _triple(key, options.get(key))
    for key in ("datasheet", "truth"):
        options[key] = _path(options.get(key))
    result = _native.evaluate(
        os.fspath(imu), os.fspath(gnss), os.fspath(reference), _path(bank), _path(profile), **options
    )
    return _wrap(result, Evaluation)


class Bank:
    """A temperature model bank: what ``thermonav characterize`` writes to ``bank.json``.

    ``to_json()`` is the CLI's file byte for byte; ``to_dict()`` the parsed document; the
    attributes read it: ``entries`` (one Record per temperature), ``temperatures_c``,
    ``channels``, ``thermal`` (the thermal calibration or None) and ``notes`` (what the CLI
    would print on stderr, e.g. why there is no thermal calibration).
    """

    def __init__(self, text: str, notes: list[str] | tuple[str, ...] = ()):
        self._text = text
        self._document = json.loads(text)
        self.notes = list(notes)

    @classmethod
    def load(cls, path) -> "Bank":
        """A bank file, read and checked value by value as the CLI reads it."""
        return cls(_native.load_bank(os.fspath(path)))

    def to_json(self) -> str:
        """The JSON text, as ``thermonav characterize`` writes ``bank.json``."""
        return self._text

    def to_dict(self) -> dict:
        """The parsed document (a fresh copy)."""
        return json.loads(self._text)

    def save(self, path) -> None:
        """Writes the JSON text to ``path``."""
        with open(path, "w", encoding="utf-8") as out:
            out.write(self._text)

    @property
    def version(self) -> int:
        """The bank's layout version."""
        return self._document["version"]

    @property
    def entries(self) -> list[Record]:
        """One Record per temperature, in increasing temperature."""
        return [_wrap(e) for e in self._document["entries"]]

    @property
    def temperatures_c(self) -> np.ndarray:
        """The entries' temperatures, degrees Celsius."""
        return np.array([e["temperature_c"] for e in self._document["entries"]], dtype=float)

    @property
    def channels(self) -> list[str]:
        """The channel names (gx, gy, gz, ax, ay, az)."""
        return list(self._document["entries"][0]["channels"])

    @property
    def thermal(self) -> Record | None:
        """The thermal calibration, or None when the records span fewer than two temperatures."""
        thermal = self._document.get("thermal")
        return None if thermal is None else _wrap(thermal)

    def to_pandas(self):
        """A long table: one row per temperature, channel and scalar quantity (needs pandas).

        Columns: ``temperature_c``, ``source``, ``channel``, ``unit`` (the channel's SI unit),
        ``quantity`` (the path in the document, e.g. ``gauss_markov.irregular_ml.correlation_time_s``)
        and ``value``. The Allan curves (``allan.tau_s``, ``allan.adev``) are left to ``to_dict``.
        """
        import pandas as pd

        rows = []
        for entry in self._document["entries"]:
            for channel, model in entry["channels"].items():
                for quantity, value in _scalars(model, ""):
                    rows.append(
                        {
                            "temperature_c": entry["temperature_c"],
                            "source": entry["source"],
                            "channel": channel,
                            "unit": model.get("unit"),
                            "quantity": quantity,
                            "value": value,
                        }
                    )
        return pd.DataFrame(rows)

    def __repr__(self) -> str:
        temperatures = ", ".join(f"{t:g}" for t in self.temperatures_c)
        thermal = "with" if self.thermal is not None else "without"
        return f"Bank({len(self._document['entries'])} entries at {temperatures} °C, {thermal} thermal calibration)"

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Bank) and self._text == other._text

    __hash__ = None


def _scalars(value: Any, prefix: str):
    """(path, number) for every number under ``value``, the Allan curves left out."""
    if isinstance(value, dict):
        for key, item in value.items():
            path = f"{prefix}.{key}" if prefix else key
            if path in ("allan.tau_s", "allan.adev"):
                continue
            yield from _scalars(item, path)
    elif isinstance(value, list):
        for k, item in enumerate(value):
            yield from _scalars(item, f"{prefix}.{k}")
    elif isinstance(value, (int, float)) and not isinstance(value, bool):
        yield prefix, float(value)


def characterize(
    records,
    temperatures_c=None,
    *,
    cutoff_hz=None,
    transition_hz=None,
    modelling_rate_hz=None,
    chamber_latitude_deg=None,
    chamber_height_m=None,
) -> Bank:
    """A temperature model bank from static records, as ``thermonav characterize FILE...``."""
    if isinstance(records, (str, os.PathLike, dict)):
        records = [records]
    records = [r if isinstance(r, dict) else os.fspath(r) for r in records]
    settings = _given(
        cutoff_hz=cutoff_hz,
        transition_hz=transition_hz,
        modelling_rate_hz=modelling_rate_hz,
        chamber_latitude_deg=chamber_latitude_deg,
        chamber_height_m=chamber_height_m,
    )
    temperatures = None if temperatures_c is None else [float(t) for t in temperatures_c]
    text, notes = _native.characterize(records, temperatures, **settings)
    return Bank(text, notes)


def load_bank(path) -> Bank:
    """A bank file (``bank.json``), read and checked as the CLI reads it."""
    return Bank.load(path)
