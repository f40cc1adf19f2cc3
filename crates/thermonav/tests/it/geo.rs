//! WGS84 conversions against pymap3d (tools/oracles/geodesy.py) and closed forms.

use crate::oracle_json;
use thermonav::frames::{Ned, Vector};
use thermonav::geo::position::{Geodetic, meridian_radius_m, transverse_radius_m};

fn f(v: &serde_json::Value) -> f64 {
    v.as_f64().expect("number")
}

// pymap3d and our code evaluate the same closed formula; agreement to 1e-6 m (1e-13
// relative at Earth radius) is floating-point rounding.
#[test]
fn geodetic_to_ecef_matches_pymap3d() {
    let oracle = oracle_json("geodesy.json");
    for case in oracle["ecef"].as_array().unwrap() {
        let p = Geodetic::from_degrees(f(&case["lat_deg"]), f(&case["lon_deg"]), f(&case["h_m"]));
        let r = p.to_ecef().to_array();
        for k in 0..3 {
            assert!((r[k] - f(&case["ecef_m"][k])).abs() < 1e-6, "{case}: {r:?}");
        }
    }
}

// The inverse is iterative in our code and closed-form (Vermeille-like) in pymap3d: round trip
// through pymap3d's ECEF must return the geodetic inputs to 1e-11 rad (0.06 mm) and 1e-6 m.
#[test]
fn ecef_to_geodetic_inverts_pymap3d_ecef() {
    let oracle = oracle_json("geodesy.json");
    for case in oracle["ecef"].as_array().unwrap() {
        let r = Vector::new(
            f(&case["ecef_m"][0]),
            f(&case["ecef_m"][1]),
            f(&case["ecef_m"][2]),
        );
        let p = Geodetic::from_ecef(&r);
        assert!(
            (p.latitude_rad.to_degrees() - f(&case["lat_deg"])).abs() < 1e-9,
            "{case}"
        );
        assert!(
            (p.longitude_rad.to_degrees() - f(&case["lon_deg"])).abs() < 1e-9,
            "{case}"
        );
        assert!(
            (p.height_m - f(&case["h_m"])).abs() < 1e-6,
            "{case}: {}",
            p.height_m
        );
    }
}

// Local NED displacements of points 0.1 to 25 km away: same definition (ECEF difference
// rotated into the origin's NED axes) in both; 1e-6 m.
#[test]
fn ned_displacement_matches_pymap3d() {
    let oracle = oracle_json("geodesy.json");
    let o = &oracle["origin"];
    let origin = Geodetic::from_degrees(f(&o[0]), f(&o[1]), f(&o[2]));
    for case in oracle["ned_from_origin"].as_array().unwrap() {
        let p = Geodetic::from_degrees(f(&case["lat_deg"]), f(&case["lon_deg"]), f(&case["h_m"]));
        let ned = p.ned_from(&origin).to_array();
        for k in 0..3 {
            assert!(
                (ned[k] - f(&case["ned_m"][k])).abs() < 1e-6,
                "{case}: {ned:?}"
            );
        }
    }
}

// Closed forms: at the equator R_N = a(1 − e²) = b²/a and R_E = a; at the pole both are a²/b.
#[test]
fn radii_of_curvature_at_equator_and_pole() {
    let (a, b) = (6_378_137.0_f64, 6_356_752.314_245_179_f64);
    assert!((meridian_radius_m(0.0) - b * b / a).abs() < 1e-6);
    assert!((transverse_radius_m(0.0) - a).abs() < 1e-9);
    let pole = std::f64::consts::FRAC_PI_2;
    assert!((meridian_radius_m(pole) - a * a / b).abs() < 1e-6);
    assert!((transverse_radius_m(pole) - a * a / b).abs() < 1e-6);
}

// The NED axes resolved in ECEF must be the local north, east and down directions: north is
// the derivative of position with latitude, east with longitude (finite differences of our
// own ECEF formula, checked above against pymap3d), down is north × east.
#[test]
fn ned_axes_point_north_east_down() {
    let p = Geodetic::from_degrees(51.08, -114.13, 1100.0);
    let c = p.ned_to_ecef();
    let d = 1e-7;
    let north = (Geodetic {
        latitude_rad: p.latitude_rad + d,
        ..p
    }
    .to_ecef()
        - p.to_ecef())
    .scale(1.0 / d);
    let east = (Geodetic {
        longitude_rad: p.longitude_rad + d,
        ..p
    }
    .to_ecef()
        - p.to_ecef())
    .scale(1.0 / d);
    let n_hat = c * Vector::<Ned>::new(1.0, 0.0, 0.0);
    let e_hat = c * Vector::<Ned>::new(0.0, 1.0, 0.0);
    assert!((north.scale(1.0 / north.norm()) - n_hat).norm() < 1e-6);
    assert!((east.scale(1.0 / east.norm()) - e_hat).norm() < 1e-6);
}

// Transport rate closed form: driving east at 10 m/s on the equator turns the NED frame about
// north at v/(a + h); driving north turns it about east at −v/(R_N + h).
#[test]
fn transport_rate_closed_form() {
    let p = Geodetic {
        latitude_rad: 0.0,
        longitude_rad: 0.0,
        height_m: 100.0,
    };
    let east = p
        .transport_rate_ned(&Vector::new(0.0, 10.0, 0.0))
        .to_array();
    assert!((east[0] - 10.0 / (6_378_137.0 + 100.0)).abs() < 1e-18);
    let north = p
        .transport_rate_ned(&Vector::new(10.0, 0.0, 0.0))
        .to_array();
    assert!((north[1] + 10.0 / (meridian_radius_m(0.0) + 100.0)).abs() < 1e-18);
}

// `displaced` is first order: moving 3 m and measuring the displacement back with the exact
// ECEF route must agree to |offset|²/R ≈ 1.4e-6 m; 1e-5 m leaves room for rounding.
#[test]
fn displaced_moves_by_the_offset_to_first_order() {
    let p = Geodetic::from_degrees(51.08, -114.13, 1100.0);
    let offset = Vector::<Ned>::new(2.0, -1.5, 1.2);
    let back = p.displaced(&offset).ned_from(&p);
    assert!((back - offset).norm() < 1e-5, "{:?}", back.to_array());
    let q = p.displaced(&Vector::new(100.0, 50.0, -20.0));
    let mid = p.midpoint(&q);
    assert!((mid.height_m - (p.height_m + q.height_m) / 2.0).abs() < 1e-12);
}

// `offset_from` inverts `displaced` exactly (both use the origin's radii), even for offsets
// of kilometres where the tangent-plane `ned_from` differs by the curvature |offset|²/2R
// (~0.3 m in down at 2 km): the round trip closes to rounding (1e-9 m).
#[test]
fn offset_from_inverts_displaced() {
    let p = Geodetic::from_degrees(44.6, -63.6, 12.0);
    for offset in [
        Vector::<Ned>::new(2000.0, -1500.0, 30.0),
        Vector::new(-0.3, 0.2, -0.1),
    ] {
        let back = p.displaced(&offset).offset_from(&p);
        assert!((back - offset).norm() < 1e-9, "{:?}", back.to_array());
    }
    let far = p.displaced(&Vector::new(2000.0, 0.0, 0.0));
    let curvature = far.ned_from(&p).z() - far.offset_from(&p).z();
    let expected = 2000.0f64.powi(2) / (2.0 * thermonav::geo::wgs84::SEMI_MAJOR_AXIS_M);
    assert!(
        (curvature / expected - 1.0).abs() < 0.02,
        "{curvature} vs {expected}"
    );
}
