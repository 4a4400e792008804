//! Helper threads that run a call's items beside the caller and stay awake between calls.
//!
//! A vector of environments steps every environment once per call, a call every few tens
//! of microseconds when each step takes one. A pool whose threads sleep between calls
//! (rayon's) must wake one at every call: on a virtual machine that costs 0.1–0.2 ms, more
//! than the step it would share, so 2 environments on 2 threads ran slower than on one.
//! [`SpinPool`]'s helpers spin for a short while ([`SPIN`]) after each call before they
//! park, as OpenMP's threads do, and the caller never waits for a helper that has not
//! started: it works through the items itself, closes the call, and waits only for the
//! items helpers took. Written here rather than taken from a crate: the pools we know
//! (rayon, its scopes, scoped thread pools) park their threads or wait for every job they
//! handed out.
//!
//! Items are taken in index order (or an order the caller gives), each exactly once, and
//! each result goes to its item's index, so what a call returns does not depend on which
//! thread ran what. Each thread has a home share of the items, the same at every call (the
//! caller the first `n / threads`, the first helper the next, …), and takes another
//! share's items only once its own are taken: an environment keeps stepping on the same
//! core, whose caches still hold what its last step touched. On the 2-core development
//! machine that made `ExploreVectorEnv` (`cf-rr`, 4–32 environments, calls alternated in
//! one process) step 2–11 % faster than taking the next free item, in one run of ten
//! 1 % slower. Each item runs inside [`explore::decision::batched`]: the pool keeps
//! the cores busy, so a run's own searches are not spread over rayon's threads too.

use std::any::Any;
use std::panic::{AssertUnwindSafe, catch_unwind, resume_unwind};
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};
use std::sync::{Arc, Condvar, Mutex, MutexGuard};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// How long a helper keeps looking for the next call before it parks.
pub const SPIN: Duration = Duration::from_micros(500);

/// A call's work as the helpers see it: the caller's closure with its lifetime erased.
#[derive(Clone, Copy)]
struct Job(*const (dyn Fn() + Sync));

// SAFETY: a `Job` points to a `Sync` closure and is only called between a helper's
// registration and its release of `active`, while `SpinPool::each` keeps the closure alive
// (it returns only once the call is closed and `active` is 0).
unsafe impl Send for Job {}

/// What the caller and the helpers share, under the mutex.
struct Slot {
    /// Incremented by each call.
    call: u64,
    /// The open call's work; `None` once it is closed.
    job: Option<Job>,
    /// Set when the pool is dropped.
    quit: bool,
    /// Helpers waiting on `Shared::wake`.
    parked: usize,
}

struct Shared {
    slot: Mutex<Slot>,
    /// `Slot::call` of the newest call, read while spinning.
    call: AtomicU64,
    /// Set with `quit`, read while spinning.
    quit: AtomicBool,
    /// Helpers that registered for the open call and have not finished it.
    active: AtomicUsize,
    /// Parked helpers wait here for the next call.
    wake: Condvar,
    /// A helper's panic, handed to the caller.
    panic: Mutex<Option<Box<dyn Any + Send>>>,
}

/// The calling thread and `threads − 1` helpers running a call's items.
pub struct SpinPool {
    shared: Arc<Shared>,
    helpers: Vec<JoinHandle<()>>,
}

impl SpinPool {
    /// A pool of `threads` threads in all, the caller included (0 is taken as 1).
    pub fn new(threads: usize) -> std::io::Result<Self> {
        let shared = Arc::new(Shared {
            slot: Mutex::new(Slot {
                call: 0,
                job: None,
                quit: false,
                parked: 0,
            }),
            call: AtomicU64::new(0),
            quit: AtomicBool::new(false),
            active: AtomicUsize::new(0),
            wake: Condvar::new(),
            panic: Mutex::new(None),
        });
        let mut helpers = Vec::new();
        for i in 1..threads.max(1) {
            let sh = Arc::clone(&shared);
            let handle = std::thread::Builder::new()
                .name(format!("frontier-helper-{i}"))
                .spawn(move || helper(&sh, i));
            match handle {
                Ok(h) => helpers.push(h),
                Err(e) => {
                    // Stop the helpers already started before reporting.
                    drop(SpinPool { shared, helpers });
                    return Err(e);
                }
            }
        }
        Ok(Self { shared, helpers })
    }

    /// Threads in all, the caller included.
    pub fn threads(&self) -> usize {
        self.helpers.len() + 1
    }

    /// `f(i, items[i])` for every item, on the calling thread and the helpers; the results
    /// in the items' order. A panic in `f` is raised again here once the call is over.
    pub fn each<T: Send, R: Send>(
        &self,
        items: Vec<T>,
        f: impl Fn(usize, T) -> R + Sync,
    ) -> Vec<R> {
        let order: Vec<usize> = (0..items.len()).collect();
        self.each_in_order(items, &order, f)
    }

    /// [`each`](Self::each), the items taken in `order` (a permutation of their indices):
    /// the longest first, a call's threads finish closer together (each thread takes its own
    /// share's items in that order, then the others'). The results are in the
    /// items' order whatever `order` is.
    ///
    /// # Panics
    /// If `order` is not a permutation of `0..items.len()`.
    pub fn each_in_order<T: Send, R: Send>(
        &self,
        items: Vec<T>,
        order: &[usize],
        f: impl Fn(usize, T) -> R + Sync,
    ) -> Vec<R> {
        let n = items.len();
        let mut seen = vec![false; n];
        assert!(
            order.len() == n
                && order
                    .iter()
                    .all(|&i| i < n && !std::mem::replace(&mut seen[i], true)),
            "each_in_order: the order is not a permutation of the {n} items"
        );
        let items: Vec<Mutex<Option<T>>> = items.into_iter().map(|t| Mutex::new(Some(t))).collect();
        let out: Vec<Mutex<Option<R>>> = (0..n).map(|_| Mutex::new(None)).collect();
        let shares = Shares::new(order, self.threads().min(n).max(1));
        let work = || {
            let start = HOME.with(std::cell::Cell::get);
            for i in shares.from(start) {
                // Each index is taken once, so its item is there.
                if let Some(t) = lock(&items[i]).take() {
                    // the pool's threads are busy: a run's own searches stay on its thread
                    let r = explore::decision::batched(|| f(i, t));
                    *lock(&out[i]) = Some(r);
                }
            }
        };
        if n > 1 && !self.helpers.is_empty() {
            self.share(&work);
        } else {
            work();
        }
        out.into_iter()
            .filter_map(|m| m.into_inner().unwrap_or_else(|p| p.into_inner()))
            .collect()
    }

    /// Run `work` on this thread while the helpers may join in; return once every helper
    /// that joined has left it.
    fn share(&self, work: &(dyn Fn() + Sync)) {
        let sh = &*self.shared;
        // SAFETY: only the lifetime is erased; the call is closed and every helper that
        // registered has finished before this function returns (also when `work` panics:
        // `Close` runs on unwinding), so no helper calls the job after `work` is gone.
        let job = Job(unsafe {
            std::mem::transmute::<*const (dyn Fn() + Sync + '_), *const (dyn Fn() + Sync + 'static)>(
                work,
            )
        });
        let parked = {
            let mut s = lock(&sh.slot);
            s.call += 1;
            s.job = Some(job);
            sh.call.store(s.call, Ordering::Release);
            s.parked
        };
        if parked > 0 {
            sh.wake.notify_all();
        }
        struct Close<'a>(&'a Shared);
        impl Drop for Close<'_> {
            fn drop(&mut self) {
                lock(&self.0.slot).job = None;
                // Registration needs an open call, so `active` only falls from here on.
                let mut spins = 0u32;
                while self.0.active.load(Ordering::Acquire) != 0 {
                    spins += 1;
                    if spins < 1 << 12 {
                        std::hint::spin_loop();
                    } else {
                        std::thread::yield_now();
                    }
                }
                if std::thread::panicking() {
                    // The caller's own panic goes on; a helper's is dropped with it.
                    lock(&self.0.panic).take();
                }
            }
        }
        let close = Close(sh);
        work();
        drop(close);
        if let Some(p) = lock(&sh.panic).take() {
            resume_unwind(p);
        }
    }
}

impl Drop for SpinPool {
    fn drop(&mut self) {
        lock(&self.shared.slot).quit = true;
        self.shared.quit.store(true, Ordering::Release);
        self.shared.wake.notify_all();
        for h in self.helpers.drain(..) {
            let _ = h.join();
        }
    }
}

thread_local! {
    /// The share of a call's items this thread takes first: 0 for a caller, i for helper i.
    static HOME: std::cell::Cell<usize> = const { std::cell::Cell::new(0) };
}

/// A call's items in `threads` shares of consecutive indices (item i in share
/// `i · threads / n`), each share in the call's order, with a cursor per share.
struct Shares {
    /// The items share by share; share s is `items[bounds[s]..bounds[s + 1]]`.
    items: Vec<usize>,
    bounds: Vec<usize>,
    /// Per share: how many of its items have been taken.
    taken: Vec<AtomicUsize>,
}

impl Shares {
    fn new(order: &[usize], threads: usize) -> Self {
        let n = order.len();
        let share = |i: usize| i * threads / n.max(1);
        let mut bounds = vec![0; threads + 1];
        for &i in order {
            bounds[share(i) + 1] += 1;
        }
        for s in 0..threads {
            bounds[s + 1] += bounds[s];
        }
        let mut fill = bounds.clone();
        let mut items = vec![0; n];
        for &i in order {
            let s = share(i);
            items[fill[s]] = i;
            fill[s] += 1;
        }
        let taken = (0..threads).map(|_| AtomicUsize::new(0)).collect();
        Self {
            items,
            bounds,
            taken,
        }
    }

    /// The items a thread whose home is share `home` takes: its own share's first, then
    /// the other shares' in turn, each item handed to exactly one taker.
    fn from(&self, home: usize) -> impl Iterator<Item = usize> + '_ {
        let t = self.taken.len();
        (0..t).flat_map(move |k| {
            let s = (home + k) % t;
            let (lo, hi) = (self.bounds[s], self.bounds[s + 1]);
            std::iter::from_fn(move || {
                let k = lo + self.taken[s].fetch_add(1, Ordering::Relaxed);
                (k < hi).then(|| self.items[k])
            })
        })
    }
}

/// A helper's life: wait for a call (spinning for [`SPIN`], then parked), register while
/// it is open, run its work, leave.
fn helper(sh: &Shared, home: usize) {
    HOME.with(|h| h.set(home));
    let mut seen = 0u64;
    loop {
        let started = Instant::now();
        let mut spins = 0u32;
        while sh.call.load(Ordering::Acquire) == seen && !sh.quit.load(Ordering::Acquire) {
            std::hint::spin_loop();
            spins = spins.wrapping_add(1);
            if spins.is_multiple_of(64) && started.elapsed() > SPIN {
                let mut s = lock(&sh.slot);
                while s.call == seen && !s.quit {
                    s.parked += 1;
                    s = sh.wake.wait(s).unwrap_or_else(|p| p.into_inner());
                    s.parked -= 1;
                }
                break;
            }
        }
        let job = {
            let s = lock(&sh.slot);
            if s.quit {
                return;
            }
            seen = s.call;
            let job = s.job;
            if job.is_some() {
                sh.active.fetch_add(1, Ordering::Relaxed);
            }
            job
        };
        let Some(job) = job else { continue };
        // SAFETY: registered under the lock while the call was open (see `Job`).
        let r = catch_unwind(AssertUnwindSafe(|| unsafe { (*job.0)() }));
        if let Err(p) = r {
            lock(&sh.panic).get_or_insert(p);
        }
        sh.active.fetch_sub(1, Ordering::Release);
    }
}

fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|p| p.into_inner())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn results_come_back_in_item_order_at_any_thread_count() {
        for threads in [0, 1, 2, 4] {
            let pool = SpinPool::new(threads).unwrap();
            assert_eq!(pool.threads(), threads.max(1));
            for n in [0, 1, 2, 3, 17, 200] {
                let items: Vec<u64> = (0..n).collect();
                let out = pool.each(items, |i, x| {
                    assert_eq!(i as u64, x);
                    x * x + 1
                });
                assert_eq!(out, (0..n).map(|x| x * x + 1).collect::<Vec<_>>());
            }
        }
    }

    #[test]
    fn an_order_changes_which_item_runs_first_not_where_results_go() {
        let pool = SpinPool::new(2).unwrap();
        let first = Mutex::new(Vec::new());
        let out = pool.each_in_order(vec![10, 20, 30, 40], &[3, 1, 0, 2], |i, x| {
            lock(&first).push(i);
            x + i
        });
        assert_eq!(out, vec![10, 21, 32, 43]);
        let mut ran = lock(&first).clone();
        ran.sort_unstable();
        assert_eq!(ran, vec![0, 1, 2, 3]);
        let one = SpinPool::new(1).unwrap();
        let _ = one.each_in_order(vec![1, 2, 3], &[2, 0, 1], |i, _| lock(&first).push(i));
        assert_eq!(
            lock(&first)[4..],
            [2, 0, 1],
            "one thread takes the items in order"
        );
    }

    #[test]
    fn each_thread_takes_its_own_share_first_then_the_others() {
        // Items 0, 1 are share 0 (the caller's), 2, 3 share 1, each in the call's order.
        let shares = Shares::new(&[3, 1, 0, 2], 2);
        assert_eq!(shares.from(1).collect::<Vec<_>>(), [3, 2, 1, 0]);
        let shares = Shares::new(&[3, 1, 0, 2], 2);
        assert_eq!(shares.from(0).collect::<Vec<_>>(), [1, 0, 3, 2]);
        // Two takers at once: every item goes to exactly one.
        let shares = Shares::new(&(0..7).rev().collect::<Vec<_>>(), 3);
        let (mut a, mut b) = (shares.from(0), shares.from(2));
        let mut got = Vec::new();
        loop {
            let (x, y) = (a.next(), b.next());
            got.extend(x.into_iter().chain(y));
            if x.is_none() && y.is_none() {
                break;
            }
        }
        assert_eq!(
            got[..2],
            [2, 6],
            "each starts with its own share's first item"
        );
        got.sort_unstable();
        assert_eq!(got, (0..7).collect::<Vec<_>>());
    }

    #[test]
    #[should_panic(expected = "not a permutation")]
    fn an_order_that_repeats_an_item_is_refused() {
        SpinPool::new(1)
            .unwrap()
            .each_in_order(vec![1, 2], &[0, 0], |_, x| x);
    }

    #[test]
    fn every_item_runs_once_over_many_calls_with_pauses() {
        let pool = SpinPool::new(3).unwrap();
        let count = AtomicUsize::new(0);
        for call in 0..2_000 {
            let out = pool.each(vec![(); 5], |i, ()| {
                count.fetch_add(1, Ordering::Relaxed);
                i
            });
            assert_eq!(out, vec![0, 1, 2, 3, 4]);
            if call % 500 == 0 {
                // Long enough for the helpers to park.
                std::thread::sleep(SPIN * 3);
            }
        }
        assert_eq!(count.load(Ordering::Relaxed), 10_000);
    }

    #[test]
    fn a_panic_in_an_item_reaches_the_caller_and_the_pool_goes_on() {
        let pool = SpinPool::new(2).unwrap();
        for bad in 0..8 {
            let r = catch_unwind(AssertUnwindSafe(|| {
                pool.each((0..8).collect(), |i, x: usize| {
                    if i == bad {
                        panic!("item {i}");
                    }
                    x
                })
            }));
            assert!(r.is_err(), "item {bad}'s panic was lost");
            assert_eq!(pool.each(vec![1, 2, 3], |_, x| x * 2), vec![2, 4, 6]);
        }
    }
}
