//! Unit tests of the SVG writer's private number formatting and style attributes.
use super::*;

#[test]
fn all_zero_dash_is_solid_and_numbers_are_short() {
    assert!(!Style::solid()
        .dash(&[0.0, 0.0])
        .attributes()
        .contains("dasharray"));
    assert_eq!(num(1.0), "1");
    assert_eq!(num(-0.0001), "0");
    assert_eq!(num(2.5), "2.5");
    assert_eq!(num(f64::INFINITY), "10000000");
}

#[test]
fn numbers_are_clamped_short_decimals() {
    // What `num` promised when it was written with `format!`: the clamped value to three
    // decimals, trailing zeros and point trimmed, no `-0`.
    let by_format = |x: f64| crate::io::text_out::f3_slow(format::clamp_px(x));
    for x in [
        0.0,
        -0.0,
        1.0,
        -0.0001,
        2.5,
        0.0625,
        1e7,
        -1e7,
        1e300,
        f64::NAN,
        f64::INFINITY,
        123.4567,
        -3.1,
    ] {
        assert_eq!(num(x), by_format(x), "{x}");
    }
}
