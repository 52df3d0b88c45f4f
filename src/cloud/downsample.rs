//! Voxel-grid downsampling (Open3D's `voxel_down_sample`, PCL's `VoxelGrid` filter) on the
//! points sorted by voxel key (the runs [`VoxelGrid::voxels`] gives for a tree, without the
//! tree): one output point per occupied voxel, in Morton order of the voxels, either the
//! centroid of the voxel's points with their attributes averaged, or the point nearest that
//! centroid with its own attributes.

use super::voxel::{Representative, SortedVoxels, Voxel, VoxelGrid};
use super::{Attributes, Cloud, CloudError, Column};
use crate::geom::Scalar;

impl VoxelGrid<3> {
    /// The cloud downsampled to one point per occupied voxel (in Morton order of the voxels),
    /// coordinates in the cloud's own frame as `f64`.
    ///
    /// # Errors
    /// [`CloudError::ColumnLength`] for attribute columns of another length than the points;
    /// as [`VoxelGrid::tree`] for points the grid's tree refuses.
    ///
    /// # Complexity
    /// The tree build's sort of the points by key, O(n log n), then O(n).
    ///
    /// ```
    /// use orthtree::cloud::{voxel::{Representative, VoxelGrid}, Cloud};
    /// let mut cloud = Cloud::from_points(vec![[0, 0, 0], [1, 1, 1], [2, 2, 2], [7, 7, 7]]);
    /// cloud.attributes.intensity = Some(vec![10, 20, 31, 5]);
    /// let grid = VoxelGrid::with_size(&cloud.points, 4.0).unwrap();
    /// let mean = grid.downsample(&cloud, Representative::Centroid).unwrap();
    /// assert_eq!(mean.points, [[1.0, 1.0, 1.0], [7.0, 7.0, 7.0]]);
    /// assert_eq!(mean.attributes.intensity, Some(vec![20, 5])); // 61 / 3 rounded
    /// let near = grid.downsample(&cloud, Representative::Nearest).unwrap();
    /// assert_eq!(near.attributes.intensity, Some(vec![20, 5]));
    /// ```
    pub fn downsample<S: Scalar>(
        &self,
        cloud: &Cloud<S>,
        representative: Representative,
    ) -> Result<Cloud<f64>, CloudError> {
        cloud.attributes.check(cloud.len())?;
        let SortedVoxels {
            order,
            voxels,
            sums,
        } = self.sorted_voxels(&cloud.points, true)?;
        let index = |slot: usize| order[slot] as usize;
        // Plain sums: exact for integer coordinates (so ties in Nearest are true ties).
        let centroids = voxels
            .iter()
            .zip(&sums)
            .map(|(v, sum)| sum.map(|s| s / v.slots.len() as f64));
        match representative {
            Representative::Nearest => {
                let mut chosen = Vec::with_capacity(voxels.len());
                for (v, c) in voxels.iter().zip(centroids) {
                    // each point's distance once, ties to the lowest index
                    let d2 = |i: usize| -> f64 {
                        let p = cloud.points[i];
                        (0..3).map(|a| (Scalar::to_f64(p[a]) - c[a]).powi(2)).sum()
                    };
                    let (_, best) = (v.slots.clone().map(index).map(|i| (d2(i), i)))
                        .min_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)))
                        .expect("an occupied voxel has a point");
                    chosen.push(best);
                }
                let picked = cloud.select(&chosen);
                Ok(Cloud {
                    points: picked
                        .points
                        .iter()
                        .map(|p| p.map(Scalar::to_f64))
                        .collect(),
                    attributes: picked.attributes,
                    frame: cloud.frame,
                })
            }
            Representative::Centroid => {
                let points = centroids.collect();
                Ok(Cloud {
                    points,
                    attributes: averaged(&cloud.attributes, &voxels, &order),
                    frame: cloud.frame,
                })
            }
        }
    }
}

/// The point indices of one voxel: its run of the voxel order.
#[derive(Clone, Copy)]
struct Group<'a> {
    slots: &'a [u32],
}

impl Group<'_> {
    fn indices(self) -> impl Iterator<Item = usize> {
        self.slots.iter().map(|&i| i as usize)
    }
}

/// The attributes of each voxel's points (`order`: the points' input indices grouped by
/// voxel), averaged as [`Representative::Centroid`] says. Nothing is gathered for a cloud
/// without attributes.
fn averaged(a: &Attributes, voxels: &[Voxel<3>], order: &[u32]) -> Attributes {
    let groups: Vec<Group<'_>> = if a.is_empty() {
        Vec::new()
    } else {
        voxels
            .iter()
            .map(|v| Group {
                slots: &order[v.slots.clone()],
            })
            .collect()
    };
    let mean = |g: Group<'_>, value: &dyn Fn(usize) -> f64| {
        g.indices().map(value).sum::<f64>() / g.slots.len() as f64
    };
    let per_group = |f: &dyn Fn(Group<'_>) -> f64| groups.iter().map(|&g| f(g)).collect::<Vec<_>>();
    Attributes {
        intensity: a.intensity.as_ref().map(|c| {
            let m = per_group(&|g| mean(g, &|i| f64::from(c[i])));
            m.iter().map(|v| v.round() as u16).collect()
        }),
        classification: a.classification.as_ref().map(|c| {
            groups
                .iter()
                .map(|g| {
                    let mut counts = [0u32; 256];
                    for i in g.indices() {
                        counts[c[i] as usize] += 1;
                    }
                    let top = *counts.iter().max().expect("256 counts");
                    counts.iter().position(|&n| n == top).expect("the maximum") as u8
                })
                .collect()
        }),
        color: a.color.as_ref().map(|c| {
            groups
                .iter()
                .map(|&g| core::array::from_fn(|k| mean(g, &|i| f64::from(c[i][k])).round() as u16))
                .collect()
        }),
        gps_time: a
            .gps_time
            .as_ref()
            .map(|c| per_group(&|g| mean(g, &|i| c[i]))),
        normal: a.normal.as_ref().map(|c| {
            groups
                .iter()
                .map(|&g| {
                    let m: [f64; 3] = core::array::from_fn(|k| mean(g, &|i| f64::from(c[i][k])));
                    let len = m.iter().map(|x| x * x).sum::<f64>().sqrt();
                    let scale = if len > 0.0 { 1.0 / len } else { 0.0 };
                    m.map(|x| (x * scale) as f32)
                })
                .collect()
        }),
        extra: a
            .extra
            .iter()
            .map(|col| Column {
                name: col.name.clone(),
                values: per_group(&|g| mean(g, &|i| col.values[i])),
            })
            .collect(),
    }
}
