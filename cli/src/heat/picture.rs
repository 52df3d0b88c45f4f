//! The heat map of `orthtree heat`: an SVG of the mesh coloured by temperature with the
//! component outlines and a colour bar, and the mesh as legacy VTK with the temperature as point
//! data; both streamed.

use orthtree::io::vtk;
use orthtree::mesh::{Board, Mesh};
use std::io::{BufWriter, Write};

/// An inferno-like colour map: `s` in [0, 1] to RGB.
fn colour(s: f64) -> [u8; 3] {
    const STOPS: [[f64; 3]; 6] = [
        [0.0, 0.0, 4.0],
        [66.0, 10.0, 104.0],
        [147.0, 38.0, 103.0],
        [221.0, 81.0, 58.0],
        [252.0, 165.0, 10.0],
        [252.0, 255.0, 164.0],
    ];
    let s = s.clamp(0.0, 1.0) * (STOPS.len() - 1) as f64;
    let i = (s.floor() as usize).min(STOPS.len() - 2);
    let f = s - i as f64;
    let mut c = [0u8; 3];
    for (ch, out) in c.iter_mut().enumerate() {
        *out = (STOPS[i][ch] * (1.0 - f) + STOPS[i + 1][ch] * f).round() as u8;
    }
    c
}

/// The heat map, streamed to `out`: each triangle filled with the colour of its mean vertex
/// temperature (256 levels, one path per level, triangles sorted into levels by counting), the
/// component outlines on top, a colour bar on the right.
pub fn write_heat_svg(
    mesh: &Mesh,
    board: &Board,
    t: &[f64],
    t_max: f64,
    out: &mut impl Write,
) -> std::io::Result<()> {
    const LEVELS: usize = 256;
    let u = board.size() as f64;
    let level_of = |tri: &[u32; 3]| {
        let mean = tri.iter().map(|&v| t[v as usize]).sum::<f64>() / 3.0;
        let level = ((mean / t_max.max(f64::MIN_POSITIVE)) * (LEVELS - 1) as f64).round();
        (level.max(0.0) as usize).min(LEVELS - 1)
    };
    // Counting sort of the triangles by level: `order[start[l]..start[l + 1]]` is level l.
    let levels: Vec<u8> = mesh
        .triangles
        .iter()
        .map(|tri| level_of(tri) as u8)
        .collect();
    let mut start = [0usize; LEVELS + 1];
    for &l in &levels {
        start[l as usize + 1] += 1;
    }
    for l in 0..LEVELS {
        start[l + 1] += start[l];
    }
    let mut next = start;
    let mut order = vec![0u32; levels.len()];
    for (k, &l) in levels.iter().enumerate() {
        order[next[l as usize]] = k as u32;
        next[l as usize] += 1;
    }
    drop(levels);

    let bar = u / 16.0;
    let (w, h) = (u + 3.0 * bar, u);
    writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" viewBox="{} {} {} {}" width="{}" height="{}">"#,
        -bar / 2.0,
        -bar / 2.0,
        w + bar / 2.0,
        h + bar,
        (w + bar) * 900.0 / (u + bar),
        900.0 * (h + bar) / (u + bar)
    )?;
    writeln!(
        out,
        r#"<rect x="{}" y="{}" width="100%" height="100%" fill="white"/>"#,
        -bar / 2.0,
        -bar / 2.0
    )?;
    writeln!(out, r#"<g transform="translate(0 {u}) scale(1 -1)">"#)?;
    let stroke = u / 4096.0;
    for level in 0..LEVELS {
        let members = &order[start[level]..start[level + 1]];
        if members.is_empty() {
            continue;
        }
        let [r, g, b] = colour(level as f64 / (LEVELS - 1) as f64);
        write!(
            out,
            r##"<path fill="#{r:02x}{g:02x}{b:02x}" stroke="#{r:02x}{g:02x}{b:02x}" stroke-width="{stroke}" d=""##
        )?;
        for &k in members {
            let [a, b, c] = mesh.triangles[k as usize].map(|v| mesh.vertices[v as usize]);
            write!(
                out,
                "M{} {}L{} {}L{} {}Z",
                a[0], a[1], b[0], b[1], c[0], c[1]
            )?;
        }
        writeln!(out, "\"/>")?;
    }
    write!(
        out,
        r##"<path fill="none" stroke="#7fdfff" stroke-width="{}" stroke-linejoin="round" d=""##,
        u / 1024.0
    )?;
    for c in board.components() {
        for (i, p) in c.outline.iter().enumerate() {
            write!(out, "{}{} {}", if i == 0 { "M" } else { "L" }, p[0], p[1])?;
        }
        write!(out, "Z")?;
    }
    writeln!(out, "\"/>")?;
    writeln!(
        out,
        r##"<rect x="0" y="0" width="{u}" height="{u}" fill="none" stroke="black" stroke-width="{}"/>"##,
        u / 512.0
    )?;
    writeln!(out, "</g>")?;
    // colour bar
    let x0 = u + bar;
    let steps = 64;
    for i in 0..steps {
        let [r, g, b] = colour((i as f64 + 0.5) / steps as f64);
        let y = u - (i + 1) as f64 * u / steps as f64;
        writeln!(
            out,
            r##"<rect x="{x0}" y="{y}" width="{}" height="{}" fill="#{r:02x}{g:02x}{b:02x}"/>"##,
            bar / 2.0,
            u / steps as f64 + 0.5
        )?;
    }
    let font = u / 40.0;
    for (y, label) in [(u, "0 K".to_string()), (font, format!("{t_max:.3} K"))] {
        writeln!(
            out,
            r#"<text x="{}" y="{y}" font-family="sans-serif" font-size="{font}" transform="rotate(-90 {} {y})" text-anchor="{}">{label}</text>"#,
            x0 + bar * 1.2,
            x0 + bar * 1.2,
            if y == u { "start" } else { "end" }
        )?;
    }
    writeln!(out, "</svg>")?;
    out.flush()
}

/// The mesh as legacy VTK with the temperature as `POINT_DATA` (and the region as `CELL_DATA`),
/// streamed to a file.
pub fn write_heat_vtk(mesh: &Mesh, t: &[f64], path: &str) -> std::io::Result<()> {
    let mut out = BufWriter::new(std::fs::File::create(path)?);
    vtk::write_vtk(mesh, &mut out)?;
    writeln!(out, "POINT_DATA {}", mesh.vertices.len())?;
    writeln!(out, "SCALARS temperature double 1\nLOOKUP_TABLE default")?;
    for v in t {
        writeln!(out, "{v:e}")?;
    }
    out.flush()
}
