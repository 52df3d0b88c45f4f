//! [`FloatBits`]: an `f64` held in an error so that the error still equals itself when the
//! value is NaN.

/// An `f64` compared by its bits, so that errors holding NaN still compare equal to themselves.
///
/// ```
/// use orthtree::geom::FloatBits;
/// assert_eq!(FloatBits::from(f64::NAN), FloatBits::from(f64::NAN));
/// assert_eq!(FloatBits::from(-1.5).get(), -1.5);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FloatBits(u64);

impl FloatBits {
    /// The value.
    pub fn get(self) -> f64 {
        f64::from_bits(self.0)
    }
}

impl From<f64> for FloatBits {
    fn from(x: f64) -> Self {
        FloatBits(x.to_bits())
    }
}

impl core::fmt::Display for FloatBits {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        core::fmt::Display::fmt(&self.get(), f)
    }
}
