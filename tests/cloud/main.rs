//! Point clouds: the PLY, XYZ/CSV and LAS readers and writers (round trips, hostile files), and
//! the voxel operations against brute force (downsampling and occupancy against a sort by voxel
//! key, outlier removal and normals against a k-nearest scan).

#[path = "../common/mod.rs"]
mod common;

mod formats;
mod formats_hostile;
#[cfg(feature = "las")]
mod las_files;
mod neighbours;
mod voxels;
