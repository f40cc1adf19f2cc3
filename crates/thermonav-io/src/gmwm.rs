//! A GMWM fit as JSON documents give it (`thermonav gmwm --json`'s channels, the Python
//! package's `gmwm`): the Haar wavelet variance with its limits and the selected model's
//! value, the parameters with their bootstrap intervals (units in their names), and the
//! candidates ranked by WIC.

use serde::Serialize;
use std::collections::BTreeMap;
use thermonav::imu::Sensor;
use thermonav::stoch::gmwm::{
    AbsentProcess, BootstrapSettings, GmwmError, GmwmEstimate, MergedInto, MergedProcess,
    ModelSelection, ModelSpec, ModelSpecError, ParameterEstimate, RESOLUTION_LEVEL, ResolvedModel,
    WHITE_MERGE_SAMPLE_PERIODS, auto_candidates, resolve_selection, select_model,
};
use thermonav::stoch::wavelet_variance::{
    WaveletVariance, WaveletVarianceError, haar_wavelet_variance,
};

/// How the parameter intervals are made, in words.
pub const INTERVAL_METHOD: &str =
    "95 % parametric bootstrap: Wald on the log scale, spread from the interquartile range";

/// What the fit reports without a bootstrap.
pub const NO_INTERVALS: &str = "none (no bootstrap; --replicates N, 10 to 1000, for parametric-bootstrap intervals and WIC): candidates ranked by the asymptotic WIC, objective + 2 x parameters";

/// Bootstrap replicates of `gmwm` and `thermonav.gmwm` unless asked: none. The bootstrap
/// refits the whole record once per replicate (100 took 93 s on 10^6 samples of six channels on
/// two cores); the asymptotic WIC ranks the candidates as the bootstrap did on the ADIS16405
/// records (see `rank_by_asymptotic_wic`).
pub const DEFAULT_REPLICATES: usize = 0;

/// The interval method of a fit with `replicates` bootstrap replicates.
pub fn interval_method(replicates: usize) -> &'static str {
    match replicates {
        0 => NO_INTERVALS,
        _ => INTERVAL_METHOD,
    }
}

/// One channel's fit.
#[derive(Debug, Serialize)]
pub struct GmwmChannelJson {
    /// The selected model.
    #[serde(flatten)]
    pub selected: SelectedJson,
    /// The composite reported: the selected one without the processes the record does not
    /// resolve (`absent`), its Gauss-Markov processes at the record's edges merged (`merged`).
    pub reported_model: String,
    /// The wavelet variance and the model's (the composite fitted without the absent
    /// processes; merging does not change it).
    pub wavelet_variance: WaveletVarianceJson,
    /// Parameter name (unit in it) → value and interval, of the reported composite.
    pub parameters: BTreeMap<String, ParameterJson>,
    /// Gauss-Markov processes of the fit reported merged into the white noise (Tc of a few
    /// sample periods) or into the random walk (Tc beyond the record).
    pub merged: Vec<MergedJson>,
    /// Processes of the selected composite the record does not resolve, left out, with why.
    pub absent: Vec<AbsentJson>,
    /// Every candidate, best (lowest WIC) first.
    pub candidates: Vec<CandidateJson>,
    /// Candidates that could not be fitted, with why.
    pub not_fitted: Vec<NotFittedJson>,
}

/// A Gauss-Markov process merged into another process.
#[derive(Debug, Serialize)]
pub struct MergedJson {
    /// The process in the fitted composite (`gm1`, ...).
    pub process: String,
    /// The composite it was fitted in.
    pub fitted_in: String,
    /// `white_noise` or `random_walk`.
    pub into: MergedInto,
    /// Its correlation time, s.
    pub correlation_time_s: f64,
    /// Its correlation time in sample periods.
    pub correlation_time_sample_periods: f64,
    /// Its σ (`sigma_rad_per_s`, `sigma_m_per_s2`) and what it amounts to alone, the white-noise
    /// density or the random-walk coefficient (named as the parameters are); the merged
    /// parameter is the root of the sum of the squares.
    #[serde(flatten)]
    pub values: BTreeMap<String, f64>,
    /// Why, in words.
    pub reason: String,
}

/// A process left out of the selected composite.
#[derive(Debug, Serialize)]
pub struct AbsentJson {
    /// The process (`qn`, `rw`, `dr`, `gm`).
    pub process: &'static str,
    /// The composite it was fitted in.
    pub fitted_in: String,
    /// How much leaving it out raised the GMWM objective (the others refitted).
    pub objective_rise: f64,
    /// Its parameters: the chi-square degrees of freedom of the test.
    pub degrees_of_freedom: usize,
    /// P(chi-square > rise); the process is absent when it is at least `level`.
    pub p_value: f64,
    /// The significance level a process must reach.
    pub level: f64,
    /// Why, in words.
    pub reason: String,
}

/// A candidate left out.
#[derive(Debug, Serialize)]
pub struct NotFittedJson {
    /// Its name.
    pub model: String,
    /// Why it could not be fitted.
    pub reason: String,
}

/// The selected model.
#[derive(Debug, Serialize)]
pub struct SelectedJson {
    /// The data's SI unit.
    pub unit: &'static str,
    /// Its name (e.g. `wn+gm`).
    pub selected_model: String,
    /// Its wavelet information criterion.
    pub wic: f64,
}

/// The Haar wavelet variance per scale, in the data's unit squared.
#[derive(Debug, Serialize)]
pub struct WaveletVarianceJson {
    /// Scales τ_j = 2^j / rate, s.
    pub scale_s: Vec<f64>,
    /// Estimated wavelet variance.
    pub variance_unit2: Vec<f64>,
    /// Lower limit.
    pub ci_low_unit2: Vec<f64>,
    /// Upper limit.
    pub ci_high_unit2: Vec<f64>,
    /// The selected model's wavelet variance.
    pub implied_unit2: Vec<f64>,
}

impl WaveletVarianceJson {
    /// Estimate, limits and the model's value at scale j.
    pub fn row(&self, j: usize) -> [f64; 4] {
        [
            self.variance_unit2[j],
            self.ci_low_unit2[j],
            self.ci_high_unit2[j],
            self.implied_unit2[j],
        ]
    }
}

/// A parameter with its interval.
#[derive(Debug, Serialize)]
pub struct ParameterJson {
    /// Estimate.
    pub value: f64,
    /// Lower limit (null without a bootstrap).
    pub ci_low: Option<f64>,
    /// Upper limit (null without a bootstrap).
    pub ci_high: Option<f64>,
}

/// A candidate's figures.
#[derive(Debug, Serialize)]
pub struct CandidateJson {
    /// Its name.
    pub model: String,
    /// Wavelet information criterion.
    pub wic: f64,
    /// Weighted least-squares objective at the fit.
    pub objective: f64,
}

/// Why a channel cannot be fitted.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ChannelFitError {
    /// No wavelet variance (too short a record, a bad rate).
    #[error(transparent)]
    WaveletVariance(#[from] WaveletVarianceError),
    /// No fit.
    #[error(transparent)]
    Fit(#[from] GmwmError),
}

/// The candidates of a model name: the automatic list for `auto` (any case), else the one
/// model named (`wn+gm`, `qn+wn+rw`, ...).
///
/// # Errors
/// A name that is not a model.
pub fn candidates_of(model: &str) -> Result<Vec<ModelSpec>, ModelSpecError> {
    if model.eq_ignore_ascii_case("auto") {
        return Ok(auto_candidates());
    }
    model.parse::<ModelSpec>().map(|spec| vec![spec])
}

/// The fit of rate samples `y` at `rate_hz` from `sensor`: the wavelet variance, the
/// candidates ranked by WIC, the selected fit.
///
/// # Errors
/// Those of [`haar_wavelet_variance`] and [`select_model`].
pub fn gmwm_channel_json(
    y: &[f64],
    rate_hz: f64,
    sensor: Sensor,
    (candidates, settings): (&[ModelSpec], BootstrapSettings),
) -> Result<GmwmChannelJson, ChannelFitError> {
    let wv = haar_wavelet_variance(y, rate_hz, None, settings.confidence)?;
    let selection = select_model(&wv, candidates, settings)?;
    let resolved = resolve_selection(&wv, &selection, settings)?;
    Ok(ranked_json(&wv, (&selection, &resolved), sensor))
}

fn ranked_json(
    wv: &WaveletVariance,
    (selection, resolved): (&ModelSelection, &ResolvedModel),
    sensor: Sensor,
) -> GmwmChannelJson {
    let ranked = &selection.ranked;
    let best = &ranked[0];
    let reported = &resolved.estimate;
    GmwmChannelJson {
        selected: SelectedJson {
            unit: sensor_unit(sensor),
            selected_model: best.fit.model.to_string(),
            wic: best.wic,
        },
        reported_model: reported.reported_model.to_string(),
        wavelet_variance: wavelet_variance_json(wv, reported),
        parameters: parameters_json(reported, sensor),
        merged: (reported.merged.iter())
            .map(|m| merged_json(m, reported, sensor))
            .collect(),
        absent: resolved.absent.iter().map(absent_json).collect(),
        candidates: ranked.iter().map(candidate_json).collect(),
        not_fitted: selection
            .not_fitted
            .iter()
            .map(|(model, reason)| NotFittedJson {
                model: model.to_string(),
                reason: reason.to_string(),
            })
            .collect(),
    }
}

/// The SI unit of a sensor's rate samples.
fn sensor_unit(sensor: Sensor) -> &'static str {
    match sensor {
        Sensor::Gyro => "rad/s",
        Sensor::Accelerometer => "m/s^2",
    }
}

fn wavelet_variance_json(wv: &WaveletVariance, best: &GmwmEstimate) -> WaveletVarianceJson {
    WaveletVarianceJson {
        scale_s: wv.scale_s.clone(),
        variance_unit2: wv.variance.clone(),
        ci_low_unit2: wv.ci_low.clone(),
        ci_high_unit2: wv.ci_high.clone(),
        implied_unit2: best.fit.implied_variance.clone(),
    }
}

/// The sensor's unit in parameter names.
fn name_unit(sensor: Sensor) -> &'static str {
    match sensor {
        Sensor::Gyro => "rad_per_s",
        Sensor::Accelerometer => "m_per_s2",
    }
}

/// The reported parameters keyed by name, the library's `unit` replaced by the sensor's unit.
fn parameters_json(best: &GmwmEstimate, sensor: Sensor) -> BTreeMap<String, ParameterJson> {
    let unit = name_unit(sensor);
    let entry = |p: &ParameterEstimate| (p.kind.name().replace("unit", unit), parameter_json(p));
    best.reported.iter().map(entry).collect()
}

fn merged_json(m: &MergedProcess, estimate: &GmwmEstimate, sensor: Sensor) -> MergedJson {
    let unit = name_unit(sensor);
    let (equivalent, reason) = match m.into {
        MergedInto::WhiteNoise => (
            "white_noise_density_unit_sqrt_s",
            format!(
                "its correlation time is {:.2} sample periods, at most {WHITE_MERGE_SAMPLE_PERIODS}: \
                 it is white noise at every averaging time beyond a few samples (a sensor's \
                 internal low-pass shows so at the shortest scales), so its spectrum at zero \
                 frequency is added to the white noise",
                m.correlation_samples
            ),
        ),
        MergedInto::RandomWalk => (
            "random_walk_unit_per_sqrt_s",
            format!(
                "its correlation time, {:.3e} s, exceeds the record ({:.1} s): the record sees \
                 only sigma^2/Tc, a random walk, so it is added to the random walk",
                m.correlation_time_s, m.record_s
            ),
        ),
    };
    let values = [
        (format!("sigma_{unit}"), m.sigma),
        (equivalent.replace("unit", unit), m.equivalent),
    ];
    MergedJson {
        process: format!("gm{}", m.gm_index),
        fitted_in: estimate.fit.model.to_string(),
        into: m.into,
        correlation_time_s: m.correlation_time_s,
        correlation_time_sample_periods: m.correlation_samples,
        values: values.into_iter().collect(),
        reason,
    }
}

fn absent_json(a: &AbsentProcess) -> AbsentJson {
    let dof = a.degrees_of_freedom;
    let reason = format!(
        "not resolved by this record: leaving it out of {} raises the GMWM objective by {:.2} \
         (chi-square with {dof} degree{} of freedom: p = {:.2}; a process is kept when p < \
         {RESOLUTION_LEVEL})",
        a.fitted_in,
        a.objective_rise,
        if dof == 1 { "" } else { "s" },
        a.p_value
    );
    AbsentJson {
        process: a.process,
        fitted_in: a.fitted_in.to_string(),
        objective_rise: a.objective_rise,
        degrees_of_freedom: dof,
        p_value: a.p_value,
        level: RESOLUTION_LEVEL,
        reason,
    }
}

fn parameter_json(p: &ParameterEstimate) -> ParameterJson {
    ParameterJson {
        value: p.value,
        ci_low: p.ci_low,
        ci_high: p.ci_high,
    }
}

fn candidate_json(e: &GmwmEstimate) -> CandidateJson {
    CandidateJson {
        model: e.fit.model.to_string(),
        wic: e.wic,
        objective: e.fit.objective,
    }
}
