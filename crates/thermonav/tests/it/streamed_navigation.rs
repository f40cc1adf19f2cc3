//! The filter run over a stream of increments with its records handed to a sink
//! ([`run_streaming`]): against the whole-record run ([`run`], whose solution is kept in a
//! Vec), which is the oracle: the same epochs, innovations, smoothed epochs and statistics to
//! the bit, and the same refusals.

use thermonav::imu::{ImuSample, ImuSeries, SampleKind};
use thermonav::ins::state::Increment;
use thermonav::nav::alignment::{InitialUncertainty, uncorrected};
use thermonav::nav::engine::{
    EngineSettings, Filtering, NavError, StreamError, increments_from_series, increments_of_samples,
};
use thermonav::nav::measurement::AntennaGeometry;
use thermonav::nav::navigate::{run, run_streaming};
use thermonav::nav::outage::Outages;
use thermonav::nav::schedule::ModelSchedule;
use thermonav::nav::sensor_model::{ImuStochasticModel, ScaleFactorPrior};
use thermonav::nav::solution::{Solution, SolutionSummary};
use thermonav::sensor::adis16364_like;
use thermonav::sim::clock::SampleClock;
use thermonav::sim::vessel::{
    GnssSettings, SurveyTemperature, VesselRecord, VesselRun, harbour_survey, simulate_vessel,
};

fn vessel(duration_s: f64) -> VesselRecord {
    let run = VesselRun {
        motion: harbour_survey(duration_s),
        temperature: SurveyTemperature::Constant {
            temperature_c: 17.0,
        },
        unit: thermonav::sim::unit::SimulatedUnit { serial: 5 },
        clock: SampleClock::new(200.0, 0.0, 0.0).unwrap(),
        gnss: GnssSettings::default(),
        seed: 5,
    };
    simulate_vessel(&adis16364_like(), &run).unwrap()
}

fn model() -> ImuStochasticModel {
    adis16364_like()
        .stochastic_model(17.0, &ScaleFactorPrior::default())
        .unwrap()
}

fn settings(smooth: bool) -> EngineSettings {
    let g = GnssSettings::default();
    EngineSettings {
        geometry: AntennaGeometry {
            lever_arm_body_m: g.lever_arm_body_m,
            baseline_body: g.baseline_body_m,
        },
        outages: Outages::from_start_duration(&[(40.0, 20.0)]).unwrap(),
        output_interval_s: 0.02,
        smooth,
        ..EngineSettings::default()
    }
}

type Streamed = Result<(Solution, SolutionSummary), StreamError<String>>;

/// The whole-record run and the streamed one (into a kept Solution and a summary).
fn both(
    record: &VesselRecord,
    increments: &[Increment],
    settings: &EngineSettings,
) -> (Result<Solution, NavError>, Streamed) {
    let model = model();
    let initial = uncorrected(record.reference.states[0]);
    let p0 = InitialUncertainty::default().covariance();
    let whole = run(
        increments,
        &record.gnss,
        initial,
        p0,
        &model,
        settings,
        &mut |_| {},
    );
    let filtering = Filtering {
        initial,
        p0,
        schedule: ModelSchedule::Fixed(&model),
        settings,
    };
    let mut sinks = (Solution::default(), SolutionSummary::default());
    let last = increments.last().map(|i| i.time);
    let stream = increments.iter().map(|i| Ok::<_, String>(*i));
    let streamed = run_streaming(
        filtering,
        stream,
        &record.gnss,
        last,
        &mut sinks,
        &mut |_| {},
    )
    .map(|tail| {
        let (mut solution, summary) = sinks;
        solution.imu_samples = tail.imu_samples;
        solution.smoothed = tail.smoothed;
        (solution, summary)
    });
    (whole, streamed)
}

// Over 90 s of the vessel with a 20 s outage and 50 Hz output, the streamed run's sink sees
// exactly the kept solution's epochs (an epoch at a fix's time shows the state after its
// updates on both paths) and innovations; its summary's statistics, first and last epoch
// are those of the kept solution; and the smoother's epochs are the same.
#[test]
fn a_streamed_run_hands_its_sink_the_whole_record_runs_solution() {
    let record = vessel(90.0);
    let increments = increments_from_series(&record.imu);
    for smooth in [false, true] {
        let (whole, streamed) = both(&record, &increments, &settings(smooth));
        let whole = whole.unwrap();
        let (solution, summary) = streamed.unwrap();
        assert!(whole.epochs.len() > 4000 && whole.innovations.len() > 100);
        assert_eq!(solution, whole, "smooth {smooth}");
        assert_eq!(smooth, !whole.smoothed.is_empty());
        assert_eq!(
            summary.innovation_statistics(),
            whole.innovation_statistics()
        );
        assert_eq!(summary, SolutionSummary::of(&whole));
        assert_eq!(summary.last.as_ref(), whole.epochs.last());
        assert_eq!(summary.epochs, whole.epochs.len());
        let first = whole.epochs[0].estimate.nav.time;
        assert_eq!(summary.first_time, Some(first));
    }
}

// A stream that fails at its 5000th increment stops the run with the stream's own error; a
// gap in the record (300 samples at 200 Hz removed after 50 s) is refused by the streamed run
// with the whole-record check's error, values and all.
#[test]
fn a_streamed_run_stops_at_a_failed_read_and_refuses_a_gap_like_the_whole_record_check() {
    let record = vessel(90.0);
    let increments = increments_from_series(&record.imu);
    let model = model();
    let settings = settings(false);
    let filtering = Filtering {
        initial: uncorrected(record.reference.states[0]),
        p0: InitialUncertainty::default().covariance(),
        schedule: ModelSchedule::Fixed(&model),
        settings: &settings,
    };
    let failing = increments.iter().enumerate().map(|(k, i)| match k {
        5000 => Err(format!("line {}", k + 2)),
        _ => Ok(*i),
    });
    let mut sink = SolutionSummary::default();
    let error = run_streaming(
        filtering,
        failing,
        &record.gnss,
        None,
        &mut sink,
        &mut |_| {},
    );
    assert_eq!(
        error.unwrap_err(),
        StreamError::Input("line 5002".to_string())
    );
    assert!(
        sink.epochs > 0 && sink.epochs < 2000,
        "{} epochs",
        sink.epochs
    );

    let mut gapped = ImuSeries::new(SampleKind::Rates);
    for k in (0..record.imu.len()).filter(|k| !(10_000..10_300).contains(k)) {
        gapped.push(&sample(&record.imu, k));
    }
    let increments = increments_from_series(&gapped);
    let (whole, streamed) = both(&record, &increments, &settings);
    let expected = whole.unwrap_err();
    assert!(matches!(expected, NavError::ImuGap { .. }), "{expected}");
    assert_eq!(streamed.unwrap_err(), StreamError::Nav(expected));
}

fn sample(series: &ImuSeries, k: usize) -> ImuSample {
    let value = |c: usize| series.channels[c][k];
    ImuSample {
        time: series.time[k],
        gyro: [value(0), value(1), value(2)],
        accel: [value(3), value(4), value(5)],
        temperature_c: series.temperature_c.as_ref().map(|t| t[k]),
    }
}

// The increments of a stream of samples are those of the series they make, for rates and for
// increments; a failed sample ends the stream with its error.
#[test]
fn increments_of_a_sample_stream_are_those_of_the_series() {
    let record = vessel(20.0);
    for kind in [SampleKind::Rates, SampleKind::Increments] {
        let mut series = record.imu.clone();
        series.kind = Some(kind);
        let samples = (0..series.len()).map(|k| Ok::<_, String>(sample(&series, k)));
        let streamed: Vec<Increment> = increments_of_samples(kind, samples)
            .collect::<Result<_, _>>()
            .unwrap();
        assert_eq!(streamed, increments_from_series(&series));
        assert!(streamed.len() > 3000);
    }
    let samples = (0..10).map(|k| match k {
        4 => Err("bad".to_string()),
        k => Ok(sample(&record.imu, k)),
    });
    let out: Vec<_> = increments_of_samples(SampleKind::Rates, samples).collect();
    assert_eq!(out.len(), 4);
    assert_eq!(out[3], Err("bad".to_string()));
}

// The same run with its sink on a thread of its own (records handed over in batches of
// 1024): the sink sees the whole-record run's epochs and innovations in the same order, with
// a smoothed run too (4500 epochs: five batches and a partial one).
#[test]
fn a_sink_on_its_own_thread_sees_the_same_records_in_order() {
    use thermonav::nav::solution::with_sink_on_own_thread;
    let record = vessel(90.0);
    let increments = increments_from_series(&record.imu);
    let model = model();
    for smooth in [false, true] {
        let settings = settings(smooth);
        let (whole, _) = both(&record, &increments, &settings);
        let whole = whole.unwrap();
        let initial = uncorrected(record.reference.states[0]);
        let filtering = Filtering {
            initial,
            p0: InitialUncertainty::default().covariance(),
            schedule: ModelSchedule::Fixed(&model),
            settings: &settings,
        };
        let mut kept = Solution::default();
        let last = increments.last().map(|i| i.time);
        let stream = increments.iter().map(|i| Ok::<_, String>(*i));
        let tail = with_sink_on_own_thread(&mut kept, |sink| {
            run_streaming(filtering, stream, &record.gnss, last, sink, &mut |_| {})
        })
        .unwrap();
        kept.imu_samples = tail.imu_samples;
        kept.smoothed = tail.smoothed;
        assert!(kept.epochs.len() > 4 * 1024);
        assert_eq!(kept, whole, "smooth {smooth}");
    }
}
