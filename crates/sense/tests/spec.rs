//! Sensor specs: Display round-trips through FromStr.

use proptest::prelude::*;
use sense::{Range, SensorSpec};

fn arb_range() -> impl Strategy<Value = Range> {
    let positive = prop_oneof![1e-3f64..1e4, (1u32..500).prop_map(f64::from)];
    (positive, any::<bool>()).prop_map(|(v, c)| if c { Range::Cells(v) } else { Range::Metres(v) })
}

fn arb_spec() -> impl Strategy<Value = SensorSpec> {
    prop_oneof![
        arb_range().prop_map(|r| SensorSpec::Los { r }),
        arb_range().prop_map(|r| SensorSpec::Footprint { r }),
        arb_range().prop_map(|r| SensorSpec::Square { r }),
        (
            arb_range(),
            prop_oneof![Just(360.0), 1e-3f64..=360.0],
            0.01f64..=360.0
        )
            .prop_map(|(r, fov_deg, res_deg)| SensorSpec::Lidar {
                r,
                fov_deg,
                res_deg
            }),
    ]
}

proptest! {
    #[test]
    fn display_round_trips(spec in arb_spec()) {
        let text = spec.to_string();
        let back: SensorSpec = text.parse().expect("canonical form parses");
        prop_assert_eq!(back, spec);
        prop_assert_eq!(back.to_string(), text);
    }

    #[test]
    fn garbage_never_panics(s in "[a-z:=,.0-9c -]{0,24}") {
        let _ = s.parse::<SensorSpec>();
    }
}
