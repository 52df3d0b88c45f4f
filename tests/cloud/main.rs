//! Point clouds: the PLY, XYZ/CSV and LAS readers and writers (round trips, hostile files), and
//! the voxel operations against brute force (downsampling and occupancy against a sort by voxel
//! key, outlier removal and normals against a k-nearest scan).

#[path = "../common/mod.rs"]
mod common;

mod formats;
mod formats_hostile;
mod neighbours;
mod voxels;
