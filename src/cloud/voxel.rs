//! Voxel grids on a point tree's cells: a [`VoxelGrid`] is a root cube and a level, its voxels
//! the cells of that level (half-open `(lo, hi]` on each axis like every cell of the crate, the
//! root's lower faces included: a point on a voxel face belongs to the lower voxel). The
//! points of a tree built on the grid ([`VoxelGrid::tree`]) are sorted by Morton key, so each
//! occupied voxel is one contiguous run of them: [`VoxelGrid::voxels`] finds the runs in one
//! pass over the leaves (a leaf at the grid's level is one voxel; a shallower leaf, holding at
//! most a bucket of points, is cut where its points' voxel changes), with no hash map.
//!
//! Bare points need no tree for this: [`VoxelGrid::occupancy_of`] and the downsampling sort
//! them by voxel key with the build's own keys and radix sort, and read the runs of that order.
//!
//! From the runs: downsampling ([`VoxelGrid::downsample`], in `downsample.rs`) and occupancy
//! as a region tree ([`VoxelGrid::occupancy`]), whose Boolean operations turn two scans of one
//! site into a change map.
//!
//! ```
//! use orthtree::cloud::voxel::VoxelGrid;
//! let grid = VoxelGrid::<3>::with_size(&[[0.0, 0.0, 0.0], [4.0, 0.5, 0.5]], 1.0).unwrap();
//! assert_eq!((grid.level(), grid.voxel_size()), (2, 1.0)); // 4 voxels of side 1 per axis
//! let a = grid.occupancy_of(&[[0.5, 0.5, 0.5], [3.5, 0.5, 0.5]]).unwrap();
//! let b = grid.occupancy_of(&[[0.5, 0.5, 0.5], [2.5, 0.5, 0.5]]).unwrap();
//! assert_eq!((&a ^ &b).len(), 2); // one voxel emptied, one filled
//! ```

use super::CloudError;
use crate::geom::{morton, Aabb, Cell, RootGeometry, Scalar};
use crate::image::{Coverage, RegionTree};
use crate::points::PointTree;
use core::ops::Range;

/// A grid of cubic voxels: the cells at `level` of the cube with lower corner `min` and side
/// `voxel_size * 2^level`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VoxelGrid<const D: usize> {
    min: [f64; D],
    voxel: f64,
    level: u8,
}

/// Which point stands for a voxel's points.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Representative {
    /// The centroid of the voxel's points; intensity, colour, GPS time and extra columns are
    /// their means (integers rounded to nearest), the normal the normalised mean, the class
    /// the most frequent one (the smallest code among ties).
    Centroid,
    /// The voxel's point nearest its centroid (ties to the lowest index), with its attributes.
    Nearest,
}

/// One occupied voxel: its cell and the run of tree slots (positions in
/// [`PointSet::items`](crate::PointSet::items) order) of its points.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Voxel<const D: usize> {
    /// The voxel's cell, at the grid's level.
    pub cell: Cell<D>,
    /// Its points' slots in the tree.
    pub slots: Range<usize>,
}

impl<const D: usize> VoxelGrid<D> {
    /// The grid of voxels of side `voxel` whose cube starts at the points' lowest corner and is
    /// the smallest power-of-two multiple of `voxel` covering them: voxel `i` starts at
    /// `min + i * voxel`. Open3D's `voxel_down_sample` starts its grid half a voxel lower
    /// (`min - voxel / 2 + i * voxel`); [`VoxelGrid::for_box`] on a box with that corner gives
    /// its voxels (a point on a voxel face goes to the lower voxel here, the upper in Open3D).
    ///
    /// # Errors
    /// [`CloudError::InvalidVoxelSize`] unless `voxel` is positive and finite;
    /// [`CloudError::BadCoordinate`] for a coordinate that is not finite;
    /// [`CloudError::TooFine`] when more than 2^[`Cell::MAX_LEVEL`] voxels are needed along an
    /// axis.
    ///
    /// # Complexity
    /// O(n) for the points' bounds.
    pub fn with_size<S: Scalar>(points: &[[S; D]], voxel: f64) -> Result<Self, CloudError> {
        // The points' bounds, through the bulk build's check; no points: the origin.
        let mut bounds =
            crate::points::scan(None, 0..points.len(), &|i| &points[i]).map_err(|e| match e {
                crate::Error::NonFiniteCoordinate { index, axis, .. }
                | crate::Error::InexactCoordinate { index, axis, .. } => {
                    CloudError::BadCoordinate {
                        index,
                        axis,
                        value: Scalar::to_f64(points[index][axis]),
                    }
                }
                other => CloudError::Tree(other),
            })?;
        if points.is_empty() {
            bounds.add_point(&[0.0; D]);
        }
        Self::for_box(&bounds, voxel)
    }

    /// The grid of voxels of side `voxel` whose cube starts at `bounds.min` and covers
    /// `bounds` (for two scans of one site: the box of both).
    ///
    /// # Errors
    /// As [`VoxelGrid::with_size`].
    pub fn for_box(bounds: &Aabb<f64, D>, voxel: f64) -> Result<Self, CloudError> {
        if !(voxel > 0.0 && voxel.is_finite()) {
            return Err(CloudError::InvalidVoxelSize(voxel));
        }
        let extent = (0..D)
            .map(|a| bounds.max[a] - bounds.min[a])
            .fold(0.0f64, f64::max);
        let max_level = Cell::<D>::MAX_LEVEL;
        let mut level = 0u8;
        while voxel * ((1u64 << level) as f64) < extent {
            if level == max_level {
                return Err(CloudError::TooFine {
                    voxels: extent / voxel,
                    max_level,
                });
            }
            level += 1;
        }
        Ok(VoxelGrid {
            min: bounds.min,
            voxel,
            level,
        })
    }

    /// The grid of the cells at `level` of the cube with lower corner `min` and side `side`.
    ///
    /// # Errors
    /// [`CloudError::LevelTooDeep`] beyond [`Cell::MAX_LEVEL`];
    /// [`CloudError::InvalidVoxelSize`] unless `side` is positive and finite.
    pub fn at_level(min: [f64; D], side: f64, level: u8) -> Result<Self, CloudError> {
        let max_level = Cell::<D>::MAX_LEVEL;
        if level > max_level {
            return Err(CloudError::LevelTooDeep { level, max_level });
        }
        let voxel = side / (1u64 << level) as f64;
        if !(voxel > 0.0 && voxel.is_finite() && min.iter().all(|m| m.is_finite())) {
            return Err(CloudError::InvalidVoxelSize(voxel));
        }
        Ok(VoxelGrid { min, voxel, level })
    }

    /// The voxels' level.
    pub fn level(&self) -> u8 {
        self.level
    }

    /// A voxel's side.
    pub fn voxel_size(&self) -> f64 {
        self.voxel
    }

    /// The voxels along each axis: 2^level.
    pub fn side_voxels(&self) -> u32 {
        1 << self.level
    }

    /// The root cube's geometry: that of a tree built with the grid's cube as root box
    /// (the cube `min ..= min + voxel_size * 2^level`, grown by the ulps that rounding needs).
    pub fn geometry(&self) -> RootGeometry<D> {
        let side = self.voxel * (1u64 << self.level) as f64;
        RootGeometry::enclosing(&Aabb {
            min: self.min,
            max: self.min.map(|m| m + side),
        })
    }

    /// The voxel holding `point` (clamped to the cube).
    pub fn voxel_of<S: Scalar>(&self, point: &[S; D]) -> Cell<D> {
        self.geometry()
            .cell_of(&point.map(Scalar::to_f64), self.level)
    }

    /// The grid's cube as a root box of coordinate type `S`.
    ///
    /// # Errors
    /// [`CloudError::GridNotRepresentable`] when a corner coordinate has no exact value of `S`.
    pub fn root_box<S: Scalar>(&self) -> Result<Aabb<S, D>, CloudError> {
        let side = self.voxel * (1u64 << self.level) as f64;
        let exact = |axis: usize, v: f64| -> Result<S, CloudError> {
            let s: Option<S> = num_traits::NumCast::from(v);
            s.filter(|s| Scalar::to_f64(*s) == v)
                .ok_or(CloudError::GridNotRepresentable { axis, value: v })
        };
        let mut min = [S::zero(); D];
        let mut max = [S::zero(); D];
        for a in 0..D {
            min[a] = exact(a, self.min[a])?;
            max[a] = exact(a, self.min[a] + side)?;
        }
        Ok(Aabb { min, max })
    }

    /// A point tree over `entries` on this grid: its root cube is the grid's, and it is not
    /// split below the grid's level.
    ///
    /// # Errors
    /// [`CloudError::GridNotRepresentable`] (see [`VoxelGrid::root_box`]);
    /// [`CloudError::Tree`] for points the build refuses (outside the cube, not finite).
    ///
    /// # Complexity
    /// That of [`PointTree`]'s build, O(n log n).
    pub fn tree<S: Scalar, T: Clone>(
        &self,
        entries: &[([S; D], T)],
    ) -> Result<PointTree<S, T, D>, CloudError> {
        Ok(self.builder()?.build(entries)?)
    }

    /// [`VoxelGrid::tree`] over `points` alone, each item the point's position
    /// ([`PointTreeBuilder::build_indexed`](crate::points::PointTreeBuilder::build_indexed)).
    ///
    /// # Errors
    /// As [`VoxelGrid::tree`].
    ///
    /// # Complexity
    /// That of [`PointTree`]'s build, O(n log n).
    pub fn indexed_tree<S: Scalar>(
        &self,
        points: &[[S; D]],
    ) -> Result<PointTree<S, u32, D>, CloudError> {
        Ok(self.builder()?.build_indexed(points)?)
    }

    /// The builder of this grid's trees: the grid's cube, no split below its level.
    fn builder<S: Scalar>(&self) -> Result<crate::points::PointTreeBuilder<S, D>, CloudError> {
        Ok(PointTree::builder()
            .root_box(self.root_box()?)
            .max_depth(self.level))
    }

    /// The occupied voxels of a tree built on this grid, in Morton order, each with the run of
    /// its points' slots.
    ///
    /// # Errors
    /// [`CloudError::GridMismatch`] when the tree's root cube is not the grid's.
    ///
    /// # Complexity
    /// O(n): one pass over the leaves; the points of leaves above the grid's level are keyed
    /// once each.
    pub fn voxels<S: Scalar, T>(
        &self,
        tree: &PointTree<S, T, D>,
    ) -> Result<Vec<Voxel<D>>, CloudError> {
        let geometry = self.geometry();
        if tree.geometry() != &geometry {
            return Err(CloudError::GridMismatch);
        }
        let mut out: Vec<Voxel<D>> = Vec::new();
        let mut slot = 0usize;
        let mut add = |cell: Cell<D>, slots: Range<usize>| match out.last_mut() {
            Some(last) if last.cell == cell && last.slots.end == slots.start => {
                last.slots.end = slots.end
            }
            _ => out.push(Voxel { cell, slots }),
        };
        for leaf in tree.leaves() {
            let n = leaf.points.len();
            if leaf.cell.level() >= self.level {
                if n > 0 {
                    add(leaf.cell.ancestor(self.level), slot..slot + n);
                }
            } else {
                for (i, p) in leaf.points.iter().enumerate() {
                    let cell = geometry.cell_of(&p.map(Scalar::to_f64), self.level);
                    add(cell, slot + i..slot + i + 1);
                }
            }
            slot += n;
        }
        Ok(out)
    }

    /// The occupied voxels of `points` in Morton order: the tree build's check, keys and sort,
    /// without the tree (`visit_by_cell`). With `contents`, each voxel's run of the points'
    /// input indices (`order`) and the sum of their coordinates, taken as the walk reads the
    /// points in voxel order; without, the cells alone (`order` and `sums` stay empty, and no
    /// point is read after the keys).
    ///
    /// # Errors
    /// As [`VoxelGrid::tree`].
    pub(super) fn sorted_voxels<S: Scalar>(
        &self,
        points: &[[S; D]],
        contents: bool,
    ) -> Result<SortedVoxels<D>, CloudError> {
        let root = self.builder::<S>()?.check_settings(points.len())?;
        crate::points::scan(root.as_ref(), 0..points.len(), &|i| &points[i])?;
        let mut sorted = SortedVoxels {
            order: crate::huge_pages::with_capacity(if contents { points.len() } else { 0 }),
            voxels: Vec::new(),
            sums: Vec::new(),
        };
        let (mut last, mut slot) = (0, 0);
        let geometry = self.geometry();
        let visit = |key, index, point: &[S; D]| {
            if contents {
                sorted.order.push(index as u32);
            }
            match sorted.voxels.last_mut() {
                Some(v) if key == last => v.slots.end = slot + 1,
                _ => {
                    last = key;
                    let cell = Cell::from_morton(key, self.level);
                    sorted.voxels.push(Voxel {
                        cell,
                        slots: slot..slot + 1,
                    });
                    if contents {
                        sorted.sums.push([0.0; D]);
                    }
                }
            }
            slot += 1;
            if let Some(sum) = sorted.sums.last_mut() {
                for a in 0..D {
                    sum[a] += point[a].to_f64();
                }
            }
        };
        crate::points::visit_by_cell(&geometry, points, self.level, contents, visit);
        Ok(sorted)
    }

    /// The occupied voxels of bare points, in Morton order, sorted by voxel without building a
    /// tree (PCL's occupied voxel centres; [`VoxelGrid::voxels`] for a tree's runs).
    ///
    /// # Errors
    /// As [`VoxelGrid::tree`].
    ///
    /// # Complexity
    /// The tree build's sort of the points by key, O(n log n).
    ///
    /// ```
    /// use orthtree::{cloud::voxel::VoxelGrid, Cell};
    /// let points = [[0.5, 0.5], [3.5, 0.5], [0.25, 0.75]];
    /// let grid = VoxelGrid::<2>::with_size(&points, 1.0).unwrap();
    /// let cells = grid.occupied_voxels(&points).unwrap();
    /// assert_eq!(cells, [Cell::new(2, [0, 0]).unwrap(), Cell::new(2, [3, 0]).unwrap()]);
    /// ```
    pub fn occupied_voxels<S: Scalar>(
        &self,
        points: &[[S; D]],
    ) -> Result<Vec<Cell<D>>, CloudError> {
        Ok(self
            .sorted_voxels(points, false)?
            .voxels
            .iter()
            .map(|v| v.cell)
            .collect())
    }

    /// The occupied voxels of a tree built on this grid as a region tree of extent
    /// `2^level` per axis (voxel `c` at pixel `c`): a [`VoxelTree`](crate::VoxelTree) in 3-D.
    ///
    /// # Errors
    /// [`CloudError::GridMismatch`] as [`VoxelGrid::voxels`]; [`CloudError::Image`] when the
    /// region tree would pass [`crate::image::DEFAULT_MAX_NODES`].
    ///
    /// # Complexity
    /// O(n + m log v) for m region-tree nodes and v occupied voxels.
    pub fn occupancy<S: Scalar, T>(
        &self,
        tree: &PointTree<S, T, D>,
    ) -> Result<RegionTree<D>, CloudError> {
        Ok(occupied(&self.voxels(tree)?, self.level)?)
    }

    /// [`VoxelGrid::occupancy`] of bare points, sorted by voxel without building a tree.
    ///
    /// # Errors
    /// As [`VoxelGrid::tree`] and [`VoxelGrid::occupancy`].
    pub fn occupancy_of<S: Scalar>(&self, points: &[[S; D]]) -> Result<RegionTree<D>, CloudError> {
        Ok(occupied(
            &self.sorted_voxels(points, false)?.voxels,
            self.level,
        )?)
    }
}

/// The occupied voxels of bare points ([`VoxelGrid::sorted_voxels`]).
pub(super) struct SortedVoxels<const D: usize> {
    /// The points' input indices, grouped by voxel (with the contents, else empty).
    pub(super) order: Vec<u32>,
    /// The voxels in Morton order, each with its run of `order`.
    pub(super) voxels: Vec<Voxel<D>>,
    /// The sum of each voxel's points (with the contents, else empty).
    pub(super) sums: Vec<[f64; D]>,
}

/// The region tree of extent `2^level` per axis whose black pixels are these voxels (in
/// Morton order, distinct): a cell of the region tree is full when all its `side^D` voxels are
/// present, empty when none is (two binary searches on their keys).
fn occupied<const D: usize>(
    voxels: &[Voxel<D>],
    level: u8,
) -> Result<RegionTree<D>, crate::image::ImageError> {
    let keys: Vec<u64> = voxels.iter().map(|v| v.cell.morton()).collect();
    // 2^32 voxels per axis (2-D, level 32) saturate to an extent the region tree refuses.
    let extent = [1u32.checked_shl(level.into()).unwrap_or(u32::MAX); D];
    RegionTree::from_region(extent, |min, side| {
        let lo = morton::interleave(min, u32::from(level));
        let count = u64::from(side).pow(D as u32);
        let first = keys.partition_point(|&k| k < lo);
        let end = keys.partition_point(|&k| k < lo + count);
        match (end - first) as u64 {
            0 => Coverage::Empty,
            c if c == count => Coverage::Full,
            _ => Coverage::Partial,
        }
    })
}
