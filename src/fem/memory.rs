//! The memory guard: the peak memory a discretisation will need, estimated from its sizes
//! before anything is allocated, against the memory this process may really use: the
//! machine's available memory (`MemAvailable`), the address-space limit (`ulimit -v`,
//! RLIMIT_AS, less what the process already maps) and the control group's limit (cgroup v2
//! `memory.max` or v1 `memory.limit_in_bytes`, less its usage, at every level of the
//! hierarchy), whichever is smallest (Linux; elsewhere nothing is known and nothing refused).
//! The address-space limit also keeps what the dense product kernel reserves on each thread
//! that will multiply (`fem/memory/kernel.rs`).

mod kernel;

use std::path::Path;

use faer::Par;

use super::error::FemError;
use crate::mesh::Element;

/// The sizes that decide a discretisation's memory.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sizes {
    /// The element (its order sets the factor's fill per unknown).
    pub element: Element,
    /// Free dofs n (the order of K).
    pub unknowns: usize,
    /// Γ_C normal dofs m (the order of the trace compliance C).
    pub trace: usize,
    /// The most contact points of any rule on Γ_C (the order of a coupling G).
    pub points: usize,
}

/// Bytes of sparse work per n·log₂n unknowns (K, its pattern, the symbolic analysis and the
/// factor on the grid's nested dissection, the factor being most of it), from the measured
/// peaks of the default scenario at levels 5–8 (two threads): 50–59 for Q1 and P1 (the same
/// pattern: every node of a cell couples), 65–67 for Q2, each rounded up so that the estimate
/// is 5–16% above every peak (BENCHMARKS.md, "Fresh memory" and "Supernodes from the grid").
fn sparse_bytes_per_nlogn(element: Element) -> f64 {
    match element {
        Element::Q1 | Element::P1 => 62.0,
        Element::Q2 => 70.0,
    }
}

/// The process itself (code, tables, the terminal): a fixed 16 MiB.
const BASE: u64 = 16 << 20;

impl Sizes {
    /// Estimated peak memory, bytes: the sparse work (grows like n log n on the grid's nested
    /// dissection) and the dense blocks on Γ_C, counted as if held together at the peak: the
    /// compliance C (m², three m×m matrices while it is formed from the factor's trailing
    /// block), a rule's coupling G (q², with C Tᵀ, m·q, while it is formed) and the contact
    /// Newton's active-set system (up to q²).
    pub fn peak_bytes(&self) -> u64 {
        let (m, q) = (self.trace as f64, self.points as f64);
        let dense = 8.0 * (3.0 * m * m).max(m * m + m * q + 2.0 * q * q);
        (self.sparse_bytes() + dense) as u64 + BASE
    }

    /// The sparse work of one factorisation of a matrix of K's pattern (n log n).
    fn sparse_bytes(&self) -> f64 {
        let n = self.unknowns.max(2) as f64;
        sparse_bytes_per_nlogn(self.element) * n * n.log2()
    }

    /// What the inf-sup estimate of docs/design.md §5 (src/infsup.rs) needs beside its
    /// discretisation, bytes: the H¹ Gram matrix A of (7) assembled and factorised on the
    /// stiffness's ordering (0.85 of a sparse term: the measured peaks of `riplab infsup`
    /// exceed the solve's by 0.72–0.74 of one beyond the dense work at Q2 levels 5–6,
    /// STABILITY.md),
    /// the trace compliance C (three m×m while it is formed), and for one rule B and B·C (q×m
    /// each) with at most six q×q matrices at once (B A⁻¹ Bᵀ, a mass matrix, its
    /// eigenvectors, Z, Zᵀ S Z and the eigensolver's work).
    pub fn infsup_extra_bytes(&self) -> u64 {
        let (m, q) = (self.trace as f64, self.points as f64);
        let dense = 8.0 * (3.0 * m * m + 2.0 * m * q + 6.0 * q * q);
        (0.85 * self.sparse_bytes() + dense) as u64
    }

    /// Refuse before allocating when the estimate exceeds what `limits` leave.
    pub fn check(&self, limits: &Limits) -> Result<(), FemError> {
        self.check_need(self.peak_bytes(), limits)
    }

    /// Refuse before allocating when `need` bytes (an estimate of work on these sizes)
    /// exceed what `limits` leave.
    pub fn check_need(&self, need: u64, limits: &Limits) -> Result<(), FemError> {
        match self.beside_parallel_threads(limits).available() {
            Some(available) if need > available => Err(FemError::TooLarge {
                unknowns: self.unknowns,
                need,
                available,
            }),
            _ => Ok(()),
        }
    }

    /// `limits`, and when these sizes run on several threads (`fem::sparse_parallelism`,
    /// `fem::dense_parallelism`), the address space less what those threads' dense product
    /// buffers take (`fem/memory/kernel.rs`).
    fn beside_parallel_threads(&self, limits: &Limits) -> Limits {
        let order = self.trace.max(self.points);
        let parallel = matches!(super::sparse_parallelism(self.unknowns), Par::Rayon(_))
            || matches!(super::dense_parallelism(order), Par::Rayon(_));
        match limits.address_space {
            Some(headroom) if parallel => Limits {
                address_space: Some(headroom.saturating_sub(kernel::parallel_to_map(headroom))),
                ..limits.clone()
            },
            _ => limits.clone(),
        }
    }
}

/// What a refusal's "available" is the smallest of, in words: the address-space limit named
/// with the dense product kernel's buffers per thread where the processor runs the kernel
/// (`fem/memory/kernel.rs`; 0.9 GiB on a host whose cores share a 480 MiB L3), so that a user
/// under `ulimit -v` reads what the limit must hold beside the work.
pub(crate) fn limits_in_words() -> String {
    limits_words(kernel::per_thread())
}

fn limits_words(per_thread: u64) -> String {
    let buffers = if per_thread == 0 {
        String::new()
    } else {
        format!(
            " and the product kernel's {} a thread",
            super::error::gib(per_thread)
        )
    };
    format!("free memory, ulimit -v less what is mapped{buffers}, and the control group's limit")
}

/// What the kernel says about this process's memory, bytes (None: unknown or unlimited).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Limits {
    /// `MemAvailable` of /proc/meminfo.
    pub machine: Option<u64>,
    /// The soft RLIMIT_AS less the address space already mapped (VmSize) and the dense
    /// product kernel's buffers of the calling thread if still to map (`fem/memory/kernel.rs`).
    pub address_space: Option<u64>,
    /// The tightest control group limit less that group's usage.
    pub cgroup: Option<u64>,
}

impl Limits {
    /// The limits of the running process.
    pub fn of_process() -> Self {
        let read = |p: &str| std::fs::read_to_string(p).ok();
        let address_space = read("/proc/self/limits")
            .and_then(|t| parse_rlimit_as(&t))
            .map(|limit| {
                let mapped = || {
                    read("/proc/self/status")
                        .and_then(|t| parse_vm_size(&t))
                        .unwrap_or(0)
                };
                let to_come = kernel::to_map(|| limit.saturating_sub(mapped()));
                limit.saturating_sub(mapped()).saturating_sub(to_come)
            });
        let cgroup = read("/proc/self/cgroup").and_then(|t| {
            let mut headroom = None;
            for (root, v2) in [
                ("/sys/fs/cgroup", true),
                ("/sys/fs/cgroup/unified", true),
                ("/sys/fs/cgroup/memory", false),
            ] {
                if let Some(rel) = cgroup_path(&t, v2) {
                    headroom = min_known(headroom, cgroup_headroom(Path::new(root), &rel, v2));
                }
            }
            headroom
        });
        Limits {
            machine: read("/proc/meminfo").and_then(|t| parse_meminfo(&t)),
            address_space,
            cgroup,
        }
    }

    /// These limits with `reserved` bytes already promised elsewhere (work under way on
    /// other threads) taken from each known one.
    pub fn less(self, reserved: u64) -> Limits {
        let less = |v: Option<u64>| v.map(|v| v.saturating_sub(reserved));
        Limits {
            machine: less(self.machine),
            address_space: less(self.address_space),
            cgroup: less(self.cgroup),
        }
    }

    /// The memory a new allocation may take: the smallest known limit.
    pub fn available(&self) -> Option<u64> {
        [self.machine, self.address_space, self.cgroup]
            .into_iter()
            .fold(None, min_known)
    }
}

fn min_known(a: Option<u64>, b: Option<u64>) -> Option<u64> {
    match (a, b) {
        (Some(a), Some(b)) => Some(a.min(b)),
        (a, b) => a.or(b),
    }
}

/// `MemAvailable:  123 kB` of /proc/meminfo, in bytes.
pub fn parse_meminfo(text: &str) -> Option<u64> {
    kib_field(text, "MemAvailable:")
}

/// `VmSize:  123 kB` of /proc/self/status, in bytes.
pub fn parse_vm_size(text: &str) -> Option<u64> {
    kib_field(text, "VmSize:")
}

fn kib_field(text: &str, key: &str) -> Option<u64> {
    let line = text.lines().find(|l| l.starts_with(key))?;
    let kib: u64 = line[key.len()..].split_whitespace().next()?.parse().ok()?;
    Some(kib.saturating_mul(1024))
}

/// The soft limit of `Max address space` in /proc/self/limits (RLIMIT_AS), None when
/// unlimited.
pub fn parse_rlimit_as(text: &str) -> Option<u64> {
    let line = text.lines().find(|l| l.starts_with("Max address space"))?;
    line["Max address space".len()..]
        .split_whitespace()
        .next()?
        .parse()
        .ok()
}

/// A cgroup limit file (`max`, or bytes; v1 writes "no limit" as a number near 2⁶³).
pub fn parse_cgroup_limit(text: &str) -> Option<u64> {
    let v: u64 = text.trim().parse().ok()?;
    (v < 1 << 60).then_some(v)
}

/// The process's cgroup path in /proc/self/cgroup: the v2 line `0::/path`, or the v1 line
/// whose controllers include `memory`.
pub fn cgroup_path(text: &str, v2: bool) -> Option<String> {
    text.lines().find_map(|line| {
        let mut f = line.splitn(3, ':');
        let (id, controllers, path) = (f.next()?, f.next()?, f.next()?);
        let mine = if v2 {
            id == "0" && controllers.is_empty()
        } else {
            controllers.split(',').any(|c| c == "memory")
        };
        mine.then(|| path.to_string())
    })
}

/// The smallest limit − usage over the group `rel` under the hierarchy mounted at `root` and
/// its ancestors. A container sees its own group at the mount's root, so a path that does
/// not exist under `root` is read from `root` itself.
pub fn cgroup_headroom(root: &Path, rel: &str, v2: bool) -> Option<u64> {
    let (limit, usage) = if v2 {
        ("memory.max", "memory.current")
    } else {
        ("memory.limit_in_bytes", "memory.usage_in_bytes")
    };
    let read = |dir: &Path, file: &str| std::fs::read_to_string(dir.join(file)).ok();
    let mut dir = root.join(rel.trim_start_matches('/'));
    if !dir.is_dir() {
        dir = root.to_path_buf();
    }
    let mut headroom = None;
    loop {
        if let Some(max) = read(&dir, limit).and_then(|t| parse_cgroup_limit(&t)) {
            let used = read(&dir, usage).and_then(|t| t.trim().parse().ok()).unwrap_or(0);
            headroom = min_known(headroom, Some(max.saturating_sub(used)));
        }
        if dir == root || !dir.pop() || !dir.starts_with(root) {
            return headroom;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_limits_name_the_kernels_buffers_where_it_runs() {
        assert_eq!(
            limits_words(1_006_632_960),
            "free memory, ulimit -v less what is mapped and the product kernel's 0.9 GiB a thread, and the control group's limit"
        );
        assert_eq!(
            limits_words(0),
            "free memory, ulimit -v less what is mapped, and the control group's limit"
        );
    }

    #[test]
    fn work_under_way_is_taken_from_every_known_limit() {
        let limits = Limits {
            machine: Some(10 << 30),
            address_space: None,
            cgroup: Some(3 << 30),
        };
        let less = limits.clone().less(2 << 30);
        assert_eq!(less.machine, Some(8 << 30));
        assert_eq!(less.address_space, None, "unknown stays unknown");
        assert_eq!(less.available(), Some(1 << 30));
        assert_eq!(limits.less(5 << 30).available(), Some(0), "never below zero");
        // A 1.5 GiB estimate fits 3 GiB, not 3 GiB less 2 GiB under way.
        let sizes = Sizes {
            element: Element::Q1,
            unknowns: 1,
            trace: 0,
            points: 0,
        };
        let need = sizes.peak_bytes();
        let room = Limits {
            machine: Some(need),
            ..Limits::default()
        };
        assert!(sizes.check(&room).is_ok());
        assert!(sizes.check(&room.less(1)).is_err());
    }

    #[test]
    fn proc_files_are_read_in_bytes() {
        let meminfo = "MemTotal:       24589764 kB\nMemFree:         1000 kB\nMemAvailable:   23828596 kB\n";
        assert_eq!(parse_meminfo(meminfo), Some(23_828_596 * 1024));
        assert_eq!(
            parse_vm_size("Name:\triplab\nVmPeak:\t  9 kB\nVmSize:\t   2048 kB\n"),
            Some(2 << 20)
        );
        let limits = "Limit                     Soft Limit           Hard Limit           Units     \n\
                      Max stack size            8388608              unlimited            bytes     \n\
                      Max address space         1536000000           unlimited            bytes     \n";
        assert_eq!(parse_rlimit_as(limits), Some(1_536_000_000));
        assert_eq!(parse_rlimit_as(&limits.replace("1536000000", "unlimited")), None);
        assert_eq!(parse_cgroup_limit("max\n"), None);
        assert_eq!(parse_cgroup_limit("9223372036854771712\n"), None);
        assert_eq!(parse_cgroup_limit("2147483648\n"), Some(1 << 31));
    }

    #[test]
    fn the_memory_cgroup_line_is_found_for_both_versions() {
        let hybrid = "4:memory:/process_api/ff8e\n3:cpuset:/\n0::/user.slice/x.scope\n";
        assert_eq!(cgroup_path(hybrid, true).as_deref(), Some("/user.slice/x.scope"));
        assert_eq!(cgroup_path(hybrid, false).as_deref(), Some("/process_api/ff8e"));
        assert_eq!(cgroup_path("5:cpu,cpuacct:/\n", false), None);
        assert_eq!(cgroup_path("1:name=systemd:/\n", true), None);
    }

    /// The tightest level of the hierarchy wins, each less its own usage.
    #[test]
    fn cgroup_limits_are_the_smallest_headroom_up_the_tree() {
        let root = std::env::temp_dir().join(format!("riplab-cgroup-{}", std::process::id()));
        let leaf = root.join("outer/inner");
        std::fs::create_dir_all(&leaf).unwrap();
        let write = |dir: &Path, f: &str, v: &str| std::fs::write(dir.join(f), v).unwrap();
        write(&root, "memory.max", "max\n");
        write(&root.join("outer"), "memory.max", "3000\n");
        write(&root.join("outer"), "memory.current", "1000\n");
        write(&leaf, "memory.max", "2500\n");
        write(&leaf, "memory.current", "100\n");
        // outer: 3000 − 1000 = 2000 < inner: 2500 − 100.
        assert_eq!(cgroup_headroom(&root, "/outer/inner", true), Some(2000));
        write(&leaf, "memory.current", "900\n");
        assert_eq!(cgroup_headroom(&root, "/outer/inner", true), Some(1600));
        // A container sees its group at the root: an unknown path reads the root.
        assert_eq!(cgroup_headroom(&root, "/elsewhere", true), None);
        write(&root, "memory.limit_in_bytes", "700\n");
        write(&root, "memory.usage_in_bytes", "200\n");
        assert_eq!(cgroup_headroom(&root, "/elsewhere", false), Some(500));
        std::fs::remove_dir_all(&root).unwrap();
    }

    #[test]
    fn the_smallest_known_limit_is_available() {
        let l = |machine, address_space, cgroup| Limits {
            machine,
            address_space,
            cgroup,
        };
        assert_eq!(l(None, None, None).available(), None);
        assert_eq!(l(Some(9), None, None).available(), Some(9));
        assert_eq!(l(Some(9), Some(4), Some(7)).available(), Some(4));
        assert_eq!(l(Some(9), None, Some(7)).available(), Some(7));
    }

    /// The dense blocks alone: a long flat strip (m = 8193 trace dofs) needs at least 3m²·8
    /// bytes, and is refused under a limit below that with the numbers in the error.
    #[test]
    fn dense_trace_blocks_are_counted() {
        let s = Sizes {
            element: Element::Q1,
            unknowns: 2 * 8193 * 2,
            trace: 8193,
            points: 2 * 8192,
        };
        let m = 8193.0f64;
        assert!(s.peak_bytes() as f64 >= 8.0 * 3.0 * m * m);
        let limits = Limits {
            machine: Some(1 << 30),
            ..Limits::default()
        };
        assert_eq!(
            s.check(&limits),
            Err(FemError::TooLarge {
                unknowns: s.unknowns,
                need: s.peak_bytes(),
                available: 1 << 30
            })
        );
        assert_eq!(s.check(&Limits::default()), Ok(()));
    }

    /// The estimate is within 30% of the peaks measured with `/usr/bin/time -v` (maximum
    /// resident set, MiB) of `riplab solve --element E --level L` on the default scenario
    /// (half model, 8 × 4 cells at level 0: m = p·8·2^L + 1 trace dofs, 2 points per edge at
    /// most), BENCHMARKS.md.
    #[test]
    fn the_estimate_is_within_30_percent_of_measured_peaks() {
        for (element, level, unknowns, peak_mib) in [
            (Element::Q1, 5, 65_664, 73.0),
            (Element::Q1, 6, 262_400, 286.0),
            (Element::Q1, 7, 1_049_088, 1267.0),
            (Element::Q1, 8, 4_195_328, 5520.0),
            (Element::P1, 5, 65_664, 72.0),
            (Element::P1, 6, 262_400, 291.0),
            (Element::P1, 7, 1_049_088, 1263.0),
            (Element::P1, 8, 4_195_328, 5522.0),
            (Element::Q2, 5, 262_400, 316.0),
            (Element::Q2, 6, 1_049_088, 1374.0),
            (Element::Q2, 7, 4_195_328, 5979.0),
        ] {
            let edges = 8usize << level;
            let s = Sizes {
                element,
                unknowns,
                trace: element.order() * edges + 1,
                points: 2 * edges,
            };
            let ratio = s.peak_bytes() as f64 / (peak_mib * 1024.0 * 1024.0);
            assert!(
                (0.7..1.3).contains(&ratio),
                "{element:?} level {level}: {ratio:.2}"
            );
        }
    }
}
