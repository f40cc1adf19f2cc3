//! Round trip between the simulator and the characterisation: simulated chamber records at
//! several temperatures give back each channel's true correlation time inside the exact
//! likelihood's 95 % interval, at the expected rate.

use thermonav::imu::Channel;
use thermonav::sensor::adis16364_like;
use thermonav::sim::chamber::{ChamberRun, ChamberWander, calgary, simulate_chamber_run};
use thermonav::sim::clock::SampleClock;
use thermonav::stoch::bank::{GaussMarkovEstimate, GaussMarkovSource};
use thermonav::stoch::characterize::{CharacterizeSettings, characterize};

// Three temperatures whose correlation times (20-375 s) are short against a 2-hour record at
// 50 Hz (the built-in profile, jittered clock with drops). 18 intervals at 95 % each: the number
// covering the truth is Binomial(18, 0.95); requiring at least 15 fails with probability
// ≈ 1.6 % for a correct estimator (the seed is fixed, so the test is deterministic).
#[test]
fn characterising_a_simulated_campaign_recovers_the_true_correlation_times() {
    let profile = adis16364_like();
    let settings = CharacterizeSettings::default();
    let mut covered = 0;
    let mut total = 0;
    for set_point_c in [-40.0, -20.0, 0.0] {
        let run = ChamberRun {
            temperature: thermonav::sim::chamber::ChamberTemperature::SetPoint {
                temperature_c: set_point_c,
            },
            unit: thermonav::sim::unit::SimulatedUnit::default(),
            power_on: 1,
            duration_s: 7200.0,
            clock: SampleClock::new(50.0, 100e-6, 0.002).unwrap(),
            site: calgary(),
            wander: ChamberWander {
                sigma_c: 0.05,
                correlation_time_s: 600.0,
            },
            seed: 77,
        };
        let record = simulate_chamber_run(&profile, &run).unwrap();
        let (entry, _) = characterize(&record.series, set_point_c, "sim", &settings).unwrap();
        for channel in Channel::ALL {
            let truth = record.truth.channels[&channel]
                .gauss_markov
                .correlation_time_s;
            total += 1;
            if let GaussMarkovEstimate::Model {
                ci95_correlation_time_s: [lo, hi],
                ..
            } = entry.channels[&channel]
                .gauss_markov
                .get(GaussMarkovSource::IRREGULAR_ML)
            {
                covered +=
                    usize::from(lo.is_none_or(|l| l <= truth) && hi.is_none_or(|h| truth <= h));
            }
        }
    }
    assert_eq!(total, 18);
    assert!(covered >= 15, "covered {covered} of 18");
}
