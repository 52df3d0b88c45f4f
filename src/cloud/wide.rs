//! [`Wide`]: non-negative numbers as a mantissa and a power of two kept apart, and the
//! Euclidean [`distance`] of two points without overflow or underflow (the offsets scaled by a
//! power of two before they are squared, as C's `hypot` does), for the statistical outliers'
//! scores of clouds whose distances `f64` cannot square or hold (`outliers.rs`).

/// A non-negative number `m * 2^e` whose power of two is kept apart, so that sums of
/// distances beyond `f64::MAX`, and the smallest distances, keep their value.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Wide {
    pub(super) m: f64,
    pub(super) e: i32,
}

impl Wide {
    pub(super) const ZERO: Wide = Wide { m: 0.0, e: 0 };

    /// The power of two of the value's leading bit (`None` for 0).
    pub(super) fn exponent(self) -> Option<i32> {
        (self.m > 0.0).then(|| self.e + exponent(self.m))
    }

    /// The value as an `f64`, exactly, when it is 0 or normal (`None` otherwise).
    pub(super) fn plain(self) -> Option<f64> {
        match self.exponent() {
            None => Some(0.0),
            Some(x) if (-1022..=1023).contains(&x) => Some(scale_by(self.m, self.e)),
            Some(_) => None,
        }
    }
}

/// The power of two of the leading bit of a positive finite `x` (`floor(log2(x))`).
pub(super) fn exponent(x: f64) -> i32 {
    let bits = x.to_bits();
    let biased = ((bits >> 52) & 0x7ff) as i32;
    if biased == 0 {
        // subnormal: the leading bit of the mantissa field, in units of 2^-1074
        63 - (bits & ((1 << 52) - 1)).leading_zeros() as i32 - 1074
    } else {
        biased - 1023
    }
}

/// `x * 2^n`, rounded once (C's `scalbn`, after musl's): exact unless the result overflows or
/// is subnormal.
pub(super) fn scale_by(mut x: f64, mut n: i32) -> f64 {
    const UP: f64 = f64::from_bits(0x7fe << 52); // 2^1023
    const DOWN: f64 = f64::from_bits(0x036 << 52); // 2^-969: 2^-1022 with 53 bits to spare
    if n > 1023 {
        x *= UP;
        n -= 1023;
        if n > 1023 {
            x *= UP;
            n = (n - 1023).min(1023);
        }
    } else if n < -1022 {
        // in two steps whose first keeps every bit, so that the result rounds once
        x *= DOWN;
        n += 969;
        if n < -1022 {
            x *= DOWN;
            n = (n + 969).max(-1022);
        }
    }
    x * f64::from_bits(((0x3ff + n) as u64) << 52)
}

/// The Euclidean distance of `p` and `q`, without overflow or underflow: the offsets scaled by
/// the power of two of the largest before they are squared (as `hypot` does), and halved first
/// when one of them is beyond `f64::MAX`.
pub(super) fn distance<const D: usize>(p: &[f64; D], q: &[f64; D]) -> Wide {
    let mut offsets: [f64; D] = core::array::from_fn(|a| p[a] - q[a]);
    let halved = offsets.iter().any(|d| d.is_infinite());
    if halved {
        // an offset beyond f64::MAX has a coordinate of at least 2^1022 in magnitude: halving
        // loses at most the last bit of a subnormal coordinate, nothing beside that
        offsets = core::array::from_fn(|a| p[a] * 0.5 - q[a] * 0.5);
    }
    let largest = offsets.iter().fold(0.0f64, |m, d| m.max(d.abs()));
    if largest == 0.0 {
        return Wide::ZERO;
    }
    let e = exponent(largest);
    let sum: f64 = offsets.iter().map(|&d| scale_by(d, -e).powi(2)).sum();
    Wide {
        m: sum.sqrt(),
        e: e + i32::from(halved),
    }
}
