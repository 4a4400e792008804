//! The line of sight a batch of runs shares: a study's trials, or a Python batch, run many
//! times on each of a few maps, and what the line-of-sight sensor sees from a cell depends
//! on the map alone. [`BatchSights`] makes one [`SightCache`] per map and range that at
//! least two runs of the batch share, on first use, all within one budget; each run takes
//! its map's ([`Session::share_sight`](crate::Session::share_sight)), with the same
//! results as without.

use std::collections::BTreeMap;
use std::sync::{Arc, OnceLock};

use grid::GridMap;
use grid::memory::Available;
use sense::{LosSensor, SensorSpec, SightBudget, SightCache};

/// The most a batch's remembered line of sight takes: about three times what the
/// `faigl2013` suite's three maps need at its three ranges (76 MiB).
pub const BATCH_SIGHT_BYTES: u64 = 256 << 20;

/// The line of sight of each map of a batch, per line-of-sight range (module doc).
pub struct BatchSights {
    /// Per run of the batch, its cache's index in `caches`, if it shares one.
    of_run: Vec<Option<usize>>,
    /// Per (map, range) shared: its sensor, and its cache once asked for (`None` inside if
    /// the budget could not pay for it).
    caches: Vec<(LosSensor, OnceLock<Option<Arc<SightCache>>>)>,
    budget: Arc<SightBudget>,
}

impl BatchSights {
    /// The budget of a batch's caches: [`BATCH_SIGHT_BYTES`], or what the tighter of
    /// `budget_mb` (a user's `--memory-mb`) and the memory `available` leaves beside runs
    /// that take `at_once` bytes together. The caches are an aid, never a reason to refuse
    /// a batch.
    pub fn budget(budget_mb: Option<u64>, available: Option<Available>, at_once: u64) -> u64 {
        crate::memory::limit(budget_mb, available).map_or(BATCH_SIGHT_BYTES, |l| {
            BATCH_SIGHT_BYTES.min(l.bytes.saturating_sub(at_once))
        })
    }

    /// The caches for a batch whose runs are `runs`, in order: per run, a key naming its
    /// map (runs with equal keys run on the same map), the map, and the run's sensor; all
    /// within `budget` bytes. Runs that do not sense with the line-of-sight sensor, or
    /// whose map and range no other run shares, get none.
    pub fn new<'a>(
        runs: impl IntoIterator<Item = (usize, &'a GridMap, SensorSpec)>,
        budget: u64,
    ) -> Self {
        // Per distinct (map, sensor) the cache it would use, and per cache its runs.
        let mut setups: BTreeMap<(usize, String), Option<usize>> = BTreeMap::new();
        let mut found: Vec<((usize, i64), LosSensor, usize)> = Vec::new();
        let mut of_run = Vec::new();
        for (map_key, map, spec) in runs {
            let k = *setups
                .entry((map_key, spec.to_string()))
                .or_insert_with(|| {
                    let SensorSpec::Los { r } = spec else {
                        return None;
                    };
                    let sensor = LosSensor::new(r.cells(map.resolution)).ok()?;
                    let key = (map_key, sensor.template().max_d2());
                    Some(match found.iter().position(|(k, ..)| *k == key) {
                        Some(k) => k,
                        None => {
                            found.push((key, sensor, 0));
                            found.len() - 1
                        }
                    })
                });
            if let Some(k) = k {
                found[k].2 += 1;
            }
            of_run.push(k);
        }
        for k in of_run.iter_mut() {
            if k.is_some_and(|k| found[k].2 < 2) {
                *k = None;
            }
        }
        Self {
            of_run,
            caches: found
                .into_iter()
                .map(|(_, sensor, _)| (sensor, OnceLock::new()))
                .collect(),
            budget: SightBudget::new(budget),
        }
    }

    /// The cache run `run` of the batch (on `map`) shares, made on first use if the
    /// budget allows.
    pub fn get(&self, run: usize, map: &GridMap) -> Option<Arc<SightCache>> {
        let k = (*self.of_run.get(run)?)?;
        let (sensor, cache) = &self.caches[k];
        cache
            .get_or_init(|| {
                SightCache::new(&map.cells, sensor.clone(), self.budget.clone()).map(Arc::new)
            })
            .clone()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use grid::{Grid, Occ};

    fn map(w: usize) -> GridMap {
        GridMap::new(Grid::new(w, 10, Occ::Free), 0.1)
    }

    /// Runs share a cache only with runs on the same map at the same range (two ranges
    /// with the same cells in range are one), and a run alone on its map and range gets
    /// none; nor do other sensors.
    #[test]
    fn runs_share_caches_by_map_and_range() {
        let (a, b) = (map(10), map(12));
        let los = |m: f64| format!("los:r={m}").parse::<SensorSpec>().expect("los");
        let lidar = "lidar:r=1".parse::<SensorSpec>().expect("lidar");
        let runs = [
            (0, &a, los(0.5)),
            (0, &a, los(0.502)), // 5.02 cells: the same cells as 5
            (0, &a, los(0.7)),
            (1, &b, los(0.5)),
            (1, &b, los(0.5)),
            (0, &a, lidar),
            (0, &a, lidar),
        ];
        let s = BatchSights::new(runs.iter().map(|(k, m, s)| (*k, *m, *s)), u64::MAX / 2);
        let got: Vec<Option<usize>> = s.of_run.clone();
        assert_eq!(got, [Some(0), Some(0), None, Some(2), Some(2), None, None]);
        let c0 = s.get(0, &a).expect("made");
        assert!(Arc::ptr_eq(&c0, &s.get(1, &a).expect("shared")));
        assert!(s.get(2, &a).is_none() && s.get(5, &a).is_none() && s.get(9, &a).is_none());
        assert!(!Arc::ptr_eq(&c0, &s.get(3, &b).expect("made")));
    }

    /// A budget that cannot pay for a cache makes none: the runs sense as without.
    #[test]
    fn no_cache_beyond_the_budget() {
        let a = map(10);
        let los = "los:r=0.5".parse::<SensorSpec>().expect("los");
        let s = BatchSights::new([(0, &a, los), (0, &a, los)], 10);
        assert!(s.get(0, &a).is_none() && s.get(1, &a).is_none());
    }

    #[test]
    fn the_budget_is_what_the_limit_leaves() {
        assert_eq!(BatchSights::budget(None, None, 1 << 30), BATCH_SIGHT_BYTES);
        assert_eq!(BatchSights::budget(Some(300), None, 200 << 20), 100 << 20);
        assert_eq!(BatchSights::budget(Some(100), None, 200 << 20), 0);
        assert_eq!(BatchSights::budget(Some(4096), None, 0), BATCH_SIGHT_BYTES);
    }
}
