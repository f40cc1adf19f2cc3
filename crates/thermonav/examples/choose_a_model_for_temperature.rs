//! Step 2 of the story: the model for the temperature the sensor will work at.
//!
//! The bank of `characterize_a_chamber` holds a Gauss-Markov bias model per chamber
//! temperature. A survey runs at some other temperature: the model is either the nearest
//! entry's or interpolated linearly in temperature between the two entries around it (held at
//! the end entry outside the campaign). This prints both choices against the simulated
//! sensor's truth, then the whole model the filter is given at 17 °C, beside the paper's
//! AR-based model and a data sheet's.
//!
//! `cargo run --release -p thermonav --example choose_a_model_for_temperature`

mod common;

use common::{bias, bias_unit, density, density_unit};
use std::time::Instant;
use thermonav::evaluation::candidates::DatasheetValues;
use thermonav::imu::Channel;
use thermonav::nav::sensor_model::{AxisModel, BankChoice, ImuStochasticModel, ScaleFactorPrior};
use thermonav::stoch::bank::{GaussMarkovSource, ModelBank, Placement, Selection};

/// Operating temperatures to select at, °C: inside the campaign, between its points, outside.
const OPERATING_C: [f64; 7] = [-50.0, -30.0, 5.0, 17.0, 33.0, 50.0, 75.0];
/// The survey's temperature, °C.
const SURVEY_C: f64 = 17.0;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let started = Instant::now();
    let profile = common::sensor();
    let bank = common::bank(&profile)?;
    println!(
        "Bank from the chamber campaign (characterize_a_chamber): entries at {:?} °C",
        bank.temperatures_c()
    );
    for channel in [Channel::Gx, Channel::Ax] {
        selection_table(&bank, &profile, channel)?;
    }

    let scale = ScaleFactorPrior::default();
    let choice = |source| BankChoice {
        temperature_c: SURVEY_C,
        selection: Selection::Linear,
        source,
    };
    let chosen =
        ImuStochasticModel::from_bank(&bank, &choice(GaussMarkovSource::IRREGULAR_ML), &scale)?;
    let truth = profile.stochastic_model(SURVEY_C, &scale)?;
    println!(
        "\nThe model the filter carries at {SURVEY_C} °C (exact-likelihood family, linear), and the sensor's truth:"
    );
    println!(
        "  {:>3}  {:>22}  {:>17}  {:>21}  {:>24}",
        "ch", "white noise (truth)", "bias Tc (truth)", "bias σ (truth)", "scale factor: σ, Tc"
    );
    for (k, channel) in Channel::ALL.into_iter().enumerate() {
        let (a, t) = (axis(&chosen, k), axis(&truth, k));
        println!(
            "  {:>3}  {:>6.3} ({:.3}) {:>7}  {:>6.0} s ({:>5.0} s)  {:>6.2} ({:>5.2}) {:>5}  {:>7.0} ppm, {:>6.0} s",
            channel.name(),
            density(channel, a.white_noise_density),
            density(channel, t.white_noise_density),
            density_unit(channel),
            a.bias.correlation_time_s,
            t.bias.correlation_time_s,
            bias(channel, a.bias.sigma),
            bias(channel, t.bias.sigma),
            bias_unit(channel),
            a.scale_factor.sigma * 1e6,
            a.scale_factor.correlation_time_s
        );
    }
    println!(
        "  The scale-factor error is a stated prior: a static record cannot reveal it. The accelerometers'"
    );
    println!(
        "  white noise is above the profile's 0.12 m/s/√h because their 1 mg steps add quantisation noise:"
    );
    println!("  √(0.12² + q²/(12 f_s)) = 0.131 m/s/√h for q = 1 mg at f_s = 10 Hz.");

    let paper = ImuStochasticModel::from_bank(&bank, &choice(GaussMarkovSource::AR_BASED), &scale)?;
    let sheet = DatasheetValues::adis16364().model(&scale);
    println!("\nOther ways to fill the same slots, gyro x and accelerometer x at {SURVEY_C} °C:");
    for (name, model) in [
        ("the paper's AR-based model", &paper),
        ("the data sheet (Tc assumed 1 h)", &sheet),
    ] {
        let (g, a) = (model.gyro[0], model.accel[0]);
        println!(
            "  {name:<32} gx Tc {:>7.1} s, σ {:>6.2} deg/h;  ax Tc {:>7.1} s, σ {:.3} mg",
            g.bias.correlation_time_s,
            bias(Channel::Gx, g.bias.sigma),
            a.bias.correlation_time_s,
            bias(Channel::Ax, a.bias.sigma)
        );
    }

    let refused = bank.select(
        f64::NAN,
        Channel::Gx,
        GaussMarkovSource::IRREGULAR_ML,
        Selection::Linear,
    );
    if let Err(e) = refused {
        println!("\nA temperature the bank cannot place is refused with a typed error: \"{e}\"");
    }
    println!("Done in {:.1} s.", started.elapsed().as_secs_f64());
    Ok(())
}

/// Tc and σ of `channel` by nearest entry and by linear interpolation at each operating
/// temperature, beside the simulated truth there.
fn selection_table(
    bank: &ModelBank,
    profile: &common::SensorProfile,
    channel: Channel,
) -> Result<(), Box<dyn std::error::Error>> {
    let unit = bias_unit(channel);
    println!(
        "\nBias model of {} by operating temperature (σ in {unit}):",
        channel.name()
    );
    println!(
        "  {:>6}  {:>28}  {:>44}  {:>19}",
        "T_op_C", "nearest entry: Tc, σ", "linear: from, Tc, σ", "simulated truth"
    );
    let source = GaussMarkovSource::IRREGULAR_ML;
    for t in OPERATING_C {
        let nearest = bank.select(t, channel, source, Selection::Nearest)?;
        let linear = bank.select(t, channel, source, Selection::Linear)?;
        let from = match (nearest.placement, linear.placement) {
            (
                _,
                Placement::Between {
                    lower_c,
                    upper_c,
                    weight,
                },
            ) => {
                format!("{lower_c}..{upper_c} °C, w {weight:.2}")
            }
            (_, Placement::Clamped { temperature_c }) => format!("held at {temperature_c} °C"),
            (_, Placement::Entry { temperature_c }) => format!("entry {temperature_c} °C"),
        };
        let Placement::Entry {
            temperature_c: entry_c,
        } = nearest.placement
        else {
            return Err("nearest selection always names one entry".into());
        };
        let truth = profile
            .channel(channel)
            .ok_or("profile without the channel")?
            .bias_at(t);
        println!(
            "  {t:>6}  {:>6} °C: {:>5.0} s, {:>6.2}  {from:>22}: {:>5.0} s, {:>6.2}  {:>5.0} s, {:>6.2}",
            entry_c,
            nearest.correlation_time_s,
            bias(channel, nearest.sigma),
            linear.correlation_time_s,
            bias(channel, linear.sigma),
            truth.correlation_time_s,
            bias(channel, truth.sigma)
        );
    }
    Ok(())
}

/// Axis `k` of a model: gyros 0-2, accelerometers 3-5 (the order of [`Channel::ALL`]).
fn axis(model: &ImuStochasticModel, k: usize) -> AxisModel {
    if k < 3 {
        model.gyro[k]
    } else {
        model.accel[k - 3]
    }
}
