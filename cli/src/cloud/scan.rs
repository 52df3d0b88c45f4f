//! The built-in synthetic scan of `orthtree cloud`: an airborne lidar pass over a 200 m x 200 m
//! site, a rolling terrain height field with box buildings (roofs and walls), 5 cm of range
//! noise and a sprinkle of stray returns above the ground (birds, dust: what outlier removal is
//! for). Seeded and deterministic, so the tests can make the same cloud.
//!
//! A second epoch of the same site ([`scan`] with `epoch` 1) is sampled afresh, has one
//! building torn down and a new one built: `orthtree cloud diff` shows both in its change map.

use orthtree::cloud::Cloud;

/// The side of the site, in metres.
pub const SITE: f64 = 200.0;

/// The default number of points.
pub const DEFAULT_POINTS: usize = 300_000;

/// SplitMix64: a small, well-mixed seeded generator.
pub struct Rng(u64);

impl Rng {
    /// A generator from `seed`.
    pub fn new(seed: u64) -> Rng {
        Rng(seed)
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in [lo, hi).
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
}

/// A building: its footprint `[x0, y0] .. [x1, y1]` and its height above the ground.
#[derive(Clone, Copy, Debug)]
struct Building {
    lo: [f64; 2],
    hi: [f64; 2],
    height: f64,
}

impl Building {
    fn contains(&self, x: f64, y: f64) -> bool {
        self.lo[0] <= x && x <= self.hi[0] && self.lo[1] <= y && y <= self.hi[1]
    }
}

/// The ground's height at `(x, y)`.
fn ground(x: f64, y: f64) -> f64 {
    6.0 * (x / 31.0).sin() * (y / 27.0).cos() + 1.5 * (x / 7.3 + y / 11.1).sin() + 0.02 * x
}

/// The buildings of epoch `epoch` (0 or 1): twelve of them from the site's own seed; epoch 1
/// loses the first and gains one more.
fn buildings(epoch: u32) -> Vec<Building> {
    let mut rng = Rng::new(0x005e_ed0f_5173);
    let mut out: Vec<Building> = (0..13)
        .map(|_| {
            let (w, d) = (rng.range(10.0, 30.0), rng.range(10.0, 30.0));
            let (x, y) = (rng.range(5.0, SITE - 35.0), rng.range(5.0, SITE - 35.0));
            Building {
                lo: [x, y],
                hi: [x + w, y + d],
                height: rng.range(6.0, 25.0),
            }
        })
        .collect();
    if epoch == 0 {
        out.pop();
    } else {
        out.remove(0);
    }
    out
}

/// One return of the scan: position, intensity, ASPRS class.
pub type Return = ([f64; 3], u16, u8);

/// The returns of [`scan`] one at a time, without holding them (for clouds larger than
/// memory).
pub struct Returns {
    houses: Vec<Building>,
    rng: Rng,
    left: usize,
}

impl Returns {
    /// The `n` returns of epoch `epoch` sampled with `seed`.
    pub fn new(seed: u64, n: usize, epoch: u32) -> Returns {
        Returns {
            houses: buildings(epoch),
            rng: Rng::new(seed ^ (u64::from(epoch) << 32)),
            left: n,
        }
    }
}

impl Iterator for Returns {
    type Item = Return;

    fn next(&mut self) -> Option<Return> {
        if self.left == 0 {
            return None;
        }
        self.left -= 1;
        let rng = &mut self.rng;
        let houses = &self.houses;
        let noise = |rng: &mut Rng| 0.05 * (rng.unit() + rng.unit() + rng.unit() - 1.5);
        let pick = rng.unit();
        let (x, y) = (rng.range(0.0, SITE), rng.range(0.0, SITE));
        Some(if pick < 0.01 {
            let z = ground(x, y) + rng.range(5.0, 40.0);
            ([x, y, z], rng.range(0.0, 200.0) as u16, 7)
        } else if pick < 0.25 && !houses.is_empty() {
            // a wall: a random side of a random building
            let b = houses[(rng.next_u64() % houses.len() as u64) as usize];
            let t = rng.unit();
            let [x, y] = match rng.next_u64() % 4 {
                0 => [b.lo[0] + t * (b.hi[0] - b.lo[0]), b.lo[1]],
                1 => [b.lo[0] + t * (b.hi[0] - b.lo[0]), b.hi[1]],
                2 => [b.lo[0], b.lo[1] + t * (b.hi[1] - b.lo[1])],
                _ => [b.hi[0], b.lo[1] + t * (b.hi[1] - b.lo[1])],
            };
            let z = ground(b.lo[0], b.lo[1]) + rng.unit() * b.height + noise(rng);
            ([x, y, z], rng.range(600.0, 900.0) as u16, 6)
        } else if let Some(b) = houses.iter().find(|b| b.contains(x, y)) {
            let z = ground(b.lo[0], b.lo[1]) + b.height + noise(rng);
            ([x, y, z], rng.range(1500.0, 2000.0) as u16, 6)
        } else {
            let z = ground(x, y) + noise(rng);
            ([x, y, z], rng.range(300.0, 700.0) as u16, 2)
        })
    }
}

/// `n` points of epoch `epoch` of the site, sampled with `seed`: about 75% on the ground and
/// roofs (one return each, seen from above), 24% on walls, 1% stray returns up to 40 m above.
/// The attributes are intensity (roofs bright, ground dimmer) and classification (2 ground,
/// 6 building, 7 noise: the ASPRS codes).
pub fn scan(seed: u64, n: usize, epoch: u32) -> Cloud<f64> {
    let mut points = Vec::with_capacity(n);
    let mut intensity = Vec::with_capacity(n);
    let mut class = Vec::with_capacity(n);
    for (p, i, c) in Returns::new(seed, n, epoch) {
        points.push(p);
        intensity.push(i);
        class.push(c);
    }
    let mut cloud = Cloud::from_points(points);
    cloud.attributes.intensity = Some(intensity);
    cloud.attributes.classification = Some(class);
    cloud
}
