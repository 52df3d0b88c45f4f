//! Large buffers backed by transparent huge pages (Linux, feature `huge-pages`, on by default):
//! the k-nearest joins' answer tables and the bulk builds' keys, sort buffers, points and items
//! (serial and `par_build`).
//!
//! A k-nearest join writes its answer, `k` slots and `k` distances per point (256 MB for the
//! 16 nearest of 10^6 points), into fresh memory, and a bulk build of n points writes about 44
//! bytes per point (`f64` points in 3-D with `u32` items). With the kernel's 4 KiB pages every
//! page costs a fault on its first write. Where transparent huge pages are offered on request
//! (`/sys/kernel/mm/transparent_hugepage/enabled` set to `madvise`, the default of many
//! distributions), `madvise(MADV_HUGEPAGE)` on the buffer before it is written lets the kernel
//! map it in 2 MiB pages instead: 512 times fewer faults, and fewer TLB misses when the build's
//! gather writes its output. Where they are on for everything (`always`) or off (`never`) the
//! advice changes nothing.
//!
//! Measured on the 2-core x86_64 VM with 24 GiB (`madvise` mode), alternated runs:
//! `joins_compare --workload self-knn --reps 5` (`par_k_nearest_self`, k = 16, 10^6 points,
//! both cores), three runs of each build: 495-575 ms with 4 KiB pages, 430-450 ms advised.
//! `build_scale --runs 1` (cold builds of uniform 3-D points, on a host without AVX-512, noisy):
//! at 10^8 points 189-236 ns/point with 4 KiB pages, 158-168 advised (three rounds); at 10^7,
//! fourteen rounds, 87.5-95.4 (median 90.6) against a median of 69.2 advised: 65.0-92.8 in
//! eleven rounds and 127, 142 and 190 in three, slow rounds the build before did not show
//! (`/proc/vmstat` counted no compaction stall and no fallback to small pages; in the slower
//! advised rounds timed by `/usr/bin/time` the extra time was user time, the system time
//! staying 0.25-0.32 s against 0.44-0.62 s unadvised); `cloud_compare --workload
//! voxel --n 10000000 --reps 3` (the downsampling, most of it the build), 1 058-1 175 ms against
//! 766-803; `build_scale --par` at 10^8, 75.6-99.7 ns/point advised (six rounds) against
//! 98.6-155.3 (three). On the day before, on a host with AVX-512, the same advice on the build had
//! measured no change at 10^8 (180-195 ns/point against 180-253).
//!
//! Mapping ahead ([`while_populating`], for `PointTreeBuilder::map_pages_ahead`): even in
//! 2 MiB pages, the kernel zeroes every fresh page on its first write, and on a virtual machine
//! whose host hands memory back (a balloon device) the host maps it again too: at 10^8 points
//! half of a cold serial build's time (51-86 of 132-170 ns/point) was the kernel's. Asking for
//! the pages with `MADV_POPULATE_WRITE` on a second thread while the build fills them moves that
//! work off the build's thread: 76-79 ns/point, the same peak memory (`build_scale --runs 1
//! [--map-ahead]`, three alternated rounds).
//!
//! The advice and the mapping are the two `unsafe` calls here (see [`advise`] and `populate`);
//! an advised Vec stays an ordinary Vec: it is read, written, grown and freed as before.

/// Buffers smaller than this are left alone: they span few whole 2 MiB pages.
#[cfg_attr(
    not(all(target_os = "linux", feature = "huge-pages")),
    allow(dead_code)
)]
const MIN_BYTES: usize = 4 << 20;

/// The alignment and size of a huge page on x86-64 and on 4 KiB-page aarch64; a multiple of
/// every base page size, so an aligned range is a valid `madvise` range everywhere.
#[cfg_attr(
    not(all(target_os = "linux", feature = "huge-pages")),
    allow(dead_code)
)]
const HUGE_PAGE: usize = 2 << 20;

/// Asks the kernel to back the whole 2 MiB pages of `v`'s allocation (its elements and its
/// spare capacity) with huge pages, when the allocation is at least [`MIN_BYTES`]; does nothing
/// elsewhere (other systems, the feature off, small buffers). The contents and the length of
/// `v` are untouched; the advice may be refused (then nothing changes). Most useful before the
/// pages are first written: a `vec![0; n]` of a large `n` is memory the system has not yet
/// handed over.
#[inline]
fn advise<T>(v: &mut Vec<T>) {
    #[cfg(all(target_os = "linux", feature = "huge-pages"))]
    {
        let bytes = v.capacity() * core::mem::size_of::<T>();
        if bytes < MIN_BYTES {
            return;
        }
        let start = v.as_mut_ptr().cast::<u8>();
        let address = start as usize;
        let skip = address.next_multiple_of(HUGE_PAGE) - address;
        let whole = bytes.saturating_sub(skip) / HUGE_PAGE * HUGE_PAGE;
        if whole == 0 {
            return;
        }
        // SAFETY: `madvise` with `MADV_HUGEPAGE` only tells the kernel how to back the pages
        // of a range with memory; it reads and writes nothing of ours and changes neither the
        // range's contents nor its protection, and a refusal is an error code we may ignore.
        // The range is valid for it: `start + skip` is aligned to a huge page (so to the base
        // page), and `skip + whole <= bytes`, the size of `v`'s allocation, which is mapped
        // memory of this process for as long as `v` lives (an allocation of at least
        // `MIN_BYTES` is never the dangling pointer of an empty Vec).
        #[allow(unsafe_code)]
        unsafe {
            libc::madvise(
                start.add(skip).cast::<libc::c_void>(),
                whole,
                libc::MADV_HUGEPAGE,
            );
        }
    }
    #[cfg(not(all(target_os = "linux", feature = "huge-pages")))]
    let _ = v;
}

/// An empty Vec with room for `n` elements, advised to be backed by huge pages before anything
/// is written to it.
#[inline]
pub(crate) fn with_capacity<T>(n: usize) -> Vec<T> {
    let mut v = Vec::with_capacity(n);
    advise(&mut v);
    v
}

/// `n` zeros in a Vec advised to be backed by huge pages before anything is written to it.
#[inline]
pub(crate) fn zeros<T: Copy + Default>(n: usize) -> Vec<T> {
    let mut v = vec![T::default(); n];
    advise(&mut v);
    v
}

/// Buffers whose pages are mapped ahead on another thread ([`while_populating`]) when their
/// ranges add up to at least this: below it the thread costs more than the faults.
#[cfg_attr(
    not(all(target_os = "linux", feature = "huge-pages")),
    allow(dead_code)
)]
const POPULATE_MIN_BYTES: usize = 64 << 20;

/// The whole allocation of `v` (its elements and its spare capacity) as a range of addresses,
/// for [`while_populating`].
#[inline]
pub(crate) fn allocation<T>(v: &Vec<T>) -> core::ops::Range<usize> {
    let start = v.as_ptr() as usize;
    start..start + v.capacity() * core::mem::size_of::<T>()
}

/// Runs `work` on this thread while another asks the kernel to map the pages of `stages`
/// (`madvise(MADV_POPULATE_WRITE)`, Linux 5.14 and later), so that the first writes to fresh
/// buffers do not stop `work` at a page fault each: on a machine with a second core the kernel
/// zeroes the pages there. The stages are mapped one after the other, in the order `work` first
/// writes them; the ranges of one stage a slice of each in turn (a 64th of every range, then the
/// next), for buffers that `work` writes side by side. The mapping stops when `work` returns.
/// The ranges must lie in allocations that outlive this call and that `work` does not free or
/// grow; nothing in them is read or written (pages already present keep their contents, new
/// ones come in zeroed, as a first write would have them). Without a second core, below
/// [`POPULATE_MIN_BYTES`], on other systems or with the feature off, it just runs `work`; a
/// kernel that refuses the advice leaves the faults to the first writes, as before.
pub(crate) fn while_populating<R>(
    stages: &[&[core::ops::Range<usize>]],
    work: impl FnOnce() -> R,
) -> R {
    #[cfg(all(target_os = "linux", feature = "huge-pages"))]
    {
        use std::sync::atomic::{AtomicBool, Ordering};
        const SLICES: usize = 64;
        let bytes: usize = stages.iter().flat_map(|s| s.iter()).map(|r| r.len()).sum();
        let cores = std::thread::available_parallelism().map_or(1, |c| c.get());
        if bytes >= POPULATE_MIN_BYTES && cores >= 2 {
            let done = AtomicBool::new(false);
            return std::thread::scope(|scope| {
                // A thread the system will not start maps nothing: the first writes fault.
                let _ = std::thread::Builder::new().spawn_scoped(scope, || {
                    for ranges in stages {
                        for slice in 0..SLICES {
                            for r in *ranges {
                                if done.load(Ordering::Relaxed) {
                                    return;
                                }
                                // where slice `s` of `r` starts; the last one ends at `r.end`
                                let cut = |s| match s {
                                    SLICES => r.end,
                                    _ => r.start + r.len() / SLICES * s,
                                };
                                populate(cut(slice)..cut(slice + 1));
                            }
                        }
                    }
                });
                let result = work();
                done.store(true, Ordering::Relaxed);
                result
            });
        }
    }
    #[cfg(not(all(target_os = "linux", feature = "huge-pages")))]
    let _ = stages;
    work()
}

/// Maps the whole base pages of `range` writable now (see [`while_populating`]).
#[cfg(all(target_os = "linux", feature = "huge-pages"))]
fn populate(range: core::ops::Range<usize>) {
    const PAGE: usize = 4096;
    let start = range.start.next_multiple_of(PAGE);
    let end = range.end / PAGE * PAGE;
    if end <= start {
        return;
    }
    // SAFETY: `MADV_POPULATE_WRITE` faults the pages of the range in as a write would, without
    // writing: it changes neither the contents a program can read (present pages keep theirs,
    // new ones are the zero pages a first write would get) nor the protection, and a refusal
    // (an older kernel) is an error code we may ignore. The range is page-aligned and inside an
    // allocation that the caller of `while_populating` keeps mapped until this returns.
    #[allow(unsafe_code)]
    unsafe {
        libc::madvise(
            start as *mut libc::c_void,
            end - start,
            libc::MADV_POPULATE_WRITE,
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The advised path itself: buffers below and above the threshold, from an aligned or an
    /// offset start, written and read back, grown past their capacity and freed.
    #[test]
    fn advised_buffers_hold_what_is_written() {
        for n in [3, MIN_BYTES / 8 + 1, 3 * HUGE_PAGE / 8 + 5] {
            let mut v: Vec<u64> = zeros(n);
            assert!(v.len() == n && v.iter().all(|&x| x == 0));
            for (i, x) in v.iter_mut().enumerate() {
                *x = (i as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15);
            }
            assert!((0..n).all(|i| v[i] == (i as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15)));
            v.push(7);
            assert_eq!((v.len(), v[n]), (n + 1, 7));
        }
        let mut v: Vec<u8> = Vec::with_capacity(MIN_BYTES + HUGE_PAGE + 12_345);
        v.extend_from_slice(&[1, 2, 3]);
        advise(&mut v);
        v.resize(MIN_BYTES + 100, 9);
        assert_eq!((&v[..4], v[MIN_BYTES + 99]), (&[1, 2, 3, 9][..], 9));
    }

    /// The mapping ahead: two buffers above the threshold (one partly written before, whose
    /// contents must stay; one from an offset, unaligned start) filled while another thread maps
    /// them, and a range below the threshold, which maps nothing.
    #[test]
    fn buffers_mapped_ahead_hold_what_is_written() {
        let n = POPULATE_MIN_BYTES / 8 + 4099;
        let value = |i: usize| (i as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15);
        let mut a: Vec<u64> = with_capacity(n);
        a.extend((0..1000).map(value));
        let mut b: Vec<u8> = Vec::with_capacity(3 * HUGE_PAGE + 77);
        b.push(5);
        let ranges = [allocation(&a), allocation(&b)];
        let first = ranges[1].start + 1;
        let written = while_populating(&[&[ranges[0].clone(), first..ranges[1].end]], || {
            a.extend((1000..n).map(value));
            b.resize(3 * HUGE_PAGE + 77, 6);
            a.len() + b.len()
        });
        assert_eq!(written, n + 3 * HUGE_PAGE + 77);
        assert!(a.iter().enumerate().all(|(i, &x)| x == value(i)));
        assert!(b[0] == 5 && b[1..].iter().all(|&x| x == 6));
        let mut small = vec![1u32; 10];
        let sum = while_populating(&[&[allocation(&small)]], || {
            small.push(2);
            small.iter().sum::<u32>()
        });
        assert_eq!(sum, 12);
    }
}
