//! What the machine offers a run: the memory available now, read from the operating system
//! (the estimates of what runs need are their crates' own, e.g. `sim::memory`'s, which read
//! no files). Shared by the command line, the Python package and the ROS node.

use std::path::{Path, PathBuf};

use crate::memory::{Available, Limit};

/// The memory this process can still take now, and the limit that leaves it, so that a
/// refusal names it ("the 976 MiB ulimit -v leaves", not "this machine has available" of a
/// machine with 20 GiB free); `None` where none of the limits can be read.
///
/// The least of three (on Linux): the machine's `MemAvailable`; the room left under the
/// memory limit of the process's control group and of each group above it (a container's
/// `--memory`, a Slurm job's `--mem`, a systemd unit's `MemoryMax`), cgroup v2 or v1; and
/// the room left under the address-space limit (`ulimit -v`, `RLIMIT_AS`). Beyond a group's
/// limit the process is killed, and beyond the address-space limit an allocation fails and
/// aborts, however much memory the machine has free.
pub fn available() -> Option<Available> {
    let read = |p: &Path| std::fs::read_to_string(p).ok();
    let machine = read(Path::new("/proc/meminfo")).and_then(|t| mem_available(&t));
    let group = read(Path::new("/proc/self/cgroup"))
        .and_then(|t| cgroup_room(&t, Path::new("/sys/fs/cgroup"), read));
    let address_space = read(Path::new("/proc/self/limits")).and_then(|limits| {
        let status = read(Path::new("/proc/self/status"))?;
        address_space_room(&limits, &status)
    });
    tightest(machine, group, address_space)
}

/// The least of the room the machine, the control group and the address-space limit
/// leave, with its limit (the machine's on a tie, then the group's).
fn tightest(
    machine: Option<u64>,
    group: Option<u64>,
    address_space: Option<u64>,
) -> Option<Available> {
    crate::memory::least([
        machine.map(|b| Available::new(b, Limit::Machine)),
        group.map(|b| Available::new(b, Limit::Cgroup)),
        address_space.map(|b| Available::new(b, Limit::AddressSpace)),
    ])
}

/// The `MemAvailable` line of a `/proc/meminfo` text, in bytes.
fn mem_available(meminfo: &str) -> Option<u64> {
    kib_field(meminfo, "MemAvailable:")
}

/// The number of kiB of the line starting with `key` of a `/proc` text, in bytes.
fn kib_field(text: &str, key: &str) -> Option<u64> {
    let line = text.lines().find(|l| l.starts_with(key))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    kib.checked_mul(1024)
}

/// The room left under the soft address-space limit (`Max address space` of a
/// `/proc/self/limits` text) by the process's current size (`VmSize` of `/proc/self/status`);
/// `None` when there is no limit.
fn address_space_room(limits: &str, status: &str) -> Option<u64> {
    let line = limits
        .lines()
        .find(|l| l.starts_with("Max address space"))?;
    let soft: u64 = line
        .trim_start_matches("Max address space")
        .split_whitespace()
        .next()?
        .parse()
        .ok()?; // "unlimited" is no limit
    let size = kib_field(status, "VmSize:").unwrap_or(0);
    Some(soft.saturating_sub(size))
}

/// The least room left under the memory limits of the control group named in a
/// `/proc/self/cgroup` text and of the groups above it, their files read by `read` under
/// `root` (the cgroup file system's mount, `/sys/fs/cgroup`); `None` if no group has a
/// limit that can be read.
///
/// Under cgroup v2 (the line `0::/path`) a group's files are `root/path/memory.max` and
/// `memory.current`; under v1 (the `memory` controller's line) `root/memory/path/`
/// `memory.limit_in_bytes` and `memory.usage_in_bytes`. The page cache the kernel would
/// drop first (`inactive_file` of `memory.stat`) counts as room. In a container the path
/// can name a group outside its view: the groups that do not exist are skipped, and the
/// mount's own root (the container's group) is read as well.
fn cgroup_room(
    self_cgroup: &str,
    root: &Path,
    read: impl Fn(&Path) -> Option<String>,
) -> Option<u64> {
    let mut rooms = Vec::new();
    for line in self_cgroup.lines() {
        let mut fields = line.splitn(3, ':');
        let (Some(_), Some(controllers), Some(path)) =
            (fields.next(), fields.next(), fields.next())
        else {
            continue;
        };
        let (base, limit, usage, inactive) = if controllers.is_empty() {
            (
                root.to_path_buf(),
                "memory.max",
                "memory.current",
                "inactive_file",
            )
        } else if controllers.split(',').any(|c| c == "memory") {
            (
                root.join("memory"),
                "memory.limit_in_bytes",
                "memory.usage_in_bytes",
                "total_inactive_file",
            )
        } else {
            continue;
        };
        for dir in groups(&base, path) {
            let number = |file: &str| -> Option<u64> { read(&dir.join(file))?.trim().parse().ok() };
            // "max" (v2) reads as no number: no limit here.
            let (Some(max), Some(used)) = (number(limit), number(usage)) else {
                continue;
            };
            let cache = read(&dir.join("memory.stat"))
                .and_then(|stat| {
                    let line = stat
                        .lines()
                        .find(|l| l.split_whitespace().next() == Some(inactive))?;
                    line.split_whitespace().nth(1)?.parse::<u64>().ok()
                })
                .unwrap_or(0);
            rooms.push(max.saturating_sub(used.saturating_sub(cache)));
        }
    }
    rooms.into_iter().min()
}

/// The folders of the group at `path` under `base` and of every group above it, up to
/// `base` itself.
fn groups(base: &Path, path: &str) -> Vec<PathBuf> {
    let mut dirs = vec![base.to_path_buf()];
    let mut dir = base.to_path_buf();
    for part in path
        .split('/')
        .filter(|p| !p.is_empty() && *p != "." && *p != "..")
    {
        dir.push(part);
        dirs.push(dir.clone());
    }
    dirs
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashMap;

    /// Regression: every refusal said "this machine has available" even when the room
    /// was what `ulimit -v` or the cgroup limit left; the tightest limit is now named.
    #[test]
    fn regression_the_tightest_limit_is_named() {
        let gib = 1u64 << 30;
        let t = tightest(Some(20 * gib), Some(4 * gib), Some(gib)).unwrap();
        assert_eq!(t, Available::new(gib, Limit::AddressSpace));
        assert_eq!(t.to_string(), "the 1024 MiB ulimit -v leaves");
        let t = tightest(Some(20 * gib), Some(4 * gib), None).unwrap();
        assert_eq!(t.limit, Limit::Cgroup);
        assert_eq!(
            tightest(Some(gib), None, Some(gib)).unwrap().limit,
            Limit::Machine
        );
        assert_eq!(tightest(None, None, None), None);
    }

    #[test]
    fn mem_available_reads_the_kib_line() {
        let text = "MemTotal:       24000000 kB\nMemFree:   100 kB\nMemAvailable:   2048 kB\n";
        assert_eq!(mem_available(text), Some(2048 * 1024));
        assert_eq!(mem_available("MemTotal: 1 kB\n"), None);
        assert_eq!(mem_available("MemAvailable: lots kB\n"), None);
    }

    /// A `/proc/self/limits` text with this soft address-space limit.
    fn limits(soft: &str) -> String {
        format!(
            "Limit                     Soft Limit           Hard Limit           Units     \n\
             Max stack size            8388608              unlimited            bytes     \n\
             Max address space         {soft:<20} unlimited            bytes     \n\
             Max file locks            unlimited            unlimited            locks     \n"
        )
    }

    /// Regression: `ulimit -v` was not counted as a limit, so a run the estimate knew would
    /// not fit under it started and aborted on an allocation.
    #[test]
    fn regression_address_space_limit_is_room_left() {
        let status = "Name:\tfrontier\nVmPeak:\t  10240 kB\nVmSize:\t   4096 kB\n";
        assert_eq!(
            address_space_room(&limits("1024000000"), status),
            Some(1_024_000_000 - 4096 * 1024)
        );
        assert_eq!(address_space_room(&limits("unlimited"), status), None);
        assert_eq!(address_space_room(&limits("1000"), status), Some(0));
    }

    /// The files of a fake cgroup file system.
    fn reader(files: &[(&str, &str)]) -> impl Fn(&Path) -> Option<String> {
        let files: HashMap<PathBuf, String> = files
            .iter()
            .map(|(p, t)| (PathBuf::from(p), t.to_string()))
            .collect();
        move |p: &Path| files.get(p).cloned()
    }

    /// Regression: a container's or a Slurm job's memory limit was not counted, only the
    /// machine's free memory, so a run that the estimate knew would not fit in the group
    /// started and was killed.
    #[test]
    fn regression_cgroup_limit_is_room_left() {
        let root = Path::new("/cg");
        // v2: the job's group has 4 GiB, 1 GiB in use of which 256 MiB inactive cache; its
        // parent has no limit ("max").
        let v2 = reader(&[
            ("/cg/memory.max", "max\n"),
            ("/cg/slurm/memory.max", "max\n"),
            ("/cg/slurm/memory.current", "9000000000\n"),
            ("/cg/slurm/job_7/memory.max", "4294967296\n"),
            ("/cg/slurm/job_7/memory.current", "1073741824\n"),
            (
                "/cg/slurm/job_7/memory.stat",
                "anon 1\nfile 2\ninactive_file 268435456\n",
            ),
        ]);
        assert_eq!(
            cgroup_room("0::/slurm/job_7\n", root, &v2),
            Some(4_294_967_296 - (1_073_741_824 - 268_435_456))
        );
        // A parent's tighter limit counts too.
        let tight = reader(&[
            ("/cg/a/memory.max", "1000\n"),
            ("/cg/a/memory.current", "400\n"),
            ("/cg/a/b/memory.max", "5000\n"),
            ("/cg/a/b/memory.current", "100\n"),
        ]);
        assert_eq!(cgroup_room("0::/a/b\n", root, &tight), Some(600));
        // v1 in a container: the path names a group outside its view, the mount's root is
        // the container's group.
        let v1 = reader(&[
            ("/cg/memory/memory.limit_in_bytes", "2147483648\n"),
            ("/cg/memory/memory.usage_in_bytes", "147483648\n"),
            (
                "/cg/memory/memory.stat",
                "inactive_file 5\ntotal_inactive_file 0\n",
            ),
        ]);
        let text = "12:pids:/docker/abc\n4:memory:/docker/abc\n0::/\n";
        assert_eq!(cgroup_room(text, root, &v1), Some(2_000_000_000));
        // No limit anywhere: nothing to say.
        let none = reader(&[("/cg/memory.max", "max\n"), ("/cg/memory.current", "5\n")]);
        assert_eq!(cgroup_room("0::/\n", root, &none), None);
        assert_eq!(cgroup_room("", root, &none), None);
    }
}
