//! Point clouds (lidar and depth-camera scans) and the voxel operations scanner users run, all
//! written on a point tree's cells:
//!
//! - [`Cloud`]: 3-D points of any [`Scalar`] (LAS files keep their integer coordinates, with
//!   the scale and offset of their [`Frame`]) and their [`Attributes`];
//! - [`voxel`]: voxel grids ([`voxel::VoxelGrid`], by voxel size or by level), voxel-grid
//!   downsampling (one point per occupied voxel: the centroid with averaged attributes, or the
//!   point nearest the centroid) and occupancy as a [`VoxelTree`](crate::VoxelTree), so that two
//!   scans XOR to a change map;
//! - [`outliers`]: statistical outlier removal (Open3D's and PCL's rule) through the k-nearest
//!   self-join;
//! - [`normals`]: normals by principal component analysis of each point's k nearest
//!   neighbours.
//!
//! The formats (XYZ/CSV text, PLY, LAS behind the `las` feature) are in [`crate::io`].
//!
//! ```
//! use orthtree::cloud::{voxel::{Representative, VoxelGrid}, Cloud};
//! let cloud = Cloud::from_points(vec![[0.1, 0.1, 0.1], [0.2, 0.3, 0.1], [1.5, 0.2, 0.1]]);
//! let grid = VoxelGrid::with_size(&cloud.points, 1.0).unwrap();
//! let down = grid.downsample(&cloud, Representative::Centroid).unwrap();
//! assert_eq!(down.len(), 2); // the first two points share a voxel
//! assert!((down.points[0][1] - 0.2).abs() < 1e-12);
//! ```

mod attributes;
mod downsample;
pub mod normals;
pub mod outliers;
pub mod voxel;
mod wide;

pub use attributes::{Attributes, Column};

use crate::geom::Scalar;
use core::fmt;

/// How a cloud's stored coordinates map to the world: `world = stored * scale + offset` per
/// axis (LAS's scale and offset; [`Frame::IDENTITY`] for files of plain coordinates).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// The factor per axis.
    pub scale: [f64; 3],
    /// The offset per axis.
    pub offset: [f64; 3],
}

impl Frame {
    /// Stored coordinates are world coordinates.
    pub const IDENTITY: Frame = Frame {
        scale: [1.0; 3],
        offset: [0.0; 3],
    };

    /// The world coordinates of a stored point (rounded once per axis, by `f64` arithmetic).
    #[inline]
    pub fn to_world<S: Scalar>(&self, p: &[S; 3]) -> [f64; 3] {
        core::array::from_fn(|a| Scalar::to_f64(p[a]) * self.scale[a] + self.offset[a])
    }
}

impl Default for Frame {
    fn default() -> Self {
        Frame::IDENTITY
    }
}

/// A point cloud: positions, their [`Attributes`] (point `i`'s values at index `i` of each
/// column) and the [`Frame`] of the positions.
#[derive(Clone, Debug, PartialEq)]
pub struct Cloud<S = f64> {
    /// The stored coordinates.
    pub points: Vec<[S; 3]>,
    /// The attribute columns.
    pub attributes: Attributes,
    /// The map from stored to world coordinates.
    pub frame: Frame,
}

impl<S: Scalar> Cloud<S> {
    /// A cloud of bare points in world coordinates.
    pub fn from_points(points: Vec<[S; 3]>) -> Self {
        Cloud {
            points,
            attributes: Attributes::default(),
            frame: Frame::IDENTITY,
        }
    }

    /// An empty cloud with room for `n` points, in memory advised to be backed by huge pages
    /// (Linux, feature `huge-pages`, from 4 MiB on; elsewhere a plain reservation). The voxel
    /// operations and tree builds read a cloud's points in spatial order, at random in
    /// memory, and with 4 KiB pages nearly every read of a large cloud also misses the address
    /// cache: `cloud_compare --workload voxel` (10^7 points) took 667-678 ms on a cloud made by
    /// [`Cloud::from_points`], 609-636 ms on one made here. Not a gain everywhere: a tree
    /// build of 10^8 points whose input was in huge pages measured no faster, its own fresh
    /// buffers then waiting for the kernel to compact memory (README, "The input in huge
    /// pages"). The file readers fill their clouds this way.
    ///
    /// ```
    /// use orthtree::cloud::Cloud;
    /// let mut cloud = Cloud::<f64>::with_capacity(1000);
    /// cloud.points.extend((0..1000).map(|i| [i as f64, 0.0, 0.0]));
    /// assert_eq!(cloud.len(), 1000);
    /// ```
    pub fn with_capacity(n: usize) -> Self {
        Cloud::from_points(crate::huge_pages::with_capacity(n))
    }

    /// The number of points.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// `true` when the cloud has no point.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// Checks the columns' lengths and the coordinates.
    ///
    /// # Errors
    /// [`CloudError::ColumnLength`] for a column of another length than the points;
    /// [`CloudError::BadCoordinate`] for a coordinate that is NaN, infinite or not exact in
    /// `f64`.
    pub fn check(&self) -> Result<(), CloudError> {
        self.attributes.check(self.points.len())?;
        for (index, p) in self.points.iter().enumerate() {
            crate::geom::validate_point(p).map_err(|axis| CloudError::BadCoordinate {
                index,
                axis,
                value: p[axis].to_f64(),
            })?;
        }
        Ok(())
    }

    /// The points with their index as item: what a point tree over the cloud is built from
    /// (the item indexes the attribute columns).
    ///
    /// # Errors
    /// [`CloudError::TooManyPoints`] above `u32::MAX` points.
    pub fn entries(&self) -> Result<Vec<([S; 3], u32)>, CloudError> {
        let n = u32::try_from(self.points.len())
            .map_err(|_| CloudError::TooManyPoints { len: self.len() })?;
        Ok(self.points.iter().copied().zip(0..n).collect())
    }

    /// The cloud of the points at `indices`, in that order, with their attributes.
    ///
    /// # Panics
    /// When an index is out of range.
    pub fn select(&self, indices: &[usize]) -> Cloud<S> {
        Cloud {
            points: indices.iter().map(|&i| self.points[i]).collect(),
            attributes: self.attributes.select(indices),
            frame: self.frame,
        }
    }

    /// The points in world coordinates.
    pub fn world_points(&self) -> Vec<[f64; 3]> {
        self.points.iter().map(|p| self.frame.to_world(p)).collect()
    }
}

/// Why a cloud operation refused its input.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum CloudError {
    /// An attribute column's length differs from the number of points.
    ColumnLength {
        /// The column's name.
        column: String,
        /// Its number of values.
        values: usize,
        /// The number of points.
        points: usize,
    },
    /// Point `index` has a coordinate on `axis` that is NaN, infinite, or not exact in `f64`.
    BadCoordinate {
        /// The point.
        index: usize,
        /// The axis.
        axis: usize,
        /// The coordinate (as `f64`).
        value: f64,
    },
    /// More points than a `u32` item can index.
    TooManyPoints {
        /// The number of points.
        len: usize,
    },
    /// A voxel size that is not a positive finite number.
    InvalidVoxelSize(f64),
    /// The voxels asked for are too small for the cloud's extent: more than 2^`max_level`
    /// voxels along an axis.
    TooFine {
        /// The voxels needed along the longest axis.
        voxels: f64,
        /// The deepest level of cells in this dimension.
        max_level: u8,
    },
    /// A level deeper than cells of this dimension reach.
    LevelTooDeep {
        /// The level asked for.
        level: u8,
        /// The deepest level.
        max_level: u8,
    },
    /// The grid's corner or side has no exact value in the cloud's coordinate type (an
    /// integer cloud and a voxel size or corner that is not an integer).
    GridNotRepresentable {
        /// The axis.
        axis: usize,
        /// The value that does not fit.
        value: f64,
    },
    /// A point lies outside the grid's cube.
    OutsideGrid {
        /// The point.
        index: usize,
        /// The first axis on which it lies outside.
        axis: usize,
    },
    /// A neighbour count of 0 (outlier removal and normals need at least one neighbour).
    ZeroNeighbors,
    /// A deviation ratio that is NaN.
    InvalidStdRatio(f64),
    /// Two grids that differ where an operation needs the same one (occupancy XOR).
    GridMismatch,
    /// The tree build refused the points.
    Tree(crate::Error),
    /// A region-tree operation refused (too many nodes).
    Image(crate::image::ImageError),
}

impl fmt::Display for CloudError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CloudError::ColumnLength {
                column,
                values,
                points,
            } => write!(
                f,
                "attribute column {column} has {values} values for {points} points"
            ),
            CloudError::BadCoordinate { index, axis, value } => write!(
                f,
                "point {index}: coordinate {value} on axis {axis} is not finite or not exact"
            ),
            CloudError::TooManyPoints { len } => {
                write!(f, "{len} points exceed the {} a cloud can index", u32::MAX)
            }
            CloudError::InvalidVoxelSize(v) => {
                write!(f, "voxel size {v} is not a positive finite number")
            }
            CloudError::TooFine { voxels, max_level } => write!(
                f,
                "{voxels:.4e} voxels along the longest axis exceed 2^{max_level} ({}), the \
                 finest cells",
                1u64 << max_level
            ),
            CloudError::LevelTooDeep { level, max_level } => {
                write!(f, "level {level} is deeper than the deepest, {max_level}")
            }
            CloudError::GridNotRepresentable { axis, value } => write!(
                f,
                "the grid value {value} on axis {axis} has no exact value in the coordinate type"
            ),
            CloudError::OutsideGrid { index, axis } => {
                write!(f, "point {index} lies outside the grid on axis {axis}")
            }
            CloudError::ZeroNeighbors => write!(f, "the neighbour count must be at least 1"),
            CloudError::InvalidStdRatio(r) => write!(f, "deviation ratio {r} is NaN"),
            CloudError::GridMismatch => write!(f, "the two occupancies use different grids"),
            CloudError::Tree(e) => write!(f, "{e}"),
            CloudError::Image(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for CloudError {}

impl From<crate::Error> for CloudError {
    fn from(e: crate::Error) -> Self {
        CloudError::Tree(e)
    }
}

impl From<crate::image::ImageError> for CloudError {
    fn from(e: crate::image::ImageError) -> Self {
        CloudError::Image(e)
    }
}
