"""Type stubs of thermonav: names, types, units and defaults of every function and result."""

import os
from collections.abc import Iterable, Mapping, Sequence
from typing import Any, Literal

import numpy as np
from numpy.typing import NDArray

__version__: str

Path = str | os.PathLike[str]
Floats = NDArray[np.float64]
TauGrid = Literal["octave", "decade", "dense"] | Sequence[int]
DeviationKind = Literal["adev", "mdev", "hdev", "ohdev", "tdev", "totdev"]
ArMethod = Literal["yule-walker", "burg", "covariance", "modified-covariance"]
Family = Literal["irregular_ml", "ar_based", "acf_fit"]
Mode = Literal["zero-phase", "filtfilt"]
GaussMarkovSource = Literal["irregular_ml", "ar_based", "acf_fit", "gmwm"]
Triple = Sequence[float]

class ThermonavError(ValueError):
    """Bad data or settings: the message names the file, the line and what was expected."""

class Record(dict[str, Any]):
    """A result: a dict whose keys are also attributes; nested dictionaries are Records."""
    def __getattr__(self, name: str) -> Any: ...
    def to_dict(self) -> dict[str, Any]:
        """A plain dict (nested Records too); arrays stay NumPy arrays."""

class AllanResult(Record):
    """An Allan-family curve of rate samples.

    Always: ``kind`` (the deviation's name), ``sample_rate_hz`` (Hz), ``tau_s`` (averaging
    times, s), ``averaging_factor`` (m = tau / tau0), ``n_terms`` (terms averaged), and the
    deviation under the kind's name (``adev``, ``mdev``, ... in the data's unit; ``tdev`` in
    the data's unit times s). For ``kind="adev"`` (unless ``limits=False``) also ``confidence`` (level of the limits),
    ``ci_low`` and ``ci_high`` (Stable32-style limits of the deviation, data's unit),
    ``noise_type_alpha`` (identified power-law exponent per tau) and ``edf`` (equivalent
    degrees of freedom).
    """
    kind: str
    sample_rate_hz: float
    tau_s: Floats
    averaging_factor: NDArray[np.uintp]
    n_terms: NDArray[np.uintp]
    adev: Floats
    ci_low: Floats
    ci_high: Floats
    noise_type_alpha: NDArray[np.int32]
    edf: Floats
    confidence: float

class NoiseTerms(Record):
    """IEEE 952 terms, each None or a Record of ``value_si``/``unit_si``, ``value``/``unit``
    (deg/sqrt(h), deg/h, m/s/sqrt(h), mg, ...), ``tau_min_s``/``tau_max_s`` (the region read),
    ``points``, ``bound`` ("estimate" or "at_most") and ``ci_low``/``ci_high`` (+ ``_si``).
    ``absent`` maps each missing term to the reason the curve does not support it.
    """
    quantization: Record | None
    random_walk: Record | None
    bias_instability: Record | None
    rate_random_walk: Record | None
    rate_ramp: Record | None
    absent: dict[str, str]

class ArModel(Record):
    """``method``, ``order``, ``coefficients`` (c_1..c_p: x_k = sum c_i x_(k-i) + w_k, the
    statsmodels sign), ``coefficient_std_errors``, ``noise_variance`` (data's unit squared);
    with ``dt_s``: ``sample_interval_s`` and ``gauss_markov`` (the AR(1)-based model:
    ``status`` "model" with ``correlation_time_s`` (s), ``sigma`` (data's unit),
    ``ci95_correlation_time_s`` ([low, high] s, None for an unbounded side), or
    "no_equivalent" with ``reason``; and ``c1``).
    """
    method: str
    order: int
    coefficients: Floats
    coefficient_std_errors: Floats
    noise_variance: float
    sample_interval_s: float
    gauss_markov: Record

class GaussMarkovModel(Record):
    """``family``; ``status`` "model" with ``correlation_time_s`` (Tc, s), ``sigma`` (data's
    unit) and ``ci95_correlation_time_s`` ([low, high] s; None for an unbounded side), or
    "no_equivalent" with ``reason``. ``irregular_ml`` adds ``white_noise_density`` (data's
    unit times sqrt(s)), ``log_likelihood`` and ``n_samples``; ``ar_based`` adds ``c1``;
    ``ar_based`` and ``acf_fit`` add ``sample_interval_s`` (the median interval, s).
    """
    family: str
    status: Literal["model", "no_equivalent"]
    correlation_time_s: float
    sigma: float
    ci95_correlation_time_s: list[float | None]
    reason: str

class FirDesign(Record):
    """``sample_rate_hz``, ``cutoff_hz``, ``transition_hz`` (Hz), ``ripple_db`` (dB),
    ``num_taps``, ``beta`` (Kaiser), ``group_delay_s`` (s) and ``taps``."""
    sample_rate_hz: float
    cutoff_hz: float
    transition_hz: float
    ripple_db: float
    num_taps: int
    beta: float
    group_delay_s: float
    taps: Floats

class Decimated(Record):
    """``samples`` (the kept outputs), ``decimation_factor``, ``output_rate_hz`` (Hz),
    ``edge_samples_dropped`` (input samples left out at each end) and ``num_taps``."""
    samples: Floats
    decimation_factor: int
    output_rate_hz: float
    edge_samples_dropped: int
    num_taps: int

class GmwmFit(Record):
    """A GMWM fit of one channel, keys as one channel of ``thermonav gmwm --json`` plus its run.

    ``sample_rate_hz`` (Hz), ``model`` (as asked), ``interval_method``, ``bootstrap_replicates``;
    ``unit`` (the data's SI unit: "rad/s" or "m/s^2"), ``selected_model`` (e.g. "wn+gm"),
    ``wic`` (its wavelet information criterion); ``wavelet_variance`` with NumPy arrays
    ``scale_s`` (tau_j = 2^j / rate, s), ``variance_unit2``, ``ci_low_unit2``, ``ci_high_unit2``
    (the Haar wavelet variance and its 95 % chi-square limits, unit squared) and
    ``implied_unit2`` (the fitted model's, without the absent processes);
    ``reported_model`` (the selected model with the processes the record does not resolve left
    out and the Gauss-Markov processes at its edges merged); ``parameters``: the reported
    model's, name (unit in it, e.g. ``white_noise_density_rad_per_s_sqrt_s``,
    ``gm1_correlation_time_s``, ``gm1_sigma_rad_per_s``) to ``value``, ``ci_low``, ``ci_high``
    (95 % parametric bootstrap); ``merged``: ``process``, ``fitted_in``, ``into``
    ("white_noise" or "random_walk"), ``correlation_time_s``,
    ``correlation_time_sample_periods``, its sigma and density, ``reason``; ``absent``:
    ``process``, ``fitted_in``, ``objective_rise``, ``degrees_of_freedom``, ``p_value``,
    ``level``, ``reason``; ``candidates``: ``model``, ``wic``, ``objective``, best first;
    ``not_fitted``: ``model``, ``reason``.
    """
    sample_rate_hz: float
    model: str
    interval_method: str
    bootstrap_replicates: int
    unit: str
    selected_model: str
    wic: float
    reported_model: str
    wavelet_variance: Record
    parameters: dict[str, Record]
    merged: list[Record]
    absent: list[Record]
    candidates: list[Record]
    not_fitted: list[Record]

class Integration(Record):
    """A GNSS/INS run: the keys of ``thermonav integrate --json`` (without the file names) and
    the solution.

    ``filter`` ("ekf"/"ukf"), ``model`` (the model used: ``gauss_markov_source``,
    ``selection``, ``temperature_c`` in degrees Celsius, ``channels`` with
    ``bias_correlation_time_s`` (s), ``bias_sigma`` (rad/s or m/s^2), ``white_noise_density``),
    ``schedule`` (``kind`` "fixed" or "scheduled"), ``compensation`` (``status``), ``initial``
    ("dual_antenna_heading", "course_over_ground" or "reference"), ``covariance_rate_hz``,
    ``output_rate_hz`` (Hz), ``outages`` (``start_s``, ``end_s``), ``imu_samples``,
    ``duration_s`` (s), ``processing_time_s`` (wall time, s), ``real_time_factor``,
    ``innovations`` (per kind: ``offered``, ``rejected``, ``mean_nis``, ``fraction_nis_in_95``,
    ``rms_innovation_ned_m`` / ``_ned_m_s`` / ``_deg``) and ``final`` (the last epoch's
    ``sd_position_ned_m``, ``sd_attitude_ned_deg``, ``gyro_bias_deg_h``, ``accel_bias_mg``, ...).

    ``solution`` (and ``smoothed`` with ``smooth=True``, else None): NumPy arrays named like the
    columns of the CLI's solution CSV and its state file: ``t_ns`` (int64 ns), ``t_s``,
    ``lat_deg``, ``lon_deg``, ``h_m``, ``vn_m_s``, ``ve_m_s``, ``vd_m_s``, ``roll_deg``,
    ``pitch_deg``, ``yaw_deg``, ``sd_n_m`` .. ``sd_att_d_deg``, ``bgx_deg_h`` .. ``baz_mg``,
    ``sgx_ppm`` .. ``saz_ppm``, ``sd_bgx_deg_h`` .. ``sd_saz_ppm`` and ``in_outage`` (bool).
    ``notes``: what the CLI prints as notes on stderr.
    """
    filter: str
    model: Record
    schedule: Record
    compensation: Record
    initial: str
    covariance_rate_hz: float
    output_rate_hz: float
    outages: list[Record]
    imu_samples: int
    duration_s: float
    processing_time_s: float
    real_time_factor: float
    innovations: list[Record]
    solution: Record
    smoothed: Record | None
    notes: list[str]

class Evaluation(Record):
    """A tournament: the keys of ``thermonav evaluate``'s ``evaluation.json`` (without
    ``report_file``): ``operating_temperature_c``, ``gauss_markov_source``, ``filters``,
    ``outages``, ``models`` (per model and filter: ``label``, ``kind``, ``filter``, the metrics
    ``rms_north_m``, ``rms_east_m``, ``rms_horizontal_m``, ``rms_heading_deg``,
    ``max_drift_horizontal_m``, ..., ``per_outage``, ``errors_csv`` (None) and ``errors``: NumPy
    arrays ``outage``, ``t_s``, ``since_outage_start_s``, ``north_m``, ``east_m``,
    ``horizontal_m``, ``heading_deg`` as the CLI's per-model error CSVs, None for a failed run),
    ``excluded``, ``best``, ``best_by_filter``, ``significance``, ``oracle_gaps``.
    """
    operating_temperature_c: float
    gauss_markov_source: str
    filters: list[str]
    models: list[Record]
    excluded: list[Record]
    significance: Record

class ImuRecord(Record):
    """``source`` (file name), ``path``, ``kind`` ("rates" or "increments"), ``t_ns`` (int64
    ns, exact), ``t_s`` (s), the six channels in SI named like the canonical CSV
    (``gx_rad_s`` .. ``az_m_s2``, or ``dthx_rad`` .. ``dvz_m_s``) and ``temp_c`` (degrees
    Celsius) when recorded."""
    source: str
    path: str
    kind: Literal["rates", "increments"]
    t_ns: NDArray[np.int64]
    t_s: Floats
    gx_rad_s: Floats
    gy_rad_s: Floats
    gz_rad_s: Floats
    ax_m_s2: Floats
    ay_m_s2: Floats
    az_m_s2: Floats
    temp_c: Floats

class GnssRecord(Record):
    """``t_ns``, ``t_s``, ``lat_deg``, ``lon_deg``, ``h_m`` and the optional groups
    ``sd_n_m``/``sd_e_m``/``sd_u_m``, ``vn_m_s``/``ve_m_s``/``vd_m_s``, ``heading_deg``/
    ``sd_heading_deg``, NaN where a fix lacks them."""
    t_ns: NDArray[np.int64]
    t_s: Floats
    lat_deg: Floats
    lon_deg: Floats
    h_m: Floats

def allan(
    x: Floats,
    rate_hz: float,
    taus: TauGrid = "octave",
    kind: DeviationKind = "adev",
    confidence: float | None = None,
    limits: bool = True,
) -> AllanResult:
    """The Allan deviation of rate samples ``x`` (float64, any unit) taken at ``rate_hz`` (Hz).

    ``taus``: "octave" (m = 1, 2, 4, ...), "decade", "dense" (20 per decade) or explicit
    averaging factors. ``kind``: "adev" (overlapping, allantools ``oadev``), "mdev", "hdev",
    "ohdev", "tdev", "totdev" (each allantools' function with ``data_type='freq'``).
    ``confidence``: level of adev's limits (default 0.683); ``limits=False`` leaves out the
    limits, noise types and edf (the curve alone, 4-5x faster). As ``thermonav allan``.
    """

def noise_terms(
    x: Floats,
    rate_hz: float,
    sensor: str,
    taus: TauGrid = "octave",
    confidence: float | None = None,
) -> NoiseTerms:
    """The IEEE 952 noise terms of rate samples ``x`` (SI: rad/s or m/s^2) at ``rate_hz`` (Hz),
    each read from one region of the overlapping Allan curve that its slope supports.

    ``sensor``: "gyro", "accelerometer" or a channel name (gx .. az): picks the edge units
    (deg/sqrt(h), deg/h or m/s/sqrt(h), mg). As ``thermonav allan --json``'s ``terms``.
    """

def ar(
    x: Floats,
    method: ArMethod = "burg",
    order: int | Literal["auto"] = "auto",
    max_order: int | None = None,
    dt_s: float | None = None,
) -> ArModel:
    """An AR(p) model of ``x`` by ``method``; ``order`` fixed (1..100) or "auto" (BIC up to
    ``max_order``, default 10). With ``dt_s`` (the sampling interval, s) also the Gauss-Markov
    equivalent of the AR(1) fit by the same method (the paper's eqs 8-10). As ``thermonav ar``.
    """

def gauss_markov(
    t_s: Floats,
    x: Floats,
    family: Family = "irregular_ml",
    method: ArMethod = "burg",
) -> GaussMarkovModel:
    """A first-order Gauss-Markov model of samples ``x`` at strictly increasing times ``t_s`` (s).

    ``family``: "irregular_ml" (exact likelihood of Gauss-Markov plus white noise on the actual
    times, likelihood-ratio 95 % interval), "ar_based" (the AR(1) fit by ``method`` turned
    into Tc, at the median interval) or "acf_fit" (sigma^2 exp(-tau/Tc) fitted to the
    autocovariance up to its first zero crossing). ``characterize`` applies them to 0.5 s block
    means (irregular_ml) and to the filtered, decimated series (the other two).
    """

def kaiser_fir(
    fs_hz: float,
    cutoff_hz: float,
    transition_hz: float | None = None,
    ripple_db: float | None = None,
) -> FirDesign:
    """A Kaiser-window low-pass: sampling rate, pass-band edge and transition width (default
    1 Hz) in Hz, ripple and attenuation in dB (default 60). Tap for tap SciPy's
    ``kaiserord`` + ``firwin``. As ``thermonav fir``."""

def zero_phase(
    x: Floats,
    rate_hz: float,
    cutoff_hz: float,
    transition_hz: float | None = None,
    ripple_db: float | None = None,
    mode: Mode = "zero-phase",
) -> Floats:
    """``x`` sampled at ``rate_hz`` low-passed by :func:`kaiser_fir`'s filter without phase
    shift, same length: "zero-phase" (one pass, the delay removed; an even design gets one more
    tap) or "filtfilt" (forward and backward, odd extension of 3 x taps, as SciPy). As
    ``thermonav filter`` without decimation."""

def filtfilt(
    x: Floats,
    rate_hz: float,
    cutoff_hz: float,
    transition_hz: float | None = None,
    ripple_db: float | None = None,
) -> Floats:
    """:func:`zero_phase` with ``mode="filtfilt"``: SciPy's ``filtfilt`` with the Kaiser taps."""

def decimate(
    x: Floats,
    rate_hz: float,
    to_hz: float,
    cutoff_hz: float,
    transition_hz: float | None = None,
    ripple_db: float | None = None,
    mode: Mode = "zero-phase",
) -> Decimated:
    """``x`` low-passed and decimated from ``rate_hz`` to ``to_hz`` (an integer factor), only the
    outputs whose filter window lies inside the record kept. The stop band (cut-off + half the
    transition) must not pass ``to_hz``/2. As ``thermonav filter --decimate-to-hz``."""

def read_imu(path: Path, strict: bool = True) -> ImuRecord:
    """A canonical IMU CSV (any accepted unit, converted to SI once). ``strict``: refuse every
    defect (times going back, duplicates, NaN, g under m/s^2 names) with file and line."""

def read_gnss(path: Path, strict: bool = True) -> GnssRecord:
    """A canonical GNSS CSV; errors name the file and the line."""

def gmwm(
    x: Floats,
    rate_hz: float,
    model: str = "auto",
    sensor: str = "gyro",
    replicates: int = 0,
    seed: int = 2009,
) -> GmwmFit:
    """The GMWM fit of rate samples ``x`` (SI: rad/s or m/s^2) at ``rate_hz`` (Hz): the model
    whose Haar wavelet variance matches the data's, weighted by its inverse variance.

    ``model``: "auto" (every automatic candidate, the lowest WIC chosen) or one model such as
    "wn+gm", "wn+rw", "qn+wn+rw+2gm". ``sensor``: "gyro", "accelerometer" or a channel name
    (names the parameters' units). ``replicates`` (0, the default: no bootstrap and no
    intervals, candidates ranked by the asymptotic WIC; or 10 to 1000) and ``seed``: the
    parametric bootstrap of the intervals, on the CLI's named random streams. As one channel of
    ``thermonav gmwm FILE --json``.
    """

def integrate(
    imu: Path,
    gnss: Path,
    bank: Path | None = None,
    profile: Path | None = None,
    *,
    model_temperature_c: float | None = None,
    operating_temperature_c: float | None = None,
    select: Literal["nearest", "linear"] | None = None,
    model: GaussMarkovSource | None = None,
    filter: Literal["ekf", "ukf"] = "ekf",
    outages: str | None = None,
    lever_arm_m: Triple | None = None,
    baseline: Triple | None = None,
    initial_from: Path | None = None,
    covariance_rate_hz: float | None = None,
    output_rate_hz: float | None = None,
    velocity_sd_m_s: float | Sequence[float] | None = None,
    gate_probability: float | None = None,
    gate_window: int | None = None,
    max_imu_gap_s: float | None = None,
    process_noise_scale: float | None = None,
    bias_hypotheses: int | None = None,
    velocity: bool | None = None,
    heading: bool | None = None,
    schedule: bool = True,
    compensation: bool = True,
    smooth: bool = False,
) -> Integration:
    """The 21-state GNSS/INS filter on an IMU CSV and a GNSS CSV with the noise model of a
    ``bank`` (``bank.json``) or a sensor ``profile`` (TOML), as ``thermonav integrate`` (its
    ``--json`` and its solution files, to the last bit; the keywords are its options, and one
    left at ``None`` takes the library's default: nearest selection, the ``irregular_ml``
    family, no outages, a process noise scale of 1, ...). ``run_options`` in the result is
    the resolved run options, as ``evaluate`` reports its own.

    The model: at ``model_temperature_c`` (degrees Celsius, nearest entry, one model for the
    run), or at the operating temperature (``operating_temperature_c``, or the IMU file's mean
    temp_c) by ``select``, scheduled by the IMU's temp_c unless ``schedule=False``; the bank's
    bias(T) subtracted unless ``compensation=False``. ``outages``: "none", "START+DURATION,..."
    (s), "spread:N,DURATION" or "every:PERIOD,DURATION". ``lever_arm_m`` (m) and ``baseline``:
    body forward/right/down. ``initial_from``: start from this reference trajectory CSV
    instead of aligning. Rates in Hz, ``velocity_sd_m_s`` one value or north/east/down (m/s),
    ``max_imu_gap_s`` (s); ``gate_probability`` 1 turns the gate off. ``smooth``: also the RTS
    smoothed solution (EKF only). Errors name the file and line, or the keyword.
    """

def evaluate(
    imu: Path,
    gnss: Path,
    reference: Path,
    bank: Path | None = None,
    profile: Path | None = None,
    *,
    model_temperature_c: float | None = None,
    operating_temperature_c: float | None = None,
    model: GaussMarkovSource | None = None,
    filter: Literal["ekf", "ukf", "both"] = "both",
    outages: str | None = None,
    monte_carlo: int = 1,
    seed: int = 2009,
    lever_arm_m: Triple | None = None,
    baseline: Triple | None = None,
    initial_from: Path | None = None,
    covariance_rate_hz: float | None = None,
    velocity_sd_m_s: float | Sequence[float] | None = None,
    gate_probability: float | None = None,
    gate_window: int | None = None,
    max_imu_gap_s: float | None = None,
    process_noise_scale: float | None = None,
    bias_hypotheses: int | None = None,
    velocity: bool | None = None,
    heading: bool | None = None,
    schedule: bool = True,
    compensation: bool = True,
    datasheet: Path | None = None,
    truth: Path | None = None,
) -> Evaluation:
    """The temperature-model tournament (the paper's Steps 2-3) on one data set, as
    ``thermonav evaluate`` (its ``evaluation.json`` and per-model error CSVs, to the last bit):
    every candidate of the ``bank`` or ``profile`` through the same filter(s), INS-only errors
    against the ``reference`` trajectory inside the GNSS ``outages``, the ranking, and with
    ``monte_carlo`` > 1 its significance over outage starts shifted by the ``seed``'s named
    stream. ``datasheet``: a profile for the data-sheet candidate (default the ADIS16364 data
    sheet); ``truth``: a simulated survey's truth.json for the oracle candidates. Every
    candidate runs with ``integrate``'s run keywords (``process_noise_scale``,
    ``velocity_sd_m_s``, ``gate_probability``, ``gate_window``, ``covariance_rate_hz``,
    ``velocity``, ``heading``, ``lever_arm_m``, ``baseline``, ``max_imu_gap_s``,
    ``bias_hypotheses``, ``model``), reported resolved as ``run_options``; a keyword left at
    ``None`` takes the library's default (``outages``: spread:8,100). The candidates that
    stand at one temperature (interpolated, compensated entry, profile) stand at
    ``model_temperature_c`` or ``operating_temperature_c`` (one of them; default the IMU file's
    mean temp_c); ``initial_from``: every run starts from this trajectory CSV instead of the
    reference, as ``integrate``'s.
    """

class Bank:
    """A temperature model bank: what ``thermonav characterize`` writes to ``bank.json``."""

    notes: list[str]
    def __init__(self, text: str, notes: Iterable[str] = ...) -> None: ...
    @classmethod
    def load(cls, path: Path) -> Bank:
        """A bank file, read and checked value by value as the CLI reads it."""
    def to_json(self) -> str:
        """The JSON text, byte for byte the CLI's ``bank.json``."""
    def to_dict(self) -> dict[str, Any]:
        """The parsed document (a fresh copy)."""
    def save(self, path: Path) -> None:
        """Writes the JSON text to ``path``."""
    @property
    def version(self) -> int:
        """The bank's layout version."""
    @property
    def entries(self) -> list[Record]:
        """One Record per temperature (``temperature_c``, ``source``, ``preprocessing``,
        ``channels``: per channel ``unit``, ``allan``, ``ar``, ``gauss_markov`` with
        ``ar_based``, ``irregular_ml`` and ``acf_fit``)."""
    @property
    def temperatures_c(self) -> Floats:
        """The entries' temperatures, degrees Celsius."""
    @property
    def channels(self) -> list[str]:
        """The channel names (gx, gy, gz, ax, ay, az)."""
    @property
    def thermal(self) -> Record | None:
        """The thermal calibration (bias against temperature per channel), or None."""
    def to_pandas(self) -> Any:
        """A long pandas DataFrame: temperature_c, source, channel, unit, quantity, value."""

def characterize(
    records: Path | Mapping[str, Any] | Sequence[Path | Mapping[str, Any]],
    temperatures_c: Sequence[float] | None = None,
    *,
    cutoff_hz: float | None = None,
    transition_hz: float | None = None,
    modelling_rate_hz: float | None = None,
    chamber_latitude_deg: float | None = None,
    chamber_height_m: float | None = None,
) -> Bank:
    """A temperature model bank from static records, one per temperature, as
    ``thermonav characterize FILE... --out bank.json`` (equal to its file to the last bit).

    ``records``: IMU CSV paths, or mappings of arrays as :func:`read_imu` returns them (``t_ns``
    or ``t_s``, ``gx_rad_s`` .. ``az_m_s2``, optional ``temp_c`` and ``source``).
    ``temperatures_c``: one per record (degrees Celsius; default: each record's mean temp_c).
    Conditioning defaults as the CLI: cut-off 0.4 Hz, transition 0.2 Hz, modelling rate 1 Hz.
    The chamber site (default 45 degrees, 0 m) sets the gravity taken off az for the thermal
    calibration, made when the records span two or more temperatures.
    """

def load_bank(path: Path) -> Bank:
    """A bank file (``bank.json``), read and checked as the CLI reads it."""
