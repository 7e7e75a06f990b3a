//! The address space the dense product kernel reserves on each thread that calls it.
//!
//! On x86-64 the dense products of faer and of the halves' partial factorisation
//! (`src/fem/gather.rs`) run in private-gemm-x86 (pinned at 0.1.22 in Cargo.toml). On a
//! thread's first product it allocates a packing buffer of twice its figure for the L3 cache,
//! and keeps it until the thread ends. The buffer is allocated but not touched, so it takes no
//! memory. It does count against the address-space limit (`ulimit -v`), and when the limit
//! cannot hold it the allocation aborts the process inside the kernel. Its size follows the
//! cache the machine reports: 960 MiB on a host whose two cores share a 480 MiB L3.
//!
//! The memory guard therefore counts these buffers for the threads that will multiply.
//! [`Limits::of_process`](super::Limits::of_process) maps the calling thread's the first time
//! it reads the limits, when the address space holds them, so that from then on what the
//! process maps includes them. A check of sizes that run in parallel
//! ([`Sizes::check_need`](super::Sizes::check_need)) also counts the second half's thread of a
//! split factorisation, made for each one (`fem::join`), and rayon's pool, whose buffers it
//! maps the same way. The kernel's figure is computed the way the kernel computes it, because
//! its cache module is private. The tests
//! `hostile_again::a_solve_under_a_tight_address_space_is_refused_never_aborted` and
//! `hostile_again::the_inf_sup_estimate_is_refused_before_it_runs_out_of_memory` (tests/cli)
//! check this end to end: under address-space limits around the buffers and the estimate, a
//! solve answers or is refused, never aborted.

use std::cell::Cell;
use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};

use super::super::gather::Kernel;

/// The kernel's defaults for L1, L2 and L3, bytes (private-gemm-x86's `CACHE_INFO_DEFAULT`
/// for x86).
const DEFAULT_CACHES: [u64; 3] = [32 << 10, 256 << 10, 2 << 20];

/// Address space left beside a thread's buffers when they are mapped, for what other threads
/// allocate meanwhile.
const MARGIN: u64 = 64 << 20;

thread_local! {
    /// Whether this thread's buffers are mapped.
    static MAPPED: Cell<bool> = const { Cell::new(false) };
}

/// Whether every thread of rayon's pool has its buffers mapped.
static POOL_MAPPED: AtomicBool = AtomicBool::new(false);

/// The bytes one thread's first product reserves: two buffers of the kernel's L3 figure,
/// each rounded up to whole 4 KiB pages (0 where the processor does not run the kernel).
pub(super) fn per_thread() -> u64 {
    static BYTES: std::sync::OnceLock<u64> = std::sync::OnceLock::new();
    *BYTES.get_or_init(|| {
        if Kernel::detect() == Kernel::Dense {
            return 0;
        }
        let read = sysfs_caches(Path::new("/sys/devices/system/cpu"), num_cpus::get_physical());
        buffers(kernel_caches(read)[2])
    })
}

/// The calling thread's buffers if still to map, bytes, `headroom` giving the address space
/// left: they are mapped here where the headroom holds them (0 then: what the process maps
/// counts them from now on).
pub(super) fn to_map(headroom: impl Fn() -> u64) -> u64 {
    let per = per_thread();
    if per == 0 || MAPPED.get() {
        return 0;
    }
    if holds(headroom(), per) {
        map_here();
        0
    } else {
        per
    }
}

/// The address space a parallel solve's other threads take beside `headroom` (read before
/// this call), bytes: the second half's buffers, always to come, and rayon's pool's, mapped
/// here where the headroom holds them, unless mapped before.
pub(super) fn parallel_to_map(headroom: u64) -> u64 {
    let per = per_thread();
    if per == 0 {
        return 0;
    }
    if POOL_MAPPED.load(Ordering::Relaxed) {
        return per;
    }
    let threads = threads_need(per, rayon::current_num_threads());
    if rayon::current_thread_index().is_none() && holds(headroom, threads) {
        rayon::broadcast(|_| {
            if !MAPPED.get() {
                map_here();
            }
        });
        POOL_MAPPED.store(true, Ordering::Relaxed);
    }
    threads
}

/// Whether `headroom` holds `need` bytes of buffers and the [`MARGIN`] beside them (never
/// when the sum overflows).
fn holds(headroom: u64, need: u64) -> bool {
    need.checked_add(MARGIN).is_some_and(|n| headroom >= n)
}

/// The buffers, bytes, of the second half's thread and a pool of `pool` threads, `per` each
/// (saturating: a figure read from sysfs may be absurd).
fn threads_need(per: u64, pool: usize) -> u64 {
    per.saturating_mul(pool as u64).saturating_add(per)
}

/// Map this thread's buffers (one 1×1 product through the kernel).
fn map_here() {
    super::super::gather::map_buffers();
    MAPPED.set(true);
}

/// Two buffers of `l3` bytes, each in whole 4 KiB pages (saturating).
fn buffers(l3: u64) -> u64 {
    l3.div_ceil(4096).saturating_mul(4096).saturating_mul(2)
}

/// The kernel's L1, L2 and L3 figures from what sysfs gave (None: its defaults): each at
/// least its default, L2 at least 4 L1 and L3 at least 4 L2.
fn kernel_caches(read: Option<[u64; 3]>) -> [u64; 3] {
    let [l1, l2, l3] = read.unwrap_or(DEFAULT_CACHES);
    let l1 = l1.max(DEFAULT_CACHES[0]);
    let l2 = l2.max(DEFAULT_CACHES[1]).max(l1.saturating_mul(4));
    let l3 = l3.max(DEFAULT_CACHES[2]).max(l2.saturating_mul(4));
    [l1, l2, l3]
}

/// The kernel's reading of `root` (/sys/devices/system/cpu): each data or unified cache's
/// size divided among the CPUs that share it, times the CPUs sharing an L1; the L3 also times
/// the `physical` cores. None when a file cannot be read (the kernel then falls back to
/// `lscpu` or to its defaults).
fn sysfs_caches(root: &Path, physical: usize) -> Option<[u64; 3]> {
    let mut caches = [0u64; 3];
    let mut l1_shared = 1;
    for cpu in std::fs::read_dir(root).ok()? {
        let cache = cpu.ok()?.path().join("cache");
        let named_cpu = cache
            .parent()
            .and_then(Path::file_name)
            .and_then(|n| n.to_str())
            .is_some_and(|n| n.starts_with("cpu"));
        if !named_cpu || !cache.is_dir() {
            continue;
        }
        for index in std::fs::read_dir(cache).ok()? {
            let index = index.ok()?.path();
            let named_index = index
                .file_name()
                .and_then(|n| n.to_str())
                .is_some_and(|n| n.starts_with("index"));
            if !named_index || !index.is_dir() {
                continue;
            }
            let Some((level, bytes, shared)) = cache_index(&index).ok()? else {
                continue;
            };
            if level == 1 {
                l1_shared = shared;
            }
            if (1..=3).contains(&level) && shared > 0 {
                caches[level - 1] = bytes / shared as u64;
            }
        }
    }
    for c in &mut caches {
        *c = c.saturating_mul(l1_shared as u64);
    }
    caches[2] = caches[2].saturating_mul(physical as u64);
    Some(caches)
}

/// One `indexN` directory: its level, size in bytes and the count of CPUs sharing it; None
/// for an instruction cache or a field the kernel skips the cache for.
fn cache_index(index: &Path) -> std::io::Result<Option<(usize, u64, usize)>> {
    let field = |name: &str| std::fs::read_to_string(index.join(name)).map(|t| t.trim().to_string());
    if !matches!(field("type")?.as_str(), "Data" | "Unified") {
        return Ok(None);
    }
    let (level, size, shared) = (field("level")?, field("size")?, field("shared_cpu_list")?);
    Ok(level
        .parse::<usize>()
        .ok()
        .zip(size_bytes(&size))
        .zip(cpu_count(&shared))
        .map(|((level, bytes), shared)| (level, bytes, shared)))
}

/// A sysfs cache size: `48K`, `2048K`, `32M`, `1G` or bytes.
fn size_bytes(text: &str) -> Option<u64> {
    let (digits, unit) = match text.as_bytes().last()? {
        b'G' => (&text[..text.len() - 1], 1 << 30),
        b'M' => (&text[..text.len() - 1], 1 << 20),
        b'K' => (&text[..text.len() - 1], 1 << 10),
        _ => (text, 1),
    };
    digits.parse::<u64>().ok()?.checked_mul(unit)
}

/// The CPUs of a list such as `0-3,8,10-11`.
fn cpu_count(text: &str) -> Option<usize> {
    text.split(',').try_fold(0usize, |count, item| {
        let n = match item.split_once('-') {
            Some((start, end)) => end
                .parse::<usize>()
                .ok()?
                .checked_add(1)?
                .checked_sub(start.parse().ok()?)?,
            None => {
                item.parse::<usize>().ok()?;
                1
            }
        };
        count.checked_add(n)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A sysfs tree of `cpus` CPUs, each with the caches (type, level, size, shared list).
    fn sysfs(name: &str, cpus: usize, caches: &[(&str, u32, &str, &str)]) -> std::path::PathBuf {
        let root = std::env::temp_dir().join(format!("riplab-sysfs-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&root);
        for cpu in 0..cpus {
            for (i, (kind, level, size, shared)) in caches.iter().enumerate() {
                let dir = root.join(format!("cpu{cpu}/cache/index{i}"));
                std::fs::create_dir_all(&dir).unwrap();
                for (file, text) in [
                    ("type", kind.to_string()),
                    ("level", level.to_string()),
                    ("size", size.to_string()),
                    ("shared_cpu_list", shared.to_string()),
                ] {
                    std::fs::write(dir.join(file), format!("{text}\n")).unwrap();
                }
            }
        }
        std::fs::create_dir_all(root.join("cpufreq")).unwrap();
        root
    }

    /// The host where the fixed limits aborted: two cores, each with its own 48K L1 data and
    /// 2 MiB L2, sharing a 491520K L3. The kernel's L3 is 491520K / 2 × 1 × 2 cores = 480 MiB,
    /// and a thread's buffers twice that: the 1006632960 bytes of the abort's message.
    #[test]
    fn a_shared_l3_is_the_kernels_figure_times_the_cores() {
        let root = sysfs(
            "shared-l3",
            2,
            &[
                ("Data", 1, "48K", "0"),
                ("Instruction", 1, "64K", "0"),
                ("Unified", 2, "2048K", "0"),
                ("Unified", 3, "491520K", "0-1"),
            ],
        );
        let caches = kernel_caches(sysfs_caches(&root, 2));
        assert_eq!(caches, [48 << 10, 2 << 20, 480 << 20]);
        assert_eq!(buffers(caches[2]), 1_006_632_960);
        let _ = std::fs::remove_dir_all(root);
    }

    /// Small or unreadable caches give the kernel's defaults, each at least four of the level
    /// below: L1 32 KiB, L2 256 KiB, L3 2 MiB, so 4 MiB of buffers.
    #[test]
    fn small_or_unknown_caches_give_the_kernels_defaults() {
        assert_eq!(kernel_caches(None), [32 << 10, 256 << 10, 2 << 20]);
        assert_eq!(buffers(kernel_caches(None)[2]), 4 << 20);
        let root = sysfs(
            "small",
            1,
            &[
                ("Data", 1, "16K", "0"),
                ("Unified", 2, "1M", "0"),
                ("Unified", 3, "3M", "0"),
            ],
        );
        // L2 is 1 MiB, so L3 is at least 4 MiB although 3 MiB was read.
        assert_eq!(
            kernel_caches(sysfs_caches(&root, 1)),
            [32 << 10, 1 << 20, 4 << 20]
        );
        let _ = std::fs::remove_dir_all(&root);
        assert_eq!(sysfs_caches(&root, 1), None, "no tree: the defaults");
    }

    /// Figures no machine reports, as a container's sysfs may: a size near 2⁶⁴ bytes and a CPU
    /// list ending at usize::MAX saturate, never overflow (the guard runs before every solve).
    #[test]
    fn absurd_cache_figures_saturate() {
        let root = sysfs(
            "absurd",
            2,
            &[
                ("Data", 1, "48K", "0-18446744073709551615"),
                ("Unified", 3, "18014398509481983K", "0"),
            ],
        );
        let caches = kernel_caches(sysfs_caches(&root, usize::MAX));
        assert_eq!(caches[2], u64::MAX);
        assert_eq!(buffers(caches[2]), u64::MAX);
        let _ = std::fs::remove_dir_all(root);
        assert_eq!(
            cpu_count("0-18446744073709551615,1"),
            None,
            "more CPUs than usize counts"
        );
        // What the guard does with such a figure: no room holds it, and the threads' sum
        // saturates.
        assert!(!holds(u64::MAX, u64::MAX));
        assert!(!holds(u64::MAX, u64::MAX - 1));
        assert_eq!(threads_need(u64::MAX, 2), u64::MAX);
        assert_eq!(threads_need(1 << 30, 2), 3 << 30);
        assert!(holds(2 << 30, 1 << 30));
    }

    #[test]
    fn cache_sizes_and_cpu_lists_are_read() {
        assert_eq!(size_bytes("48K"), Some(48 << 10));
        assert_eq!(size_bytes("32M"), Some(32 << 20));
        assert_eq!(size_bytes("1G"), Some(1 << 30));
        assert_eq!(size_bytes("512"), Some(512));
        assert_eq!(size_bytes("K"), None);
        assert_eq!(cpu_count("0"), Some(1));
        assert_eq!(cpu_count("0-3,8,10-11"), Some(7));
        assert_eq!(cpu_count("3-1"), None);
        assert_eq!(cpu_count(""), None);
    }
}
