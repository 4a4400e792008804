//! The statistics agree with SciPy/NumPy reference values (fixtures made by
//! `tests/fixtures/make_stats_fixtures.py`, SciPy 1.17): summaries, rank-test p-values and
//! Shapiro–Wilk W and p all to 1e-9 relative (measured: ≤ 4e-16, since the code follows SciPy's
//! algorithms operation by operation); and each test takes the same path (exact / asymptotic /
//! permutation) as SciPy's `method='auto'`.

use bench::stats::{
    Method, MethodUsed, mann_whitney_u_with, shapiro_wilk, summarize, wilcoxon_signed_rank_with,
};
use serde_json::Value;

const FIXTURES: &str = include_str!("fixtures/stats.json");

fn fixtures() -> Value {
    serde_json::from_str(FIXTURES).expect("fixture JSON parses")
}

fn floats(v: &Value) -> Vec<f64> {
    v.as_array()
        .expect("array")
        .iter()
        .map(|x| x.as_f64().expect("number"))
        .collect()
}

fn num(case: &Value, key: &str) -> f64 {
    case[key]
        .as_f64()
        .unwrap_or_else(|| panic!("{key} is a number in {}", case["name"]))
}

/// |got − want| ≤ rel·max(|want|, floor).
fn assert_close(what: &str, got: f64, want: f64, rel: f64, floor: f64) {
    let tol = rel * want.abs().max(floor);
    assert!(
        (got - want).abs() <= tol,
        "{what}: got {got:e}, SciPy {want:e} (|diff| {:e} > {tol:e})",
        (got - want).abs()
    );
}

fn method(case: &Value) -> Method {
    match case["method"].as_str() {
        Some("auto") => Method::Auto,
        Some("exact") => Method::Exact,
        Some("asymptotic") => Method::Asymptotic,
        other => panic!("unknown method {other:?}"),
    }
}

fn used(case: &Value) -> MethodUsed {
    match case["used"].as_str() {
        Some("exact") => MethodUsed::Exact,
        Some("asymptotic") => MethodUsed::Asymptotic,
        Some("permutation") => MethodUsed::Permutation,
        other => panic!("unknown path {other:?}"),
    }
}

#[test]
fn summaries_match_numpy() {
    let f = fixtures();
    let cases = f["summary"].as_array().expect("summary cases");
    assert!(cases.len() >= 10);
    for c in cases {
        let name = c["name"].as_str().unwrap_or("?");
        let s = summarize(&floats(&c["x"])).expect("valid sample");
        assert_eq!(s.n as u64, c["n"].as_u64().expect("n"), "{name} n");
        for (what, got) in [
            ("mean", s.mean),
            ("median", s.median),
            ("q1", s.q1),
            ("q3", s.q3),
            ("iqr", s.iqr),
            ("min", s.min),
            ("max", s.max),
        ] {
            assert_close(&format!("{name} {what}"), got, num(c, what), 1e-12, 1e-300);
        }
        match c["sd"].as_f64() {
            Some(sd) => assert_close(&format!("{name} sd"), s.sd, sd, 1e-10, 1e-300),
            None => assert!(s.sd.is_nan(), "{name}: sd of one value is NaN"),
        }
    }
}

#[test]
fn mann_whitney_matches_scipy() {
    let f = fixtures();
    let cases = f["mann_whitney"].as_array().expect("mann_whitney cases");
    assert!(cases.len() >= 25);
    for c in cases {
        let name = c["name"].as_str().unwrap_or("?");
        let r = mann_whitney_u_with(&floats(&c["x"]), &floats(&c["y"]), method(c)).expect("valid");
        assert_eq!(r.method, used(c), "{name} path");
        assert_close(&format!("{name} U1"), r.u1, num(c, "u1"), 1e-12, 1.0);
        assert_close(&format!("{name} p"), r.p_value, num(c, "p"), 1e-9, 1e-300);
    }
}

#[test]
fn wilcoxon_matches_scipy() {
    let f = fixtures();
    let cases = f["wilcoxon"].as_array().expect("wilcoxon cases");
    assert!(cases.len() >= 25);
    for c in cases {
        let name = c["name"].as_str().unwrap_or("?");
        let r = wilcoxon_signed_rank_with(&floats(&c["x"]), &floats(&c["y"]), method(c))
            .expect("valid");
        assert_eq!(
            r.zeros as u64,
            c["zeros"].as_u64().expect("zeros"),
            "{name} zeros"
        );
        if r.n == 0 {
            // All differences zero: we report "nothing to test" (SciPy: 1 for N ≤ 13).
            assert_eq!(r.method, MethodUsed::Degenerate, "{name} path");
        } else {
            assert_eq!(r.method, used(c), "{name} path");
        }
        assert_close(
            &format!("{name} statistic"),
            r.statistic,
            num(c, "statistic"),
            1e-12,
            1.0,
        );
        assert_close(&format!("{name} p"), r.p_value, num(c, "p"), 1e-9, 1e-300);
    }
}

#[test]
fn shapiro_wilk_matches_scipy() {
    let f = fixtures();
    let cases = f["shapiro"].as_array().expect("shapiro cases");
    assert!(cases.len() >= 20);
    for c in cases {
        let name = c["name"].as_str().unwrap_or("?");
        let r = shapiro_wilk(&floats(&c["x"])).expect("valid");
        assert_close(&format!("{name} W"), r.w, num(c, "w"), 1e-9, 1e-300);
        assert_close(&format!("{name} p"), r.p_value, num(c, "p"), 1e-9, 1e-300);
    }
}
