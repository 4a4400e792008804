//! Print a generated environment as ASCII art: `#` occupied, `.` free.
//!
//! `cargo run -p world --example print_env -- office 7 [width_m height_m] [resolution]`
//! With `--rooms`, free cells show their room id (mod 36) as 0-9a-z instead of `.`.

use std::process::ExitCode;

use grid::Occ;
use world::{EnvKind, EnvSpec, generate};

fn main() -> ExitCode {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    let show_rooms = args.iter().any(|a| a == "--rooms");
    args.retain(|a| a != "--rooms");
    let kind: EnvKind = match args.first().map(|s| s.parse()) {
        Some(Ok(k)) => k,
        Some(Err(e)) => {
            eprintln!("{e}");
            return ExitCode::FAILURE;
        }
        None => {
            for k in EnvKind::all() {
                let i = k.info();
                eprintln!(
                    "{:<9} {} m x {} m at {} m: {}",
                    k, i.size_m.0, i.size_m.1, i.resolution, i.description
                );
            }
            return ExitCode::SUCCESS;
        }
    };
    let num = |i: usize| args.get(i).and_then(|s| s.parse::<f64>().ok());
    let mut spec = EnvSpec::new(kind, args.get(1).and_then(|s| s.parse().ok()).unwrap_or(0));
    if let (Some(w), Some(h)) = (num(2), num(3)) {
        spec = spec.with_size(w, h);
    }
    if let Some(r) = num(4) {
        spec = spec.with_resolution(r);
    }
    let env = match generate(&spec) {
        Ok(e) => e,
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::FAILURE;
        }
    };
    let digits = b"0123456789abcdefghijklmnopqrstuvwxyz";
    let w = env.map.width();
    for (y, row) in env.map.cells.data().chunks(w).enumerate() {
        let line: String = row
            .iter()
            .enumerate()
            .map(|(x, &c)| match c {
                Occ::Free => match (&env.rooms, show_rooms) {
                    (Some(r), true) => digits[r[y * w + x] as usize % 36] as char,
                    _ => '.',
                },
                Occ::Occupied => '#',
                Occ::Unknown => ' ',
            })
            .collect();
        println!("{line}");
    }
    let (free, occ, _) = env.map.counts();
    println!(
        "{}: {} x {} cells at {} m, {free} free, {occ} occupied, {} rooms, fingerprint {:016x}",
        env.name,
        w,
        env.map.height(),
        env.map.resolution,
        env.room_count,
        env.fingerprint()
    );
    ExitCode::SUCCESS
}
