//! The messages of [`MeshValidationError`]: one sentence per broken invariant, naming the
//! triangles, vertices, edges and points concerned, with the measured value against the rule
//! (an angle in degrees, a doubled area, the region's name).

use super::violation::{MeshValidationError, RegionRule};
use super::{degrees, SegmentKind};
use crate::mesh::error::Half;
use core::fmt;

impl fmt::Display for MeshValidationError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::TriangleVertexOutOfRange {
                triangle,
                vertices,
                vertex_count,
            } => write!(
                f,
                "triangle {triangle} {vertices:?} refers to a vertex out of range (there are \
                 {vertex_count} vertices)"
            ),
            Self::RegionCount { regions, triangles } => {
                write!(f, "{regions} regions for {triangles} triangles")
            }
            Self::SegmentVertexOutOfRange {
                segment,
                vertices,
                vertex_count,
            } => write!(
                f,
                "segment {segment} {vertices:?} refers to a vertex out of range (there are \
                 {vertex_count} vertices)"
            ),
            Self::TooManyTriangles { triangles } => {
                write!(f, "{triangles} triangles: too many to check")
            }
            Self::VertexOutsideBoard {
                vertex,
                point,
                size,
            } => write!(
                f,
                "vertex {vertex} at {point:?} lies outside the board [0, {size}]^2"
            ),
            Self::NotCounterClockwise {
                triangle,
                vertices,
                points: [a, b, c],
                doubled_area,
            } => {
                let what = if *doubled_area == 0 {
                    "degenerate"
                } else {
                    "clockwise"
                };
                write!(
                    f,
                    "triangle {triangle} {vertices:?} at {a:?}, {b:?}, {c:?} is {what} (doubled \
                     area {doubled_area})"
                )
            }
            Self::EdgeInMoreThanTwoTriangles {
                edge: [a, b],
                triangles,
            } => write!(
                f,
                "edge {a}-{b} belongs to {} triangles {triangles:?}",
                triangles.len()
            ),
            Self::RepeatedDirectedEdge {
                from,
                to,
                triangles: [s, t],
            } => write!(
                f,
                "triangles {s} and {t} both use the directed edge {from} -> {to}"
            ),
            Self::UnpairedEdge {
                from,
                to,
                points: [p, q],
                triangle,
            } => write!(
                f,
                "edge {from} -> {to} ({p:?} -> {q:?}) of triangle {triangle} has no triangle on \
                 its other side and does not run counter-clockwise along the board boundary"
            ),
            Self::BoundaryCover {
                side,
                at,
                gap,
                triangle,
            } => {
                let what = if *gap { "a gap" } else { "an overlap" };
                write!(
                    f,
                    "the boundary edges on the {side} side have {what} at {at} (triangle \
                     {triangle})"
                )
            }
            Self::BoundaryEnd { side, end, size } => write!(
                f,
                "the boundary edges on the {side} side end at {end}, not at U = {size}"
            ),
            Self::CoincidentVertices {
                vertices: [v, w],
                point,
            } => write!(f, "vertices {v} and {w} are both at {point:?}"),
            Self::NotLatticeDirection {
                component,
                edge,
                from,
                to,
            } => write!(
                f,
                "component {component} edge {edge} {from:?} -> {to:?} is not a lattice direction"
            ),
            Self::OutlineVertexMissing { component, point } => {
                write!(
                    f,
                    "component {component} vertex {point:?} is not a mesh vertex"
                )
            }
            Self::OutlineEdgeBroken {
                component,
                edge,
                from,
                to,
                at,
            } => write!(
                f,
                "component {component} edge {edge} {from:?} -> {to:?}: no mesh edge leaves \
                 {at:?} along it"
            ),
            Self::RegionOutOfRange {
                triangle,
                vertices,
                region,
                components,
            } => write!(
                f,
                "triangle {triangle} {vertices:?} has region {region}, but the board has \
                 {components} components"
            ),
            Self::WrongRegion {
                triangle,
                region,
                expected,
                edge: [a, b],
                rule,
            } => {
                write!(f, "triangle {triangle} has region {region}, but it lies ")?;
                match rule {
                    RegionRule::LeftOfOutline(c) => write!(f, "left of component {c}'s outline")?,
                    RegionRule::RightOfOutline(c) => write!(f, "right of component {c}'s outline")?,
                    RegionRule::AcrossFrom(t) => {
                        write!(f, "across a non-input edge from triangle {t}")?
                    }
                }
                write!(f, " (edge {a} -> {b}), so region {expected}")
            }
            Self::RegionArea {
                region,
                doubled_area,
                expected_doubled_area,
            } => write!(
                f,
                "the triangles of region {region} cover area {}, component {region} has area {}",
                Half(*doubled_area),
                Half(*expected_doubled_area)
            ),
            Self::SegmentNotEdge {
                segment,
                vertices: [a, b],
                kind,
            } => write!(f, "segment {segment} {a}-{b} ({kind:?}) is not a mesh edge"),
            Self::RepeatedSegment {
                segments: [j, k],
                vertices: [a, b],
                kind,
            } => write!(f, "segments {j} and {k} both mark {a}-{b} as {kind:?}"),
            Self::MissingBoundarySegment { edge: [a, b] } => {
                write!(f, "board boundary edge {a}-{b} has no Boundary segment")
            }
            Self::MissingOutlineSegment {
                edge: [a, b],
                component,
            } => write!(
                f,
                "edge {a}-{b} of component {component}'s outline has no segment"
            ),
            Self::SegmentWrongKind {
                segment,
                vertices: [a, b],
                kind,
            } => {
                write!(f, "segment {segment} {a}-{b} is marked as on ")?;
                match kind {
                    SegmentKind::Boundary => write!(f, "the board boundary")?,
                    SegmentKind::Component(c) => write!(f, "component {c}'s outline")?,
                }
                write!(f, ", but is not")
            }
            Self::Area { doubled_area, size } => write!(
                f,
                "the triangles cover area {}, not U^2 = {}",
                Half(*doubled_area),
                i128::from(*size) * i128::from(*size)
            ),
            Self::Angle {
                triangle,
                vertices,
                vertex,
                point,
                dot,
                cross,
            } => {
                let what = if *dot < 0 { "above 90" } else { "below 45" };
                write!(
                    f,
                    "triangle {triangle} {vertices:?}: the angle at vertex {vertex} {point:?} is \
                     {:.2} degrees, {what}",
                    degrees((*dot, *cross))
                )
            }
            Self::Euler {
                vertices,
                edges,
                triangles,
            } => {
                let chi = *vertices as i64 - *edges as i64 + *triangles as i64;
                write!(
                    f,
                    "V - E + F = {vertices} - {edges} + {triangles} = {chi}, not 1"
                )
            }
            Self::NotDelaunay {
                edge: [a, b],
                vertex,
                point,
                triangle,
                circumcircle_of,
                opposite,
            } => write!(
                f,
                "across edge {a}-{b}: vertex {vertex} {point:?} of triangle {triangle} lies \
                 strictly inside the circumcircle of triangle {circumcircle_of} (opposite vertex \
                 {opposite})"
            ),
        }
    }
}
