//! How much memory a process can still take (or its user lets it take) and which limit
//! leaves it: what the map loaders (and the runs of the crates above) compare their
//! estimates with before allocating.
//!
//! The loaders read no limits themselves ([`crate::machine`] reads them from the operating
//! system): a library user who wants no check passes none.

use std::fmt;

/// The limit that leaves a process the memory it has [`Available`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Limit {
    /// The machine's free memory (`MemAvailable`).
    Machine,
    /// The memory limit of the process's control group (a container's, a Slurm job's).
    Cgroup,
    /// The address-space limit (`ulimit -v`).
    AddressSpace,
    /// A budget the caller chose.
    Budget,
    /// A budget the user gave with the named flag (`--memory-mb`), in MiB.
    Flag(&'static str),
}

/// Bytes of memory a process can still take, and the limit that leaves them.
///
/// Displays as the limit would be named in a refusal, e.g. "the 976 MiB ulimit -v leaves"
/// or, for a user's budget, as the user gave it: "--memory-mb 512".
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Available {
    /// Bytes that can still be taken.
    pub bytes: u64,
    /// Which limit leaves them.
    pub limit: Limit,
}

impl Available {
    /// `bytes` left by `limit`.
    pub fn new(bytes: u64, limit: Limit) -> Self {
        Self { bytes, limit }
    }

    /// A budget of `bytes` chosen by the caller.
    pub fn budget(bytes: u64) -> Self {
        Self::new(bytes, Limit::Budget)
    }

    /// A budget of `mib` MiB the user gave with `flag` (e.g. `--memory-mb`).
    pub fn flag(flag: &'static str, mib: u64) -> Self {
        // A budget too large to count in bytes is no limit: it saturates, and no estimate
        // exceeds it to be named.
        Self::new(mib.saturating_mul(1 << 20), Limit::Flag(flag))
    }
}

/// The least of the `limits` that are known (the first of equal ones): the one that applies
/// when a process is under several (the machine's, a cgroup's, a user's budget).
pub fn least(limits: impl IntoIterator<Item = Option<Available>>) -> Option<Available> {
    limits.into_iter().flatten().min_by_key(|a| a.bytes)
}

impl fmt::Display for Available {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mib = self.bytes / (1 << 20);
        match self.limit {
            Limit::Machine => write!(f, "the {mib} MiB this machine has available"),
            Limit::Cgroup => write!(f, "the {mib} MiB the cgroup memory limit leaves"),
            Limit::AddressSpace => write!(f, "the {mib} MiB ulimit -v leaves"),
            Limit::Budget => write!(f, "the memory budget of {mib} MiB"),
            Limit::Flag(flag) => write!(f, "{flag} {mib}"),
        }
    }
}

/// `bytes` as a refusal says it: in MiB rounded up from 1 MiB on, else in KiB or bytes (a
/// file of 18 bytes is not "about 1 MiB").
pub fn describe_bytes(bytes: u64) -> String {
    if bytes >= 1 << 20 {
        format!("{} MiB", bytes.div_ceil(1 << 20))
    } else if bytes >= 1 << 10 {
        format!("{} KiB", bytes.div_ceil(1 << 10))
    } else if bytes == 1 {
        "1 byte".to_string()
    } else {
        format!("{bytes} bytes")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_limit_is_named() {
        let mib = 1 << 20;
        assert_eq!(
            Available::new(2048 * mib, Limit::Machine).to_string(),
            "the 2048 MiB this machine has available"
        );
        assert_eq!(
            Available::new(512 * mib, Limit::Cgroup).to_string(),
            "the 512 MiB the cgroup memory limit leaves"
        );
        assert_eq!(
            Available::new(976 * mib + 5, Limit::AddressSpace).to_string(),
            "the 976 MiB ulimit -v leaves"
        );
        assert_eq!(
            Available::budget(64 * mib).to_string(),
            "the memory budget of 64 MiB"
        );
        assert_eq!(
            Available::flag("--memory-mb", 512).to_string(),
            "--memory-mb 512"
        );
    }

    #[test]
    fn the_least_known_limit_applies() {
        let machine = Available::new(8 << 30, Limit::Machine);
        let budget = Available::flag("--memory-mb", 512);
        assert_eq!(least([Some(machine), Some(budget)]), Some(budget));
        assert_eq!(least([None, Some(machine), None]), Some(machine));
        assert_eq!(least([None, None]), None);
        // Of equal ones, the first.
        let cgroup = Available::new(8 << 30, Limit::Cgroup);
        assert_eq!(least([Some(machine), Some(cgroup)]), Some(machine));
        assert_eq!(least([Some(cgroup), Some(machine)]), Some(cgroup));
    }
}
