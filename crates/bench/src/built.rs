//! Which strategy presets can run yet: a preset whose pieces are still placeholders
//! (`todo!()`) panics in a tiny dry run, and a suite then says so and runs the rest
//! (issue 9, "A suite whose strategies are not built yet says so and runs the rest").

use std::collections::BTreeMap;
use std::sync::{Mutex, OnceLock};

use explore::strategy::Strategy;
use grid::{Grid, GridMap, Occ};

/// Whether `strategy` completes a dry run of two robots on a tiny open map; the answer is
/// cached per preset name. `Err` carries the panic message.
pub fn check(strategy: &Strategy) -> Result<(), String> {
    static CACHE: OnceLock<Mutex<BTreeMap<String, Result<(), String>>>> = OnceLock::new();
    let cache = CACHE.get_or_init(|| Mutex::new(BTreeMap::new()));
    let key = format!("{strategy:?}");
    if let Some(r) = cache.lock().map_err(|e| e.to_string())?.get(&key) {
        return r.clone();
    }
    let result = dry_run(strategy);
    cache
        .lock()
        .map_err(|e| e.to_string())?
        .insert(key, result.clone());
    result
}

/// The panic message of a caught panic payload.
pub fn panic_message(payload: &(dyn std::any::Any + Send)) -> String {
    if let Some(s) = payload.downcast_ref::<&str>() {
        (*s).to_string()
    } else if let Some(s) = payload.downcast_ref::<String>() {
        s.clone()
    } else {
        "panicked".to_string()
    }
}

thread_local! {
    static QUIET: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// Run `f` with panic messages of this thread silenced (other threads still report theirs):
/// a dry run of an unbuilt strategy is expected to panic.
fn quietly<R>(f: impl FnOnce() -> R) -> R {
    static HOOK: OnceLock<()> = OnceLock::new();
    HOOK.get_or_init(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if !QUIET.with(|q| q.get()) {
                previous(info);
            }
        }));
    });
    QUIET.with(|q| q.set(true));
    let r = f();
    QUIET.with(|q| q.set(false));
    r
}

fn dry_run(strategy: &Strategy) -> Result<(), String> {
    // A 14 x 10 room with a wall stub, so that there are several frontier regions.
    let (w, h) = (14usize, 10usize);
    let mut cells = Grid::new(w, h, Occ::Free);
    for y in 0..h {
        for x in 0..w {
            let wall = x == 0 || y == 0 || x == w - 1 || y == h - 1 || (x == 7 && y < 6);
            if wall {
                cells[y * w + x] = Occ::Occupied;
            }
        }
    }
    let map = GridMap::new(cells, 0.5);
    let mut cfg = sim::RunConfig::new(strategy.clone());
    cfg.sensor = sense::SensorSpec::Los {
        r: sense::Range::Cells(3.0),
    };
    cfg.robots = 2;
    cfg.max_moves = 400;
    let outcome = quietly(|| std::panic::catch_unwind(|| sim::run(&map, &cfg).map(|_| ())));
    match outcome {
        Ok(Ok(())) => Ok(()),
        Ok(Err(e)) => Err(e.to_string()),
        Err(payload) => Err(panic_message(payload.as_ref())),
    }
}
