//! PNG reading and writing (feature `png`): round trips and the 50% luminance threshold on
//! grey, grey-alpha and RGB input.
#![cfg(feature = "png")]

use orthtree::image::ImageTree;
use orthtree::io::png::{self, PngDepth};

fn encode(w: u32, h: u32, colour: ::png::ColorType, data: &[u8]) -> Vec<u8> {
    let mut out = Vec::new();
    let mut e = ::png::Encoder::new(&mut out, w, h);
    e.set_color(colour);
    e.set_depth(::png::BitDepth::Eight);
    let mut wr = e.write_header().unwrap();
    wr.write_image_data(data).unwrap();
    wr.finish().unwrap();
    out
}

#[test]
fn thresholds_at_half_luminance() {
    let grey = encode(4, 1, ::png::ColorType::Grayscale, &[0, 127, 128, 255]);
    assert_eq!(
        png::from_bytes(&grey).unwrap().to_bools(),
        [true, true, false, false]
    );
    // pure green is bright (0.7152), pure blue dark (0.0722); transparent black is white
    let rgb = encode(2, 1, ::png::ColorType::Rgb, &[0, 255, 0, 0, 0, 255]);
    assert_eq!(png::from_bytes(&rgb).unwrap().to_bools(), [false, true]);
    let ga = encode(2, 1, ::png::ColorType::GrayscaleAlpha, &[0, 0, 0, 255]);
    assert_eq!(png::from_bytes(&ga).unwrap().to_bools(), [false, true]);
}

#[test]
fn round_trips_padded_sizes() {
    for (w, h) in [(1, 1), (9, 3), (100, 37)] {
        let t = ImageTree::from_fn([w, h], |[x, y]| (x * 7 + y * 3) % 5 < 2).unwrap();
        for depth in [PngDepth::One, PngDepth::Eight] {
            assert_eq!(
                png::from_bytes(&png::to_bytes(&t, depth).unwrap()).unwrap(),
                t
            );
        }
    }
}
