//! `nullpath geodesic` as a user runs it: JSON with exactly the documented keys, and clear,
//! non-zero-exit errors for bad arguments.

#![allow(clippy::unwrap_used)] // A panic is a failed test.

use std::process::Command;

fn nullpath(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_nullpath")).args(args).output().unwrap()
}

#[test]
fn json_has_exactly_the_documented_keys_and_the_exact_angle() {
    let out = nullpath(&["geodesic", "--spacetime", "schwarzschild", "--mass", "1", "--impact", "20", "--json"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let mut keys: Vec<_> = v.as_object().unwrap().keys().cloned().collect();
    keys.sort();
    assert_eq!(keys, ["deflection_rad", "fate", "max_abs_hamiltonian", "steps"]);
    assert_eq!(v["fate"], "escaped");
    let exact = spacetime::analytic::schwarzschild_deflection(1.0, 20.0);
    assert!((v["deflection_rad"].as_f64().unwrap() / exact - 1.0).abs() < 1e-7);
    assert!(v["steps"].as_u64().unwrap() > 0);
}

#[test]
fn every_fate_is_reported() {
    let fate = |args: &[&str]| {
        let out = nullpath(&[&["geodesic", "--json"], args].concat());
        assert!(out.status.success());
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        v["fate"].as_str().unwrap().to_owned()
    };
    assert_eq!(fate(&["--spacetime", "kerr", "--spin", "0.9", "--impact", "2"]), "captured");
    // Reissner–Nordström, Q = 0.8 M: r_ph = (3M + √(9M² − 8Q²))/2, critical impact parameter
    // b_c = r_ph²/√(r_ph² − 2M r_ph + Q²) = 4.5460 M.
    let rn = |b: &str| fate(&["--spacetime", "reissner-nordstrom", "--charge", "0.8", "--impact", b]);
    assert_eq!((rn("4.53").as_str(), rn("4.56").as_str()), ("captured", "escaped"));
    assert_eq!(fate(&["--spacetime", "ellis", "--throat", "1", "--impact", "0.5"]), "traversed");
    assert_eq!(fate(&["--spacetime", "minkowski", "--impact", "1"]), "escaped");
    let wormhole =
        |b: &str| fate(&["--spacetime", "wormhole", "--length", "0.5", "--lensing-width", "0.05", "--impact", b]);
    assert_eq!((wormhole("0.9").as_str(), wormhole("1.5").as_str()), ("traversed", "escaped"));
    assert_eq!(
        fate(&["--spacetime", "schwarzschild", "--impact", "30", "--integrator", "rk4", "--inclination", "30"]),
        "escaped"
    );
}

#[test]
fn bad_arguments_fail_with_a_clear_message() {
    for (args, needle) in [
        (&["geodesic", "--spacetime", "kerr", "--spin", "1.5", "--impact", "3"][..], "spin"),
        (&["geodesic", "--spacetime", "schwarzschild", "--mass", "-1", "--impact", "3"][..], "mass"),
        (&["geodesic", "--spacetime", "ellis", "--throat", "0", "--impact", "3"][..], "throat"),
        (&["geodesic", "--spacetime", "schwarzschild", "--impact", "nan"][..], "impact"),
        (&["geodesic", "--spacetime", "wormhole", "--impact", "3"][..], "--lensing-width"),
        (&["geodesic", "--spacetime", "wormhole", "--lensing-width", "0", "--impact", "3"][..], "lensing"),
        (&["geodesic", "--spacetime", "schwarzschild"][..], "--impact"),
        (&["geodesic", "--spacetime", "schwarzschild", "--impact", "3", "--rtol", "0"][..], "rtol"),
    ] {
        let out = nullpath(args);
        assert!(!out.status.success(), "{args:?} should fail");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(needle), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{args:?}: {err}");
    }
}
