//! The walk's large read-mostly arrays (BVH node pairs, leaf-order triangle corners) in memory
//! the kernel is asked to back with 2 MiB pages (`madvise(MADV_HUGEPAGE)`, before the first
//! write, as Embree does). With 4 KiB pages the million-triangle `bumpy` spreads its ~60 MB
//! walk data over ~15,000 pages, and an incoherent ray misses the TLB on nearly every node
//! pair. Only a hint: where the kernel gives no huge pages (transparent huge pages off, not
//! Linux) the memory is ordinary, and the contents are the same either way.

use bytemuck::Pod;
use memmap2::MmapMut;

/// A fixed-length array of `T` in an anonymous mapping advised for huge pages, or on the heap
/// where no mapping was had (or none is needed: no items).
#[derive(Debug)]
pub struct HugePaged<T>(Storage<T>);

#[derive(Debug)]
enum Storage<T> {
    /// Exactly the items' bytes.
    Mapped(MmapMut),
    Heap(Box<[T]>),
}

impl<T: Pod> HugePaged<T> {
    /// `len` zeroed items, filled by `fill` in place.
    pub fn new(len: usize, fill: impl FnOnce(&mut [T])) -> Self {
        let bytes = len * size_of::<T>();
        let mapped = (bytes > 0).then(|| MmapMut::map_anon(bytes)).and_then(|m| {
            m.inspect_err(|e| log::debug!("no memory mapping for {len} walk items ({e}): on the heap")).ok()
        });
        match mapped {
            Some(mut map) => {
                advise_huge_pages(&map);
                // An anonymous mapping is zero-filled and starts on a page boundary: aligned
                // for any `T` of this crate.
                fill(bytemuck::cast_slice_mut(&mut map[..]));
                Self(Storage::Mapped(map))
            }
            None => {
                let mut items = vec![T::zeroed(); len].into_boxed_slice();
                fill(&mut items);
                Self(Storage::Heap(items))
            }
        }
    }
}

#[cfg(target_os = "linux")]
fn advise_huge_pages(map: &MmapMut) {
    if let Err(e) = map.advise(memmap2::Advice::HugePage) {
        log::debug!("no huge pages for the walk's arrays: {e}");
    }
}

#[cfg(not(target_os = "linux"))]
fn advise_huge_pages(_: &MmapMut) {}

impl<T: Pod> std::ops::Deref for HugePaged<T> {
    type Target = [T];

    fn deref(&self) -> &[T] {
        match &self.0 {
            Storage::Mapped(map) => bytemuck::cast_slice(&map[..]),
            Storage::Heap(items) => items,
        }
    }
}

impl<T: Pod + PartialEq> PartialEq for HugePaged<T> {
    fn eq(&self, other: &Self) -> bool {
        **self == **other
    }
}

impl<T: Pod> Default for HugePaged<T> {
    fn default() -> Self {
        Self::new(0, |_| {})
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn filled_in_place_and_read_back_whatever_the_storage() {
        let paged = HugePaged::<[u32; 2]>::new(100_000, |out| {
            for (i, o) in out.iter_mut().enumerate() {
                *o = [i as u32, 7];
            }
        });
        assert_eq!(paged.len(), 100_000);
        assert_eq!(paged[99_999], [99_999, 7]);
        assert!(paged.iter().enumerate().all(|(i, v)| *v == [i as u32, 7]));
        let empty = HugePaged::<[u32; 2]>::default();
        assert!(empty.is_empty());
        assert_ne!(paged, empty);
    }
}
