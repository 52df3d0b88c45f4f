//! Point clouds: the PLY, XYZ/CSV and LAS readers and writers (round trips, hostile files), and
//! the voxel operations against brute force (downsampling and occupancy against a sort by voxel
//! key, outlier removal and normals against a k-nearest scan, outlier removal on clouds whose
//! distances leave `f64`'s range); the out-of-core build against the in-memory one (feature
//! `saved`).

mod formats;
mod formats_hostile;
#[cfg(all(feature = "las", feature = "rayon"))]
mod las_entries;
#[cfg(feature = "las")]
mod las_files;
mod neighbours;
#[cfg(feature = "saved")]
mod out_of_core;
mod outlier_extremes;
mod voxels;
