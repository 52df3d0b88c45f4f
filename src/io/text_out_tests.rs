//! Tests of [`TextOut`]: every number it formats by hand equals what `format!` writes.

use super::*;
use rand::rngs::SmallRng;
use rand::{Rng, SeedableRng};

/// What `TextOut` writes for `values`, one per line, through `put`.
fn written<T: Copy>(values: &[T], mut put: impl FnMut(&mut TextOut<'_, Vec<u8>>, T)) -> String {
    let mut v = Vec::new();
    let mut out = TextOut::new(&mut v);
    for &x in values {
        put(&mut out, x);
        out.nl().unwrap();
    }
    out.finish().unwrap();
    String::from_utf8(v).unwrap()
}

/// Asserts `f3` equals the reference, [`f3_slow`] (`format!("{x:.3}")` less its trailing zeros
/// and point, `-0` as `0`), on every value, naming the first that differs.
fn assert_f3(values: &[f64]) {
    let text = written(values, |o, x| _ = o.f3(x));
    for (line, &x) in text.lines().zip(values) {
        let expected = f3_slow(x);
        assert_eq!(line, expected, "f3({x:e}), bits {:#x}", x.to_bits());
        assert_eq!(f3_string(x), expected, "f3_string({x:e})");
    }
    assert_eq!(text.lines().count(), values.len());
}

#[test]
fn integers_as_std_formats_them() {
    let mut rng = SmallRng::seed_from_u64(7);
    let mut signed = vec![
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
    for k in 0..19 {
        let p = 10i64.pow(k);
        signed.extend([p - 1, p, p + 1, -p + 1, -p, -p - 1]);
    }
    for bits in 0..64 {
        signed.extend((0..50).map(|_| rng.r#gen::<i64>() >> bits));
    }
    let mut unsigned: Vec<u64> = vec![0, u64::MAX, u64::MAX - 1, 1 << 63];
    unsigned.extend((0..20).map(|k| 10u64.pow(k)));
    unsigned.extend((0..20).map(|k| 10u64.pow(k) - 1));
    for bits in 0..64 {
        unsigned.extend((0..50).map(|_| rng.r#gen::<u64>() >> bits));
    }
    let expected: String = signed.iter().map(|x| format!("{x}\n")).collect();
    assert_eq!(written(&signed, |o, x| _ = o.i(x)), expected);
    let expected: String = unsigned.iter().map(|x| format!("{x}\n")).collect();
    assert_eq!(written(&unsigned, |o, x| _ = o.u(x)), expected);
}

#[test]
fn decimals_as_std_formats_them_at_the_extremes() {
    let mut values = vec![
        0.0,
        -0.0,
        1.0,
        -1.0,
        0.0005,
        -0.0005,
        0.0015,
        0.0025,
        0.9995,
        0.9994999,
        999.9995,
        f64::MIN_POSITIVE,
        -f64::MIN_POSITIVE,
        f64::from_bits(1),
        -f64::from_bits(1),
        f64::MAX,
        -f64::MAX,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NAN,
        1e7,
        -1e7,
        1.8e16,
        1.9e16,
        u64::MAX as f64 / 1000.0,
        (u64::MAX as f64 / 1000.0).next_down(),
        (u64::MAX as f64 / 1000.0).next_up(),
        2f64.powi(53),
        2f64.powi(54) + 2.0,
        1e300,
        1e-300,
    ];
    for k in -80..80 {
        let p = 2f64.powi(k);
        values.extend([p, -p, p.next_up(), p.next_down(), 10f64.powi(k / 4)]);
    }
    assert_f3(&values);
}

#[test]
fn decimals_as_std_formats_them_on_random_values() {
    let mut rng = SmallRng::seed_from_u64(11);
    let mut values = Vec::new();
    // Any bit pattern: every magnitude, subnormals, infinities and NaNs.
    values.extend((0..20_000).map(|_| f64::from_bits(rng.r#gen())));
    // Pixel-sized values, where the picture's coordinates lie.
    values.extend((0..20_000).map(|_| rng.gen_range(-1e7..1e7)));
    values.extend((0..20_000).map(|_| rng.gen_range(-2.0..2.0)));
    // Dyadic values k / 2^j, as a board's grid maps to pixels: many exact ties at 1/2000.
    values.extend((0..20_000).map(|_| {
        let k = rng.gen_range(-(1i64 << 40)..1i64 << 40) as f64;
        k / 2f64.powi(rng.gen_range(0..60))
    }));
    // Near the ties: thousandths and a half, give or take an ulp.
    values.extend((0..20_000).map(|_| {
        let t = (rng.gen_range(-1_000_000_000i64..1_000_000_000) as f64 + 0.5) / 1000.0;
        match rng.gen_range(0..3) {
            0 => t.next_down(),
            1 => t,
            _ => t.next_up(),
        }
    }));
    assert_f3(&values);
}

#[test]
fn long_output_arrives_whole() {
    let values: Vec<u64> = (0..100_000).collect();
    let expected: String = values.iter().map(|k| format!("{k}\n")).collect();
    assert_eq!(written(&values, |o, k| _ = o.u(k)), expected);
}

#[test]
fn a_line_longer_than_the_buffer_arrives_whole() {
    let long = "x".repeat(5 * BLOCK);
    let text = written(&[0u64, 1, 2], |o, k| {
        _ = o.s(&long).u(k).sp().f3(k as f64 / 8.0)
    });
    let expected: String = (0..3)
        .map(|k| format!("{long}{k} {}\n", f3_slow(k as f64 / 8.0)))
        .collect();
    assert_eq!(text, expected);
}

#[test]
fn counters_count_as_std_formats() {
    let starts = [
        0,
        1,
        8,
        9,
        98,
        99,
        999_999,
        99_999_999,
        123_456_789_999,
        u64::MAX - 2,
    ];
    for first in starts {
        let mut counter = Counter::new(first);
        let text = written(&[(); 1500], |o, ()| _ = o.count(&mut counter).sp());
        let expected: String = (0..1500u128)
            .map(|k| format!("{} \n", u128::from(first) + k))
            .collect();
        assert_eq!(text, expected, "from {first}");
    }
    // At twenty nines it stays.
    let mut nines = Counter::new(0);
    nines.digits = [b'9'; INTEGER_BYTES];
    nines.len = INTEGER_BYTES;
    nines.bump();
    assert_eq!(
        (nines.digits, nines.len),
        ([b'9'; INTEGER_BYTES], INTEGER_BYTES)
    );
}
