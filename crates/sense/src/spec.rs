//! Sensor specs: the textual description of a sensor (`los:r=5`, `footprint:r=3`,
//! `lidar:r=8,fov=180,res=1`, `los:r=4c`, `square:r=3.5`, `sonar`, `laser-limited-sonar`,
//! `laser`) and how it is turned into a [`Sensor`].
//!
//! Ranges are in metres, or in cells with a `c` suffix (`r=4c`, as in the multi-robot
//! study's 4-cell sensor). Angles are in degrees. Lidar defaults: `fov=180`, `res=1`
//! (Holz et al.'s scanner). Kinds and keys are lower-case; whitespace around items is
//! ignored. `Display` writes the canonical form, which parses back to the same spec.
//!
//! Yamauchi's sensor presets (his robot's 10 ft usable sonar range is the default `r` of
//! all three):
//! - `sonar[:r=R]`: the ring of 16 sonar transducers alone ([`crate::sonar`]);
//! - `laser-limited-sonar[:r=R]`: the ring, each reading capped by the planar laser;
//! - `laser[:r=R]`: the planar laser alone, swept over 360° at 1° — the same as
//!   `lidar:r=R,fov=360,res=1`, which is its canonical form.
//!
//! The sonar kinds need the evidence-grid belief (they add graded evidence).

use std::fmt;
use std::str::FromStr;

use crate::error::SenseError;
use crate::footprint::FootprintSensor;
use crate::lidar::{LidarSensor, MIN_LIDAR_RES_DEG};
use crate::los::LosSensor;
use crate::sensor::Sensor;
use crate::sonar::{SonarMode, SonarParams, SonarSensor};
use crate::square::SquareSensor;

/// A sensor range: metres (converted with the map's resolution) or cells.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Range {
    /// A range in metres.
    Metres(f64),
    /// A range in cells (written with a `c` suffix).
    Cells(f64),
}

impl Range {
    /// The range in cells for a map of `resolution` metres per cell.
    pub fn cells(self, resolution: f64) -> f64 {
        match self {
            Range::Metres(m) => grid::units::cells(m, resolution),
            Range::Cells(c) => c,
        }
    }
}

impl fmt::Display for Range {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Range::Metres(m) => write!(f, "{}", grid::Num(*m)),
            Range::Cells(c) => write!(f, "{c}c"),
        }
    }
}

/// A sensor described by kind and parameters, before it is built for a map resolution.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SensorSpec {
    /// The ideal 360° line-of-sight laser ([`LosSensor`]).
    Los {
        /// Range.
        r: Range,
    },
    /// Every cell within range, through walls ([`FootprintSensor`]).
    Footprint {
        /// Range.
        r: Range,
    },
    /// Explore-Bench's square window of half-side `r` ([`SquareSensor`]).
    Square {
        /// Half-side of the window.
        r: Range,
    },
    /// A laser scanner with a field of view ([`LidarSensor`]).
    Lidar {
        /// Range.
        r: Range,
        /// Field of view in degrees, in (0, 360].
        fov_deg: f64,
        /// Angular resolution in degrees, in [0.01, 360].
        res_deg: f64,
    },
    /// Yamauchi's ring of sonar transducers ([`SonarSensor`]), alone or laser-limited.
    Sonar {
        /// Range.
        r: Range,
        /// Whether each reading is capped by the planar laser (`laser-limited-sonar`).
        laser_limited: bool,
    },
}

/// The coarsest cells the sonar kinds run on, in metres. Measured with `cf-rr` on the
/// generated office and hospital (seeds 0–2): at 0.05 m both kinds cover over 99 %, at
/// 0.1 m laser-limited sonar 81–96 %; at 0.15 m it stopped at 2.4 % on one office, and at
/// 0.5 m (the office's default) both stop after a move or two. A cone 25° wide and an echo
/// band a cell deep mark whole corridors occupied when a cell is a large share of the
/// 3 m range.
pub const SONAR_MAX_CELL_M: f64 = 0.1;

/// The default range of Yamauchi's presets: his sonar's usable 10 ft.
pub const YAMAUCHI_RANGE: Range = Range::Metres(crate::sonar::DEFAULT_RANGE_M);

const EXPECT_RANGE: &str = "a positive number of metres (or cells with suffix c)";
const EXPECT_FOV: &str = "a field of view in (0, 360] degrees";
const EXPECT_RES: &str = "an angular resolution in [0.01, 360] degrees";

impl SensorSpec {
    /// Build the sensor for a map of `resolution` metres per cell. For the sonar kinds this
    /// is the planar 360° laser of the same range (what laser-limiting and predicted scans
    /// use); the ring itself comes from [`SensorSpec::sonar`].
    pub fn build(&self, resolution: f64) -> Result<Box<dyn Sensor>, SenseError> {
        if !(resolution.is_finite() && resolution > 0.0) {
            return Err(SenseError::BadResolution(resolution));
        }
        let r = self.range_cells(resolution);
        let out_of_bounds = |max| SenseError::RangeOutOfBounds {
            spec: self.to_string(),
            cells: r,
            resolution,
            max,
        };
        let max = match self {
            SensorSpec::Los { .. } => crate::ray_template::MAX_TEMPLATE_RANGE_CELLS,
            SensorSpec::Square { .. } => crate::square::MAX_SQUARE_HALF_CELLS,
            _ => crate::footprint::MAX_RANGE_CELLS,
        };
        if r.is_nan() || r < 1.0 {
            return Err(out_of_bounds(max));
        }
        let built: Result<Box<dyn Sensor>, SenseError> = (|| {
            Ok(match *self {
                SensorSpec::Los { .. } => Box::new(LosSensor::new(r)?) as Box<dyn Sensor>,
                SensorSpec::Footprint { .. } => Box::new(FootprintSensor::new(r)?),
                SensorSpec::Square { .. } => Box::new(SquareSensor::new(r)?),
                SensorSpec::Lidar {
                    fov_deg, res_deg, ..
                } => Box::new(LidarSensor::new(r, fov_deg, res_deg)?),
                SensorSpec::Sonar { .. } => Box::new(LidarSensor::new(r, 360.0, 1.0)?),
            })
        })();
        built.map_err(|e| match e {
            SenseError::BadRange { max, .. } => out_of_bounds(max),
            e => e,
        })
    }

    /// An upper bound of the bytes building this sensor for `resolution` metres per cell
    /// takes beyond the map's own arrays: the `los` kind's ray template
    /// ([`ray_template::build_bytes`](crate::ray_template::build_bytes), up to about
    /// 480 MiB); the other kinds keep a row or a beam list (0 here).
    pub fn build_bytes(&self, resolution: f64) -> u64 {
        match self {
            SensorSpec::Los { .. } => {
                crate::ray_template::build_bytes(self.range_cells(resolution))
            }
            _ => 0,
        }
    }

    /// Which sonar ring this is, if it is one.
    pub fn sonar_mode(&self) -> Option<SonarMode> {
        match *self {
            SensorSpec::Sonar { laser_limited, .. } => Some(if laser_limited {
                SonarMode::LaserLimited
            } else {
                SonarMode::Sonar
            }),
            _ => None,
        }
    }

    /// The sonar ring of a sonar kind for a map of `resolution` metres per cell (Yamauchi's
    /// parameters, [`SonarParams::yamauchi`], with this spec's range); `None` for the others.
    /// Cells coarser than [`SONAR_MAX_CELL_M`] are refused.
    pub fn sonar(&self, resolution: f64) -> Option<Result<SonarSensor, SenseError>> {
        let SensorSpec::Sonar { r, .. } = *self else {
            return None;
        };
        if !(resolution.is_finite() && resolution > 0.0) {
            return Some(Err(SenseError::BadResolution(resolution)));
        }
        if resolution > SONAR_MAX_CELL_M * (1.0 + 1e-9) {
            return Some(Err(SenseError::SonarTooCoarse(resolution)));
        }
        let params = SonarParams {
            range: r.cells(resolution),
            ..SonarParams::yamauchi(resolution)
        };
        Some(SonarSensor::new(params).map_err(SenseError::from))
    }

    /// The 360° version of this sensor (for a sweep on arrival): a lidar with `fov=360`;
    /// the circular sensors unchanged.
    pub fn sweep(&self) -> SensorSpec {
        match *self {
            SensorSpec::Lidar { r, res_deg, .. } => SensorSpec::Lidar {
                r,
                fov_deg: 360.0,
                res_deg,
            },
            other => other,
        }
    }

    /// The range in cells for a map of `resolution` metres per cell.
    pub fn range_cells(&self, resolution: f64) -> f64 {
        self.range().cells(resolution)
    }

    /// The range as written.
    pub fn range(&self) -> Range {
        match *self {
            SensorSpec::Los { r }
            | SensorSpec::Footprint { r }
            | SensorSpec::Square { r }
            | SensorSpec::Lidar { r, .. }
            | SensorSpec::Sonar { r, .. } => r,
        }
    }
}

impl fmt::Display for SensorSpec {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SensorSpec::Los { r } => write!(f, "los:r={r}"),
            SensorSpec::Footprint { r } => write!(f, "footprint:r={r}"),
            SensorSpec::Square { r } => write!(f, "square:r={r}"),
            SensorSpec::Lidar {
                r,
                fov_deg,
                res_deg,
            } => {
                write!(f, "lidar:r={r},fov={fov_deg},res={res_deg}")
            }
            SensorSpec::Sonar {
                r,
                laser_limited: false,
            } => write!(f, "sonar:r={r}"),
            SensorSpec::Sonar {
                r,
                laser_limited: true,
            } => write!(f, "laser-limited-sonar:r={r}"),
        }
    }
}

/// Parse a finite number (rejecting `inf`, `nan`).
fn number(s: &str) -> Option<f64> {
    s.parse::<f64>().ok().filter(|v| v.is_finite())
}

fn parse_range(value: &str) -> Option<Range> {
    let (num, cells) = match value.strip_suffix('c') {
        Some(n) => (n, true),
        None => (value.strip_suffix('m').unwrap_or(value), false),
    };
    let v = number(num.trim_end()).filter(|&v| v > 0.0)?;
    Some(if cells {
        Range::Cells(v)
    } else {
        Range::Metres(v)
    })
}

impl FromStr for SensorSpec {
    type Err = SenseError;

    fn from_str(spec: &str) -> Result<Self, SenseError> {
        let (kind, items) = match spec.split_once(':') {
            Some((k, rest)) => (k.trim(), Some(rest)),
            None => (spec.trim(), None),
        };
        let valid: &'static str = match kind {
            "los" | "footprint" | "square" | "sonar" | "laser-limited-sonar" | "laser" => "r",
            "lidar" => "r, fov, res",
            _ => {
                return Err(SenseError::UnknownKind {
                    spec: spec.into(),
                    kind: kind.into(),
                });
            }
        };
        let mut r = None;
        let mut fov_deg = 180.0;
        let mut res_deg = 1.0;
        let mut given: Vec<&str> = Vec::with_capacity(3);
        for item in items.into_iter().flat_map(|s| s.split(',')) {
            let Some((key, value)) = item.split_once('=') else {
                return Err(SenseError::Malformed {
                    spec: spec.into(),
                    item: item.trim().into(),
                });
            };
            let (key, value) = (key.trim(), value.trim());
            let bad = |expected: &str| SenseError::BadValue {
                spec: spec.into(),
                key: key.into(),
                expected: expected.into(),
                found: value.into(),
            };
            match (key, kind) {
                ("r", _) => r = Some(parse_range(value).ok_or_else(|| bad(EXPECT_RANGE))?),
                ("fov", "lidar") => {
                    fov_deg = number(value)
                        .filter(|&v| v > 0.0 && v <= 360.0)
                        .ok_or_else(|| bad(EXPECT_FOV))?;
                }
                ("res", "lidar") => {
                    res_deg = number(value)
                        .filter(|v| (MIN_LIDAR_RES_DEG..=360.0).contains(v))
                        .ok_or_else(|| bad(EXPECT_RES))?;
                }
                _ => {
                    return Err(SenseError::UnknownKey {
                        spec: spec.into(),
                        key: key.into(),
                        valid,
                    });
                }
            }
            if given.contains(&key) {
                return Err(SenseError::DuplicateKey {
                    spec: spec.into(),
                    key: key.into(),
                });
            }
            given.push(key);
        }
        let yamauchi = matches!(kind, "sonar" | "laser-limited-sonar" | "laser");
        let r = match r {
            Some(r) => r,
            None if yamauchi => YAMAUCHI_RANGE,
            None => {
                return Err(SenseError::MissingKey {
                    spec: spec.into(),
                    key: "r",
                    expected: EXPECT_RANGE,
                });
            }
        };
        Ok(match kind {
            "los" => SensorSpec::Los { r },
            "footprint" => SensorSpec::Footprint { r },
            "square" => SensorSpec::Square { r },
            "sonar" | "laser-limited-sonar" => SensorSpec::Sonar {
                r,
                laser_limited: kind == "laser-limited-sonar",
            },
            "laser" => SensorSpec::Lidar {
                r,
                fov_deg: 360.0,
                res_deg: 1.0,
            },
            _ => SensorSpec::Lidar {
                r,
                fov_deg,
                res_deg,
            },
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(s: &str) -> Result<SensorSpec, SenseError> {
        s.parse()
    }

    #[test]
    fn sonar_refuses_cells_coarser_than_a_tenth_of_a_metre() {
        for kind in ["sonar", "laser-limited-sonar"] {
            let spec = parse(kind).unwrap();
            assert!(spec.sonar(0.1).unwrap().is_ok());
            assert!(spec.sonar(0.05).unwrap().is_ok());
            match spec.sonar(0.5).unwrap() {
                Err(SenseError::SonarTooCoarse(r)) => assert_eq!(r, 0.5),
                other => panic!("{kind}: expected SonarTooCoarse, got {other:?}"),
            }
        }
        assert!(parse("laser").unwrap().sonar(0.5).is_none());
    }

    #[test]
    fn parses_the_documented_forms() {
        assert_eq!(
            parse("los:r=5"),
            Ok(SensorSpec::Los {
                r: Range::Metres(5.0)
            })
        );
        assert_eq!(
            parse("los:r=4c"),
            Ok(SensorSpec::Los {
                r: Range::Cells(4.0)
            })
        );
        assert_eq!(
            parse("footprint:r=3"),
            Ok(SensorSpec::Footprint {
                r: Range::Metres(3.0)
            })
        );
        assert_eq!(
            parse("lidar:r=8,fov=180,res=1"),
            Ok(SensorSpec::Lidar {
                r: Range::Metres(8.0),
                fov_deg: 180.0,
                res_deg: 1.0
            })
        );
        assert_eq!(
            parse(" lidar : r = 2.5c , res=0.5"),
            Ok(SensorSpec::Lidar {
                r: Range::Cells(2.5),
                fov_deg: 180.0,
                res_deg: 0.5
            })
        );
        assert_eq!(
            parse("los:r=1.5m"),
            Ok(SensorSpec::Los {
                r: Range::Metres(1.5)
            })
        );
    }

    #[test]
    fn error_messages_name_spec_key_and_expectation() {
        let msg = |s: &str| parse(s).expect_err("should fail").to_string();
        assert_eq!(
            msg("lidar:r=x"),
            "sensor 'lidar:r=x': key 'r': expected a positive number of metres \
             (or cells with suffix c), found \"x\""
        );
        assert_eq!(
            msg("radar:r=3"),
            "sensor 'radar:r=3': unknown kind 'radar': expected one of los, footprint, lidar, square, \
             sonar, laser-limited-sonar, laser"
        );
        assert_eq!(
            msg("los:r=3,fov=90"),
            "sensor 'los:r=3,fov=90': unknown key 'fov': expected one of r"
        );
        assert_eq!(
            msg("lidar:r=3,range=9"),
            "sensor 'lidar:r=3,range=9': unknown key 'range': expected one of r, fov, res"
        );
        assert_eq!(
            msg("los"),
            "sensor 'los': missing key 'r': expected a positive number of metres \
             (or cells with suffix c)"
        );
        assert_eq!(msg("los:r"), "sensor 'los:r': item 'r': expected key=value");
        assert_eq!(
            msg("los:r=1,r=2"),
            "sensor 'los:r=1,r=2': key 'r' given more than once"
        );
        assert_eq!(
            msg("lidar:r=1,fov=0"),
            "sensor 'lidar:r=1,fov=0': key 'fov': expected a field of view in (0, 360] degrees, \
             found \"0\""
        );
        assert_eq!(
            msg("lidar:r=1,res=-1"),
            "sensor 'lidar:r=1,res=-1': key 'res': expected an angular resolution in \
             [0.01, 360] degrees, found \"-1\""
        );
        for bad in [
            "los:r=0",
            "los:r=-2",
            "los:r=inf",
            "los:r=NaN",
            "los:r=c",
            "los:r=3cc",
        ] {
            assert!(
                matches!(parse(bad), Err(SenseError::BadValue { .. })),
                "{bad}"
            );
        }
    }

    /// Regression: `los:r=0.0001` was built as a sensor of 0.001 cells, which sees only the
    /// robot's own cell: the run ended at once with "no reachable frontier" and exit 0.
    #[test]
    fn regression_sensor_range_under_a_cell_is_refused() {
        for (spec, res) in [
            ("los:r=0.0001", 0.1),
            ("lidar:r=0.04", 0.05),
            ("footprint:r=0.5c", 1.0),
        ] {
            let e = parse(spec)
                .expect("valid")
                .build(res)
                .err()
                .expect("refused");
            assert!(
                matches!(e, SenseError::RangeOutOfBounds { .. }),
                "{spec}: {e}"
            );
            let msg = e.to_string();
            assert!(msg.contains("expected 1 to"), "{msg}");
            assert!(msg.contains("sees only the cell it stands on"), "{msg}");
        }
        assert!(parse("los:r=0.1").expect("valid").build(0.1).is_ok());
    }

    #[test]
    fn too_long_a_range_is_named_in_cells_and_metres() {
        let e = parse("los:r=200")
            .expect("valid")
            .build(0.5)
            .err()
            .expect("refused");
        assert_eq!(
            e.to_string(),
            "sensor 'los:r=200': range 400 cells at 0.5 m per cell: expected 1 to 256 cells \
             (0.5 to 128 m)"
        );
    }

    /// Regression: `square:r=1e6c` was accepted (the plain sensors' million cells) and cast
    /// 8 million rays a scan whatever the map's size: `frontier explore --env office` (a
    /// 50 x 40 map) ran for more than a minute. The window is bounded at 1024 cells.
    #[test]
    fn regression_square_window_past_its_bound_is_refused() {
        let e = parse("square:r=1e6c")
            .expect("valid")
            .build(0.5)
            .err()
            .expect("refused");
        assert_eq!(
            e.to_string(),
            "sensor 'square:r=1000000c': range 1000000 cells at 0.5 m per cell: expected 1 to \
             1024 cells (0.5 to 512 m)"
        );
        assert!(parse("square:r=1024c").expect("valid").build(0.5).is_ok());
        assert!(parse("square:r=1025c").expect("valid").build(0.5).is_err());
    }

    #[test]
    fn display_round_trips() {
        for s in [
            "los:r=5",
            "los:r=4c",
            "footprint:r=0.25",
            "lidar:r=8,fov=180,res=1",
            "sonar:r=3.048",
            "laser-limited-sonar:r=2",
        ] {
            let spec = parse(s).expect("valid");
            assert_eq!(spec.to_string(), s);
            assert_eq!(parse(&spec.to_string()), Ok(spec));
        }
        assert_eq!(
            parse("lidar:r=8").expect("valid").to_string(),
            "lidar:r=8,fov=180,res=1"
        );
    }

    #[test]
    fn build_sweep_and_ranges() {
        let spec = parse("lidar:r=2,fov=90,res=2").expect("valid");
        assert_eq!(spec.range_cells(0.5), 4.0);
        assert_eq!(
            spec.sweep(),
            parse("lidar:r=2,fov=360,res=2").expect("valid")
        );
        let s = spec.build(0.5).expect("builds");
        assert_eq!(s.range_cells(), 4.0);
        assert!(!s.is_omnidirectional());
        assert!(
            spec.sweep()
                .build(0.5)
                .expect("builds")
                .is_omnidirectional()
        );
        let los = parse("los:r=4c").expect("valid");
        assert_eq!(los.sweep(), los);
        assert_eq!(los.build(0.05).expect("builds").range_cells(), 4.0);
        assert!(los.build(0.0).is_err());
        assert!(los.build(f64::NAN).is_err());
        // 100 m at 5 cm is 2000 cells: too large for a template, an error and no panic.
        assert!(matches!(
            parse("los:r=100").expect("valid").build(0.05),
            Err(SenseError::RangeOutOfBounds { .. })
        ));
        assert!(parse("footprint:r=3").expect("valid").build(0.5).is_ok());
    }

    #[test]
    fn yamauchi_presets() {
        let ten_ft = Range::Metres(crate::sonar::DEFAULT_RANGE_M);
        assert_eq!(
            parse("sonar"),
            Ok(SensorSpec::Sonar {
                r: ten_ft,
                laser_limited: false
            })
        );
        assert_eq!(
            parse("laser-limited-sonar:r=2"),
            Ok(SensorSpec::Sonar {
                r: Range::Metres(2.0),
                laser_limited: true
            })
        );
        assert_eq!(
            parse("laser"),
            Ok(SensorSpec::Lidar {
                r: ten_ft,
                fov_deg: 360.0,
                res_deg: 1.0
            })
        );
        assert_eq!(parse("sonar").unwrap().sonar_mode(), Some(SonarMode::Sonar));
        assert_eq!(
            parse("laser-limited-sonar").unwrap().sonar_mode(),
            Some(SonarMode::LaserLimited)
        );
        assert_eq!(parse("laser").unwrap().sonar_mode(), None);
        assert!(parse("laser").unwrap().sonar(0.1).is_none());
        let ring = parse("sonar:r=2").unwrap().sonar(0.1).unwrap().unwrap();
        assert!((ring.params().range - 20.0).abs() < 1e-9);
        // The planar laser beside the ring: 360°, same range.
        let laser = parse("sonar:r=2").unwrap().build(0.1).unwrap();
        assert!(laser.is_omnidirectional());
        assert!((laser.range_cells() - 20.0).abs() < 1e-9);
        assert!(matches!(
            parse("sonar:fov=30"),
            Err(SenseError::UnknownKey { .. })
        ));
        assert!(parse("sonar").unwrap().sonar(0.0).unwrap().is_err());
    }
}
