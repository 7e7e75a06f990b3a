//! The process's allocator: the system's, asking Linux for transparent huge pages
//! (`madvise(MADV_HUGEPAGE)`) on every block of [`THRESHOLD`] bytes or more.
//!
//! A fresh solve touches gigabytes once: K, each subdomain's factor (0.5 GB apiece at level 7,
//! 2 GB at level 8) and faer's workspaces are new mappings, and with 4 KiB pages the kernel
//! takes one fault (and clears one page) per 4 KiB: 440,000–540,000 faults at level 7, a fifth
//! of the CPU time. Most Linux systems enable transparent huge pages only where a program asks
//! for them (`/sys/kernel/mm/transparent_hugepage/enabled` = `madvise`); asked, the same
//! blocks fault once per 2 MiB (28,000 faults) and level 7 takes 2.8 s instead of 4.0–4.5 s
//! (BENCHMARKS.md, "Huge pages"). Small blocks are left alone: they live in the allocator's
//! arenas, where a huge page would only waste memory. Elsewhere than Linux this is the
//! system allocator unchanged.
//!
//! The binary and the benchmarks install it (`#[global_allocator]`); the library does not
//! impose it on its users.

use std::alloc::{GlobalAlloc, Layout, System};

/// The system allocator, with huge pages asked for on blocks of [`THRESHOLD`] bytes or more.
pub struct HugePages;

/// Blocks from this size on (4 MiB, two huge pages) are advised.
pub const THRESHOLD: usize = 4 << 20;

// SAFETY: every call is forwarded to `System` with the caller's arguments unchanged; `advise`
// only gives the kernel a hint about pages inside the block just returned.
unsafe impl GlobalAlloc for HugePages {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        // SAFETY: the caller's contract for `alloc` is `System.alloc`'s.
        let block = unsafe { System.alloc(layout) };
        advise(block, layout.size());
        block
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        // SAFETY: as `alloc`. Fresh mappings are zero without being touched, so the advice
        // still comes before the first fault.
        let block = unsafe { System.alloc_zeroed(layout) };
        advise(block, layout.size());
        block
    }

    unsafe fn dealloc(&self, block: *mut u8, layout: Layout) {
        // SAFETY: `block` was allocated by `System` (through this allocator) with `layout`.
        unsafe { System.dealloc(block, layout) }
    }

    unsafe fn realloc(&self, block: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        // SAFETY: as `dealloc`, and the caller's contract for `realloc` is `System.realloc`'s.
        let moved = unsafe { System.realloc(block, layout, new_size) };
        advise(moved, new_size);
        moved
    }
}

/// Ask for huge pages on the whole pages inside `[block, block + size)`, when `size` is at
/// least [`THRESHOLD`]. A refusal (a kernel without transparent huge pages) changes nothing.
fn advise(block: *mut u8, size: usize) {
    #[cfg(target_os = "linux")]
    if !block.is_null() && size >= THRESHOLD {
        // SAFETY: sysconf reads a constant of the running system.
        let page = usize::try_from(unsafe { libc::sysconf(libc::_SC_PAGESIZE) }).unwrap_or(4096);
        let start = (block as usize).next_multiple_of(page);
        let end = (block as usize + size) / page * page;
        if end > start {
            // SAFETY: [start, end) lies inside the block the allocator just returned to us;
            // MADV_HUGEPAGE changes how its pages are backed, never its contents.
            unsafe { libc::madvise(start as *mut libc::c_void, end - start, libc::MADV_HUGEPAGE) };
        }
    }
    #[cfg(not(target_os = "linux"))]
    let _ = (block, size);
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Whether the kernel would back the mapping that holds `address` with huge pages
    /// (`THPeligible` of /proc/self/smaps), None when that cannot be read.
    #[cfg(target_os = "linux")]
    fn eligible(address: usize) -> Option<bool> {
        let smaps = std::fs::read_to_string("/proc/self/smaps").ok()?;
        let mut inside = false;
        for line in smaps.lines() {
            if let Some((range, _)) = line.split_once(' ')
                && let Some((lo, hi)) = range.split_once('-')
                && let (Ok(lo), Ok(hi)) = (usize::from_str_radix(lo, 16), usize::from_str_radix(hi, 16))
            {
                inside = (lo..hi).contains(&address);
            } else if inside && let Some(flag) = line.strip_prefix("THPeligible:") {
                return Some(flag.trim() == "1");
            }
        }
        None
    }

    /// A large block is eligible for huge pages when the system allows them only on request;
    /// the bytes it holds are unchanged by the advice, and a small block is not advised.
    #[cfg(target_os = "linux")]
    #[test]
    fn large_blocks_ask_for_huge_pages() {
        let mode = std::fs::read_to_string("/sys/kernel/mm/transparent_hugepage/enabled").unwrap_or_default();
        // First a small block (the system allocator maps it on its own, as it does the large
        // ones while none has been freed): not advised.
        let small = Layout::from_size_align(THRESHOLD / 2, 8).unwrap();
        // SAFETY: a non-zero size; the block is freed with the same layout.
        let block = unsafe { HugePages.alloc(small) };
        if mode.contains("[madvise]") {
            assert_ne!(eligible(block as usize), Some(true), "a 2 MiB block was advised");
        }
        unsafe { HugePages.dealloc(block, small) };

        let layout = Layout::from_size_align(16 << 20, 8).unwrap();
        // SAFETY: a non-zero size; the block is freed below with the same layout.
        let block = unsafe { HugePages.alloc_zeroed(layout) };
        assert!(!block.is_null());
        let middle = block as usize + (8 << 20);
        if mode.contains("[madvise]") {
            assert_eq!(eligible(middle), Some(true), "a 16 MiB block is not eligible");
        }
        // SAFETY: the block holds 16 MiB of zeroed bytes.
        let bytes = unsafe { std::slice::from_raw_parts_mut(block, 16 << 20) };
        assert!(bytes.iter().all(|&b| b == 0));
        bytes[12345] = 7;
        // SAFETY: the block was allocated above with `layout`, and grown with it here.
        let grown = unsafe { HugePages.realloc(block, layout, 32 << 20) };
        assert_eq!(unsafe { *grown.add(12345) }, 7);
        unsafe { HugePages.dealloc(grown, Layout::from_size_align(32 << 20, 8).unwrap()) };
    }
}
