//! The geometric checks of [`Mesh::validate`](super::Mesh::validate), in exact integer
//! arithmetic: every angle in [45, 90] degrees (compared as dot and cross products, no
//! trigonometry), and the Delaunay property of exercise 14.3 (no vertex strictly inside the
//! circumcircle of the triangle across each interior edge: the in-circle determinant).

use super::checks::Validator;
use super::*;

impl Validator<'_> {
    /// `angles`, and the smallest and largest angle in degrees.
    pub(super) fn angles(&self) -> (Check, Option<[f64; 2]>) {
        let mut f = Finding::default();
        // The smallest and largest angle as (dot, |cross|): vectors in the closed upper half
        // plane, compared exactly by their cross product; converted to degrees at the end.
        let mut range: Option<[(i128, i128); 2]> = None;
        let less = |(d1, c1): (i128, i128), (d2, c2): (i128, i128)| d1 * c2 - c1 * d2 > 0;
        for (t, tri) in self.good_triangles() {
            let p = self.tri_points(t);
            for i in 0..3 {
                let (a, b, c) = (p[i], p[(i + 1) % 3], p[(i + 2) % 3]);
                let u = [b[0] as i128 - a[0] as i128, b[1] as i128 - a[1] as i128];
                let v = [c[0] as i128 - a[0] as i128, c[1] as i128 - a[1] as i128];
                let dot = u[0] * v[0] + u[1] * v[1];
                let cr = (u[0] * v[1] - u[1] * v[0]).abs();
                let angle = (dot, cr);
                range = Some(match range {
                    None => [angle, angle],
                    Some([lo, hi]) => [
                        if less(angle, lo) { angle } else { lo },
                        if less(hi, angle) { angle } else { hi },
                    ],
                });
                if dot < 0 || dot > cr {
                    f.fail(|| MeshValidationError::Angle {
                        triangle: t,
                        vertices: tri,
                        vertex: tri[i],
                        point: a,
                        dot,
                        cross: cr,
                    });
                }
            }
        }
        let range = range.map(|r| r.map(degrees));
        let check = f.finish(|| match range {
            Some([lo, hi]) => format!("angles from {lo:.1} to {hi:.1} degrees"),
            None => "no triangles".into(),
        });
        (check, range)
    }

    /// `delaunay`, over the interior edges between triangles of positive doubled area `area2`.
    pub(super) fn delaunay(&self, area2: &[i128]) -> Check {
        let mut f = Finding::default();
        let mut pairs = 0usize;
        for (h, a, b) in self.half_edges() {
            let Some(g) = self.twin(h) else { continue };
            let (s, t) = (h as usize / 3, g as usize / 3);
            if h > g || area2[s] <= 0 || area2[t] <= 0 {
                continue;
            }
            pairs += 1;
            let [p0, p1, p2] = self.tri_points(s);
            let d_index = self.mesh.triangles[t][(g as usize % 3 + 2) % 3];
            let d = self.point(d_index);
            if incircle(p0, p1, p2, d) > 0 {
                let c = self.mesh.triangles[s][(h as usize % 3 + 2) % 3];
                f.fail(|| MeshValidationError::NotDelaunay {
                    edge: [a, b],
                    vertex: d_index,
                    point: d,
                    triangle: t,
                    circumcircle_of: s,
                    opposite: c,
                });
            }
        }
        f.finish(|| format!("{pairs} interior edges locally Delaunay"))
    }
}
