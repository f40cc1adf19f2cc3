//! The generic UKF against FilterPy 2.0 (../shared/data/ukf-peer-vectors, cross-checked by
//! its authors against pykalman): sigma points, weights, the unscented transform and a
//! 200-step run, all within 1e-10 (the requirement; the values are printed with 17
//! significant digits, so the difference is the rounding of two implementations).

use crate::shared_data;
use nalgebra::{SMatrix, SVector};
use serde_json::Value;
use thermonav::filter::sigma_points::{SigmaPointScheme, unscented_transform};
use thermonav::filter::ukf::Ukf;

fn reference() -> Value {
    let path = shared_data("ukf-peer-vectors/ukf_reference.json");
    serde_json::from_str(&std::fs::read_to_string(path).expect("ukf reference present"))
        .expect("JSON")
}

fn num(v: &Value) -> f64 {
    v.as_f64().expect("number")
}

fn vector<const N: usize>(v: &Value) -> SVector<f64, N> {
    SVector::from_fn(|i, _| num(&v[i]))
}

fn matrix<const N: usize, const M: usize>(v: &Value) -> SMatrix<f64, N, M> {
    SMatrix::from_fn(|i, j| num(&v[i][j]))
}

fn scheme(case: &Value) -> SigmaPointScheme {
    match case["kind"].as_str() {
        Some("merwe_scaled") => SigmaPointScheme::MerweScaled {
            alpha: num(&case["alpha"]),
            beta: num(&case["beta"]),
            kappa: num(&case["kappa"]),
        },
        _ => SigmaPointScheme::Julier {
            kappa: num(&case["kappa"]),
        },
    }
}

fn close(a: f64, b: f64, what: &str) {
    assert!(
        (a - b).abs() <= 1e-10 * b.abs().max(1.0),
        "{what}: {a} vs {b}"
    );
}

fn check_case<const N: usize>(case: &Value) {
    let name = case["name"].as_str().unwrap_or("case");
    let s = scheme(case);
    let (x, p) = (vector::<N>(&case["x"]), matrix::<N, N>(&case["P"]));
    let points = s.points(&x, &p).unwrap();
    for (i, point) in points.iter().enumerate() {
        for j in 0..N {
            close(
                point[j],
                num(&case["sigma_points"][i][j]),
                &format!("{name} point {i},{j}"),
            );
        }
    }
    let w = s.weights(N);
    for i in 0..2 * N + 1 {
        close(w.mean[i], num(&case["Wm"][i]), &format!("{name} Wm {i}"));
        close(
            w.covariance[i],
            num(&case["Wc"][i]),
            &format!("{name} Wc {i}"),
        );
    }
    // The transform of the points must give back (x, P), an identity of the scheme. With
    // α = 1e-3 the weights reach ±1e6 and cancel, so the rounding bound is
    // 4 ε Σ|W| max(|x|, |P|) rather than the 1e-10 used against FilterPy.
    let (mean, cov) = unscented_transform(&points, &w, &SMatrix::zeros());
    let weight_sum: f64 = w.mean.iter().chain(&w.covariance).map(|v| v.abs()).sum();
    let scale = x.amax().max(p.amax()).max(1.0);
    let tolerance = (4.0 * f64::EPSILON * weight_sum * scale).max(1e-10);
    for i in 0..N {
        assert!((mean[i] - x[i]).abs() <= tolerance, "{name} mean {i}");
        for j in 0..N {
            assert!(
                (cov[(i, j)] - p[(i, j)]).abs() <= tolerance,
                "{name} cov {i},{j}"
            );
        }
    }
}

#[test]
fn sigma_points_and_weights_match_filterpy() {
    let r = reference();
    let cases = r["cases"].as_array().unwrap();
    assert_eq!(cases.len(), 8);
    for case in cases {
        match case["n"].as_u64() {
            Some(2) => check_case::<2>(case),
            Some(3) => check_case::<3>(case),
            Some(4) => check_case::<4>(case),
            Some(15) => check_case::<15>(case),
            Some(21) => check_case::<21>(case),
            other => panic!("unexpected dimension {other:?}"),
        }
    }
}

#[test]
fn unscented_transform_of_polar_to_cartesian_matches_filterpy() {
    let r = reference();
    for case in r["unscented_transform_polar_to_cartesian"]
        .as_array()
        .unwrap()
    {
        let s = SigmaPointScheme::MerweScaled {
            alpha: num(&case["alpha"]),
            beta: num(&case["beta"]),
            kappa: num(&case["kappa"]),
        };
        let x = vector::<2>(&case["x_polar_r_theta"]);
        let p = matrix::<2, 2>(&case["P_polar"]);
        let points: Vec<SVector<f64, 2>> = s
            .points(&x, &p)
            .unwrap()
            .iter()
            .map(|q| SVector::<f64, 2>::new(q[0] * q[1].cos(), q[0] * q[1].sin()))
            .collect();
        for (i, q) in points.iter().enumerate() {
            close(
                q[0],
                num(&case["transformed_sigma_points"][i][0]),
                "transformed x",
            );
            close(
                q[1],
                num(&case["transformed_sigma_points"][i][1]),
                "transformed y",
            );
        }
        let (mean, cov) = unscented_transform(&points, &s.weights(2), &SMatrix::zeros());
        for i in 0..2 {
            close(mean[i], num(&case["y_mean"][i]), "y mean");
            for j in 0..2 {
                close(cov[(i, j)], num(&case["P_y"][i][j]), "P_y");
            }
        }
    }
}

#[test]
fn two_hundred_step_range_only_run_matches_filterpy() {
    let r = reference();
    let run = &r["ukf_run_radar_range_only"];
    let dt = num(&run["dt"]);
    let s = SigmaPointScheme::MerweScaled {
        alpha: num(&run["points"]["alpha"]),
        beta: num(&run["points"]["beta"]),
        kappa: num(&run["points"]["kappa"]),
    };
    let q = matrix::<3, 3>(&run["Q"]);
    let rm = matrix::<1, 1>(&run["R"]);
    let mut ukf = Ukf::new(vector::<3>(&run["x0"]), matrix::<3, 3>(&run["P0"]), s);
    let fx = |x: &SVector<f64, 3>| SVector::<f64, 3>::new(x[0] + x[1] * dt, x[1], x[2]);
    let hx = |x: &SVector<f64, 3>| SVector::<f64, 1>::new(x[0].hypot(x[2]));
    let zs = run["measurements_range"].as_array().unwrap();
    assert_eq!(zs.len(), 200);
    for (k, z) in zs.iter().enumerate() {
        ukf.predict(fx, &q).unwrap();
        compare(&ukf, &run["x_prior"][k], &run["P_prior"][k], k, "prior");
        ukf.update(&SVector::<f64, 1>::new(num(z)), hx, &rm)
            .unwrap();
        compare(&ukf, &run["x_post"][k], &run["P_post"][k], k, "posterior");
    }
}

fn compare(ukf: &Ukf<3>, x: &Value, p: &Value, k: usize, what: &str) {
    for i in 0..3 {
        close(ukf.x[i], num(&x[i]), &format!("step {k} {what} x{i}"));
        for j in 0..3 {
            close(
                ukf.p[(i, j)],
                num(&p[i][j]),
                &format!("step {k} {what} P{i}{j}"),
            );
        }
    }
}
