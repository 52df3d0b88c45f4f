//! Number and text formatting for SVG output: finite pixel values, short decimals, escaped text,
//! and the repair of unusable views.

use crate::geom::Aabb;

/// Pixel coordinates are clamped to this magnitude, so every number written is finite.
pub(super) const MAX_PX: f64 = 1e7;

/// The view with the repairs documented at [`Svg::new`](super::Svg::new).
pub(super) fn repair_view(view: Aabb<f64, 2>) -> Aabb<f64, 2> {
    if !view.min.iter().chain(&view.max).all(|v| v.is_finite()) {
        return super::square(1.0);
    }
    let mut v = view;
    for a in 0..2 {
        if v.min[a] > v.max[a] {
            core::mem::swap(&mut v.min[a], &mut v.max[a]);
        }
    }
    let half = |v: &Aabb<f64, 2>, a: usize| v.max[a] * 0.5 - v.min[a] * 0.5;
    let (h0, h1) = (half(&v, 0), half(&v, 1));
    for (a, mine, other) in [(0, h0, h1), (1, h1, h0)] {
        if mine == 0.0 {
            let h = if other > 0.0 { other } else { 0.5 };
            let c = v.min[a];
            // Centred on c; saturate rather than overflow near the ends of the f64 range.
            v.min[a] = (c - h).max(-f64::MAX);
            v.max[a] = (c + h).min(f64::MAX);
            if half(&v, a) == 0.0 {
                // h vanished next to c's magnitude: widen by an ulp each way.
                v.min[a] = c.next_down().max(-f64::MAX);
                v.max[a] = c.next_up().min(f64::MAX);
            }
        }
    }
    v
}

/// A length: non-negative and finite, else 0.
pub(super) fn length(x: f64) -> f64 {
    if x.is_finite() && x > 0.0 {
        x
    } else {
        0.0
    }
}

/// A pixel coordinate clamped to a finite range (NaN, which only a degenerate view could
/// produce, becomes 0).
#[inline]
pub(super) fn clamp_px(x: f64) -> f64 {
    if x.is_nan() {
        0.0
    } else {
        x.clamp(-MAX_PX, MAX_PX)
    }
}

/// A pixel value clamped by [`clamp_px`], with at most three decimals and no trailing zeros
/// (formatted by hand, as `{:.3}` rounds).
pub(super) fn num(x: f64) -> String {
    crate::io::text_out::f3_string(clamp_px(x))
}

/// Escapes a string for an attribute value in double quotes.
pub(super) fn escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for ch in s.chars() {
        match ch {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            _ => out.push(ch),
        }
    }
    out
}
