//! [`TextOut`]: the buffered text output of the mesh writers: integers formatted by hand into
//! one reused byte buffer, handed to the writer in blocks of about 64 KiB, so that writing a
//! line allocates nothing and costs a few nanoseconds per number.

use std::io::{self, Write};

/// The buffer is handed to the writer once it holds this many bytes.
const BLOCK: usize = 1 << 16;

/// "00" to "99", two bytes each.
const PAIRS: &[u8; 200] = b"0001020304050607080910111213141516171819\
                            2021222324252627282930313233343536373839\
                            4041424344454647484950515253545556575859\
                            6061626364656667686970717273747576777879\
                            8081828384858687888990919293949596979899";

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
    #[inline]
    fn room(&mut self, more: usize) {
        if self.pos + more > self.buf.len() {
            let len = (self.pos + more).max(2 * self.buf.len());
            self.buf.resize(len, 0);
        }
    }

    /// Appends an unsigned integer in decimal.
    #[inline]
    pub fn u(&mut self, v: u64) -> &mut Self {
        let n = v.checked_ilog10().unwrap_or(0) as usize + 1;
        self.room(n);
        let digits = &mut self.buf[self.pos..self.pos + n];
        let mut i = n;
        let mut v = v;
        // Two digits per division.
        while v >= 100 {
            let pair = (v % 100) as usize * 2;
            v /= 100;
            i -= 2;
            digits[i..i + 2].copy_from_slice(&PAIRS[pair..pair + 2]);
        }
        if v >= 10 {
            let pair = v as usize * 2;
            digits[..2].copy_from_slice(&PAIRS[pair..pair + 2]);
        } else {
            digits[0] = b'0' + v as u8;
        }
        self.pos += n;
        self
    }

    /// Appends a signed integer in decimal.
    #[inline]
    pub fn i(&mut self, v: i64) -> &mut Self {
        if v < 0 {
            self.byte(b'-');
        }
        self.u(v.unsigned_abs())
    }

    /// Appends one byte.
    #[inline]
    fn byte(&mut self, b: u8) {
        self.room(1);
        self.buf[self.pos] = b;
        self.pos += 1;
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

    /// Appends a space.
    #[inline]
    pub fn sp(&mut self) -> &mut Self {
        self.byte(b' ');
        self
    }

    /// Ends a line, handing a full block to the writer.
    #[inline]
    pub fn nl(&mut self) -> io::Result<()> {
        self.byte(b'\n');
        self.spill()
    }

    /// Hands a full block to the writer (call between items of a long line).
    #[inline]
    pub fn spill(&mut self) -> io::Result<()> {
        if self.pos >= BLOCK {
            self.out.write_all(&self.buf[..self.pos])?;
            self.pos = 0;
        }
        Ok(())
    }

    /// Hands the rest to the writer and flushes it.
    pub fn finish(mut self) -> io::Result<()> {
        self.out.write_all(&self.buf[..self.pos])?;
        self.pos = 0;
        self.out.flush()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integers_as_std_formats_them() {
        let mut v = Vec::new();
        let mut out = TextOut::new(&mut v);
        let values = [
            0,
            1,
            -1,
            9,
            10,
            99,
            100,
            12345,
            i64::MAX,
            i64::MIN,
            -1073741824,
        ];
        for x in values {
            out.i(x).sp();
        }
        out.u(u64::MAX).nl().unwrap();
        out.finish().unwrap();
        let mut expected: String = values.iter().map(|x| format!("{x} ")).collect();
        expected.push_str(&format!("{}\n", u64::MAX));
        assert_eq!(String::from_utf8(v).unwrap(), expected);
    }

    #[test]
    fn long_output_arrives_whole() {
        let mut v = Vec::new();
        let mut out = TextOut::new(&mut v);
        for k in 0..100_000u64 {
            out.u(k).nl().unwrap();
        }
        out.finish().unwrap();
        let expected: String = (0..100_000).map(|k| format!("{k}\n")).collect();
        assert_eq!(v, expected.into_bytes());
    }
}
