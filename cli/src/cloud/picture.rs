//! Top-down pictures of a cloud: a heat map of point density (points per pixel, on a log
//! scale) and a change map (voxels gone in red, voxels new in green), written as PNG with the
//! `png` feature and as SVG without it (as `orthtree image` does).

use crate::Failure;
use std::io::Write;
use std::path::{Path, PathBuf};

/// The longest side of a PNG picture, in pixels.
const PNG_SIDE: usize = 512;
/// The longest side of an SVG picture, in cells (each a rectangle; runs of equal colour
/// merged).
const SVG_SIDE: usize = 160;

/// A top-down raster over the box `min .. max` of the x-y plane: `w x h` cells, row 0 at the
/// top (largest y), each with two counts (one channel for density; gone and new for changes).
pub struct Raster {
    min: [f64; 2],
    cell: f64,
    w: usize,
    h: usize,
    counts: Vec<[f64; 2]>,
}

impl Raster {
    /// A raster over `min .. max` with at most `side` cells along the longer axis.
    fn new(min: [f64; 2], max: [f64; 2], side: usize) -> Raster {
        let extent = (max[0] - min[0]).max(max[1] - min[1]);
        let cell = if extent > 0.0 {
            extent / side as f64
        } else {
            1.0
        };
        let cells = |a: usize| (((max[a] - min[a]) / cell).ceil() as usize).clamp(1, side);
        let (w, h) = (cells(0), cells(1));
        Raster {
            min,
            cell,
            w,
            h,
            counts: vec![[0.0; 2]; w * h],
        }
    }

    /// A raster with about `per_cell` points in an average cell of `n` points spread over
    /// the box, at least 16 and at most the output format's side (512 for PNG, 160 for SVG)
    /// cells along the longer axis.
    pub fn for_box(min: [f64; 2], max: [f64; 2], n: usize, per_cell: f64) -> Raster {
        let top = if cfg!(feature = "png") {
            PNG_SIDE
        } else {
            SVG_SIDE
        };
        let side = ((n as f64 / per_cell).sqrt() as usize).clamp(16, top);
        Raster::new(min, max, side)
    }

    /// Adds `weight` to channel `channel` of the cell holding `(x, y)` (points outside are
    /// clamped to the border).
    pub fn add(&mut self, x: f64, y: f64, channel: usize, weight: f64) {
        let i = (((x - self.min[0]) / self.cell) as usize).min(self.w - 1);
        let j = (((y - self.min[1]) / self.cell) as usize).min(self.h - 1);
        self.counts[(self.h - 1 - j) * self.w + i][channel] += weight;
    }

    /// Adds `weight` to channel `channel` of every cell the rectangle `lo .. hi` covers
    /// (a voxel column's footprint), in proportion to the overlap.
    pub fn add_rect(&mut self, lo: [f64; 2], hi: [f64; 2], channel: usize, weight: f64) {
        let to = |v: f64, a: usize| (v - self.min[a]) / self.cell;
        let (x0, x1, y0, y1) = (to(lo[0], 0), to(hi[0], 0), to(lo[1], 1), to(hi[1], 1));
        let area = ((x1 - x0) * (y1 - y0)).max(f64::MIN_POSITIVE);
        let i0 = (x0.floor().max(0.0) as usize).min(self.w - 1);
        let j0 = (y0.floor().max(0.0) as usize).min(self.h - 1);
        let i1 = (x1.ceil().max(1.0) as usize).min(self.w);
        let j1 = (y1.ceil().max(1.0) as usize).min(self.h);
        for j in j0..j1 {
            let oy = (y1.min(j as f64 + 1.0) - y0.max(j as f64)).max(0.0);
            for i in i0..i1 {
                let ox = (x1.min(i as f64 + 1.0) - x0.max(i as f64)).max(0.0);
                self.counts[(self.h - 1 - j) * self.w + i][channel] += weight * ox * oy / area;
            }
        }
    }

    /// The picture's size in cells.
    pub fn size(&self) -> (usize, usize) {
        (self.w, self.h)
    }

    /// The side of a cell in world units.
    pub fn cell(&self) -> f64 {
        self.cell
    }

    /// The density colours: black where empty, then a ramp from dark blue through magenta and
    /// orange to pale yellow by log(1 + count) against the largest.
    pub fn density_rgb(&self) -> Vec<[u8; 3]> {
        let top = self.counts.iter().map(|c| c[0]).fold(0.0, f64::max);
        let scale = (1.0 + top).ln().max(f64::MIN_POSITIVE);
        self.counts
            .iter()
            .map(|c| match c[0] {
                v if v <= 0.0 => [0, 0, 0],
                v => ramp((1.0 + v).ln() / scale),
            })
            .collect()
    }

    /// The change colours on a dark grey ground: channel 0 (gone) red, channel 1 (new) green,
    /// each as bright as the square root of its count against the largest ( a column where a building went
    /// outshines the one or two voxels that flicker where a surface is sampled afresh); both
    /// give yellow.
    pub fn change_rgb(&self) -> Vec<[u8; 3]> {
        let top = self
            .counts
            .iter()
            .map(|c| c[0].max(c[1]))
            .fold(0.0, f64::max);
        let level = |v: f64| (v / top.max(f64::MIN_POSITIVE)).clamp(0.0, 1.0).sqrt();
        self.counts
            .iter()
            .map(|c| {
                let (r, g) = (level(c[0]), level(c[1]));
                let mix = |v: f64| (24.0 + 231.0 * v) as u8;
                [mix(r), mix(g), 24]
            })
            .collect()
    }
}

/// A colour ramp over `t` in [0, 1] (after matplotlib's "magma", five stops).
fn ramp(t: f64) -> [u8; 3] {
    const STOPS: [[f64; 3]; 5] = [
        [20.0, 14.0, 54.0],
        [114.0, 31.0, 129.0],
        [205.0, 64.0, 113.0],
        [252.0, 137.0, 97.0],
        [252.0, 253.0, 191.0],
    ];
    let t = t.clamp(0.0, 1.0) * (STOPS.len() - 1) as f64;
    let k = (t.floor() as usize).min(STOPS.len() - 2);
    let f = t - k as f64;
    core::array::from_fn(|c| (STOPS[k][c] + f * (STOPS[k + 1][c] - STOPS[k][c])).round() as u8)
}

/// Writes the `w x h` colours as `stem.png` (feature `png`; each cell a square of pixels, the
/// picture at least 512 pixels on its longer side) or `stem.svg`; returns the path.
///
/// # Errors
/// [`Failure::Input`] naming the file when writing fails.
pub fn write(rgb: &[[u8; 3]], (w, h): (usize, usize), stem: &Path) -> Result<PathBuf, Failure> {
    let ext = if cfg!(feature = "png") { "png" } else { "svg" };
    let path = stem.with_extension(ext);
    let fail = |e: &dyn std::fmt::Display| Failure::Input(format!("{}: {e}", path.display()));
    let file = std::fs::File::create(&path).map_err(|e| fail(&e))?;
    let mut out = std::io::BufWriter::new(file);
    #[cfg(feature = "png")]
    {
        let zoom = (PNG_SIDE / w.max(h)).max(1);
        let mut pixels = Vec::with_capacity(w * h * zoom * zoom * 3);
        for row in rgb.chunks(w) {
            for _ in 0..zoom {
                for c in row {
                    for _ in 0..zoom {
                        pixels.extend_from_slice(c);
                    }
                }
            }
        }
        let mut encoder = png::Encoder::new(&mut out, (w * zoom) as u32, (h * zoom) as u32);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        let mut writer = encoder.write_header().map_err(|e| fail(&e))?;
        writer.write_image_data(&pixels).map_err(|e| fail(&e))?;
        writer.finish().map_err(|e| fail(&e))?;
    }
    #[cfg(not(feature = "png"))]
    write_svg(rgb, (w, h), &mut out).map_err(|e| fail(&e))?;
    out.flush().map_err(|e| fail(&e))?;
    Ok(path)
}

/// The colours as SVG: one rectangle per run of equal colour along a row, 4 units a cell.
#[cfg(not(feature = "png"))]
fn write_svg(rgb: &[[u8; 3]], (w, h): (usize, usize), out: &mut impl Write) -> std::io::Result<()> {
    const PX: usize = 4;
    writeln!(
        out,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{}\" height=\"{}\" \
         shape-rendering=\"crispEdges\">",
        w * PX,
        h * PX
    )?;
    for j in 0..h {
        let row = &rgb[j * w..(j + 1) * w];
        let mut i = 0;
        while i < w {
            let run = row[i..].iter().take_while(|c| **c == row[i]).count();
            let [r, g, b] = row[i];
            writeln!(
                out,
                "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{PX}\" fill=\"#{r:02x}{g:02x}{b:02x}\"/>",
                i * PX,
                j * PX,
                run * PX
            )?;
            i += run;
        }
    }
    writeln!(out, "</svg>")
}
