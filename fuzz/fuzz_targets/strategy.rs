//! Strategy names, sensing modes and belief kinds.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|name: &str| {
    let _ = explore::strategy::Strategy::preset(name);
    let _ = name.parse::<explore::strategy::SensingMode>();
    let _ = name.parse::<sense::belief::BeliefKind>();
});
