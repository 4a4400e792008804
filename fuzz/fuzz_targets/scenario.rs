//! Scenario files (TOML) resolved into a plan, as `frontier bench FILE` does.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|text: &str| {
    let src = bench::Source {
        file: "fuzz.toml".into(),
        text: text.into(),
        dir: None,
    };
    let _ = bench::Plan::resolve(&src, bench::Unbuilt::Error);
});
