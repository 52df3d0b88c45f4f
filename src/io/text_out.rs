//! [`TextOut`]: the buffered text output of the mesh and picture writers. Integers and short
//! decimals are formatted by hand into one reused byte buffer (no `format!` machinery, nothing
//! allocated per line), and the buffer is handed to the writer in blocks of about 64 KiB.
//!
//! Integers come out as `{}` formats them; decimals as `{:.3}` does, without trailing zeros
//! (see [`TextOut::f3`]). Both are checked against `format!` by the tests below.

use std::io::{self, Write};

/// The buffer is handed to the writer once it holds this many bytes.
const BLOCK: usize = 1 << 16;

/// The most bytes one integer takes: `i64::MIN` and `u64::MAX` have 20.
const INTEGER_BYTES: usize = 20;

/// `'0'` in every byte of a `u64`.
const ZEROS: u64 = 0x3030_3030_3030_3030;

/// The eight decimal digits of `v` (below 10^8, leading zeros included), one per byte, the most
/// significant in the lowest byte (so that [`u64::to_le_bytes`] gives them in writing order).
///
/// All eight digits come out of a few multiplications on lanes of one `u64` (SIMD within a
/// register): `v` is split into two halves of four digits (32-bit lanes), each half into two
/// pairs (16-bit lanes), each pair into two digits (8-bit lanes). The divisions by 100 and 10
/// are multiplications by reciprocals, exact for the ranges they get: `n * 10486 >> 20 = n / 100`
/// for `n < 10^4` and `n * 103 >> 10 = n / 10` for `n < 100`, and no lane's product overflows
/// into the next.
#[inline(always)]
fn digits8(v: u32) -> u64 {
    debug_assert!(v < 100_000_000);
    let x = u64::from(v / 10_000) | u64::from(v % 10_000) << 32;
    let hundreds = ((x * 10_486) >> 20) & 0x0000_007f_0000_007f;
    let x = hundreds | (x - hundreds * 100) << 16;
    let tens = ((x * 103) >> 10) & 0x000f_000f_000f_000f;
    tens | (x - tens * 10) << 8
}

/// Writes `v` (below 10^8) without leading zeros at the start of `dst` (at least 8 long: all 8
/// bytes are written, the ones past the digits being junk); returns the digit count.
#[inline(always)]
fn put_below_1e8(dst: &mut [u8], v: u32) -> usize {
    let d = digits8(v);
    // Leading zero digits are the low zero bytes; 0 keeps one digit.
    let zeros = ((d | 1 << 56).trailing_zeros() / 8) as usize;
    let ascii = (d >> (8 * zeros)) + ZEROS;
    dst[..8].copy_from_slice(&ascii.to_le_bytes());
    8 - zeros
}

/// Writes the eight digits of `v` (below 10^8), leading zeros included, at the start of `dst`.
#[inline(always)]
fn put_8_digits(dst: &mut [u8], v: u32) {
    dst[..8].copy_from_slice(&(digits8(v) + ZEROS).to_le_bytes());
}

/// Writes `v` in decimal at the start of `dst` (at least [`INTEGER_BYTES`] long; bytes past the
/// digits may be overwritten); returns the number of bytes written: eight digits at a time with
/// [`digits8`].
#[inline(always)]
fn put_u64(dst: &mut [u8], v: u64) -> usize {
    const E8: u64 = 100_000_000;
    if v < E8 {
        return put_below_1e8(dst, v as u32);
    }
    if v < E8 * E8 {
        let n = put_below_1e8(dst, (v / E8) as u32);
        put_8_digits(&mut dst[n..], (v % E8) as u32);
        return n + 8;
    }
    // Below 1845 * 10^16: four digits at most in front.
    let n = put_below_1e8(dst, (v / (E8 * E8)) as u32);
    put_8_digits(&mut dst[n..], (v / E8 % E8) as u32);
    put_8_digits(&mut dst[n + 8..], (v % E8) as u32);
    n + 16
}

/// `|x|` rounded to the nearest multiple of 1/1000, in thousandths, exactly as `{:.3}` rounds
/// the exact binary value (ties to even); `None` if `x` is not finite or the result does not
/// fit in a `u64`.
fn thousandths(x: f64) -> Option<u64> {
    if !x.is_finite() {
        return None;
    }
    let bits = x.abs().to_bits();
    let biased = (bits >> 52) as i32;
    let fraction = bits & ((1 << 52) - 1);
    // |x| = m * 2^e exactly.
    let (m, e) = match biased {
        0 => (fraction, -1074),
        _ => (fraction | 1 << 52, biased - 1075),
    };
    let scaled = u128::from(m) * 1000; // below 2^63
    if e >= 0 {
        // An integer: exact if it fits.
        let shifted = scaled.checked_shl(e as u32).filter(|s| s >> e == scaled)?;
        return u64::try_from(shifted).ok();
    }
    let shift = e.unsigned_abs();
    if shift >= 127 {
        // Below 2^-64 thousandths: rounds to 0 (no tie, the half is far larger).
        return Some(0);
    }
    let quotient = scaled >> shift;
    let rest = scaled - (quotient << shift);
    let half = 1u128 << (shift - 1);
    let up = rest > half || (rest == half && quotient & 1 == 1);
    u64::try_from(quotient + u128::from(up)).ok()
}

/// The most bytes [`put_f3`] writes: a sign, 17 digits, a point and 3 decimals.
const F3_BYTES: usize = 24;

/// Writes `x` as [`f3_string`] does at the start of `dst` (at least [`F3_BYTES`] long);
/// returns the number of bytes written, or `None` (nothing written) for the values left to
/// `format!`.
#[inline]
fn put_f3(dst: &mut [u8], x: f64) -> Option<usize> {
    let q = thousandths(x)?;
    let dst = &mut dst[..F3_BYTES];
    let mut pos = 0;
    if q != 0 && x.is_sign_negative() {
        dst[0] = b'-';
        pos = 1;
    }
    pos += put_u64(&mut dst[pos..], q / 1000);
    let mut fraction = (q % 1000) as u32;
    if fraction != 0 {
        let mut digits = 3;
        while fraction.is_multiple_of(10) {
            fraction /= 10;
            digits -= 1;
        }
        dst[pos] = b'.';
        for k in (1..=digits).rev() {
            dst[pos + k] = b'0' + (fraction % 10) as u8;
            fraction /= 10;
        }
        pos += digits + 1;
    }
    Some(pos)
}

/// `x` rounded to three decimals as `format!("{x:.3}")` writes it, less its trailing zeros and
/// a trailing point, and `0` for any value that rounds to zero (no `-0`): `0.1`, `-2.5`,
/// `12`, `0.062` for 0.0625 (ties to even, on the exact binary value). Finite values below
/// 1.8e16 in magnitude are formatted by hand; infinities, NaN and larger values by `format!`.
pub(crate) fn f3_string(x: f64) -> String {
    let mut buf = [0u8; F3_BYTES];
    match put_f3(&mut buf, x) {
        // The bytes are ASCII digits, a sign and a point.
        Some(n) => buf[..n].iter().map(|&b| char::from(b)).collect(),
        None => f3_slow(x),
    }
}

/// [`f3_string`] through `format!`, for the values [`put_f3`] does not take.
#[cold]
pub(crate) fn f3_slow(x: f64) -> String {
    let s = format!("{x:.3}");
    let trimmed = if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.')
    } else {
        &s
    };
    if trimmed == "-0" { "0" } else { trimmed }.to_string()
}

/// Consecutive integers, as line numbers are: the digits of the current value kept as text, so
/// that the next one costs an increment of the last digit (a carry now and then) instead of a
/// conversion. Written with [`TextOut::count`].
pub(crate) struct Counter {
    /// The digits, `digits[..len]`; the bytes past them are `'0'`.
    digits: [u8; INTEGER_BYTES],
    len: usize,
}

impl Counter {
    /// A counter whose first value is `first`.
    pub fn new(first: u64) -> Self {
        let mut digits = [b'0'; INTEGER_BYTES];
        let mut scratch = [0u8; INTEGER_BYTES];
        let len = put_u64(&mut scratch, first);
        digits[..len].copy_from_slice(&scratch[..len]);
        Counter { digits, len }
    }

    /// Moves on to the next value: past `u64::MAX` too, in text, up to twenty nines, where it
    /// stays (no line count gets near).
    #[inline(always)]
    fn bump(&mut self) {
        for i in (0..self.len).rev() {
            if self.digits[i] < b'9' {
                self.digits[i] += 1;
                return;
            }
            self.digits[i] = b'0';
        }
        // All nines: one digit more, a 1 and zeros.
        if self.len < INTEGER_BYTES {
            self.digits[0] = b'1';
            self.len += 1;
        } else {
            self.digits = [b'9'; INTEGER_BYTES];
        }
    }
}

/// A byte buffer in front of a writer (see the module doc). Call [`TextOut::finish`] at the end:
/// bytes still buffered when it is dropped are lost.
pub(crate) struct TextOut<'a, W: Write + ?Sized> {
    out: &'a mut W,
    /// Always initialised to its full length; `buf[..pos]` is the text not yet handed over.
    buf: Vec<u8>,
    pos: usize,
}

impl<'a, W: Write + ?Sized> TextOut<'a, W> {
    /// A buffer in front of `out`.
    pub fn new(out: &'a mut W) -> Self {
        TextOut {
            out,
            buf: vec![0; 2 * BLOCK],
            pos: 0,
        }
    }

    /// Makes room for `more` bytes after `pos`.
    #[inline(always)]
    fn room(&mut self, more: usize) {
        if self.buf.len() - self.pos < more {
            self.grow(more);
        }
    }

    /// The rare path of [`TextOut::room`]: a line longer than the buffer.
    #[cold]
    #[inline(never)]
    fn grow(&mut self, more: usize) {
        let len = (self.pos + more).max(2 * self.buf.len());
        self.buf.resize(len, 0);
    }

    /// Appends an unsigned integer in decimal.
    #[inline(always)]
    pub fn u(&mut self, v: u64) -> &mut Self {
        self.room(INTEGER_BYTES);
        self.pos += put_u64(&mut self.buf[self.pos..], v);
        self
    }

    /// Appends the counter's value in decimal, then moves it on to the next.
    #[inline(always)]
    pub fn count(&mut self, counter: &mut Counter) -> &mut Self {
        self.room(INTEGER_BYTES);
        self.buf[self.pos..self.pos + INTEGER_BYTES].copy_from_slice(&counter.digits);
        self.pos += counter.len;
        counter.bump();
        self
    }

    /// Appends a signed integer in decimal.
    #[inline(always)]
    pub fn i(&mut self, v: i64) -> &mut Self {
        self.room(INTEGER_BYTES + 1);
        if v < 0 {
            self.buf[self.pos] = b'-';
            self.pos += 1;
        }
        self.pos += put_u64(&mut self.buf[self.pos..], v.unsigned_abs());
        self
    }

    /// Appends `x` as [`f3_string`] writes it.
    #[inline]
    pub fn f3(&mut self, x: f64) -> &mut Self {
        self.room(F3_BYTES);
        match put_f3(&mut self.buf[self.pos..], x) {
            Some(n) => self.pos += n,
            None => {
                self.s(&f3_slow(x));
            }
        }
        self
    }

    /// Appends text.
    #[inline]
    pub fn s(&mut self, text: &str) -> &mut Self {
        let bytes = text.as_bytes();
        self.room(bytes.len());
        self.buf[self.pos..self.pos + bytes.len()].copy_from_slice(bytes);
        self.pos += bytes.len();
        self
    }

    /// Appends each of `values` after a space.
    #[inline(always)]
    pub fn spaced(&mut self, values: &[u64]) -> &mut Self {
        for &v in values {
            self.sp().u(v);
        }
        self
    }

    /// Appends a space.
    #[inline(always)]
    pub fn sp(&mut self) -> &mut Self {
        self.room(1);
        self.buf[self.pos] = b' ';
        self.pos += 1;
        self
    }

    /// Ends a line, handing a full block to the writer.
    #[inline(always)]
    pub fn nl(&mut self) -> io::Result<()> {
        self.room(1);
        self.buf[self.pos] = b'\n';
        self.pos += 1;
        self.spill()
    }

    /// Hands a full block to the writer (call between items of a long line).
    #[inline(always)]
    pub fn spill(&mut self) -> io::Result<()> {
        if self.pos >= BLOCK {
            self.hand_over()?;
        }
        Ok(())
    }

    /// Hands the buffered text to the writer.
    #[inline(never)]
    fn hand_over(&mut self) -> io::Result<()> {
        self.out.write_all(&self.buf[..self.pos])?;
        self.pos = 0;
        Ok(())
    }

    /// Hands the rest to the writer and flushes it.
    pub fn finish(mut self) -> io::Result<()> {
        self.hand_over()?;
        self.out.flush()
    }
}

#[cfg(test)]
#[path = "text_out_tests.rs"]
mod tests;
