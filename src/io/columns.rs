//! The columns of a point file (PLY properties, the fields of an XYZ/CSV line) mapped to a
//! [`Cloud`]'s positions and attribute columns, each value converted exactly or refused: the
//! one mapping every text and PLY reader shares.

use super::ply::Kind;
use crate::cloud::{Attributes, Cloud, Column};
use crate::geom::Scalar;

/// Where a column's value goes.
#[derive(Clone, Copy, Debug)]
enum Target {
    Position(usize),
    Intensity,
    Classification,
    Color(usize),
    GpsTime,
    Normal(usize),
    Extra(usize),
}

/// The map from a file's column names to a cloud's columns: `x y z`, `intensity`,
/// `classification`, `red green blue` (all three), `gps_time`, `nx ny nz` (all three), and
/// every other name an extra column.
#[derive(Clone, Debug)]
pub(crate) struct Columns {
    targets: Vec<Target>,
    extra: Vec<String>,
    names: Vec<String>,
}

impl Columns {
    /// The map for these names (in file order).
    pub(crate) fn new(names: &[&str]) -> Columns {
        let has = |n: &str| names.contains(&n);
        let rgb = has("red") && has("green") && has("blue");
        let normal = has("nx") && has("ny") && has("nz");
        let mut extra = Vec::new();
        let targets = names
            .iter()
            .map(|name| match *name {
                "x" => Target::Position(0),
                "y" => Target::Position(1),
                "z" => Target::Position(2),
                "intensity" => Target::Intensity,
                "classification" => Target::Classification,
                "red" if rgb => Target::Color(0),
                "green" if rgb => Target::Color(1),
                "blue" if rgb => Target::Color(2),
                "gps_time" => Target::GpsTime,
                "nx" if normal => Target::Normal(0),
                "ny" if normal => Target::Normal(1),
                "nz" if normal => Target::Normal(2),
                other => {
                    extra.push(other.to_string());
                    Target::Extra(extra.len() - 1)
                }
            })
            .collect();
        let names = names.iter().map(|n| n.chars().take(32).collect()).collect();
        Columns {
            targets,
            extra,
            names,
        }
    }

    /// The name of column `i` (cut after 32 characters).
    pub(crate) fn name(&self, i: usize) -> String {
        self.names[i].clone()
    }

    /// What column `i` holds, for the error naming a value [`push`](Self::push) refused there
    /// (coordinates of scalar type `S`).
    pub(crate) fn holds<S: Scalar>(&self, i: usize) -> String {
        match self.targets[i] {
            Target::Position(_) => format!(
                "a finite value that {} holds exactly",
                core::any::type_name::<S>()
            ),
            Target::Intensity | Target::Color(_) => "an integer from 0 to 65535".into(),
            Target::Classification => "an integer from 0 to 255".into(),
            Target::Normal(_) => "a value that f32 holds exactly".into(),
            Target::GpsTime | Target::Extra(_) => "a number".into(),
        }
    }

    /// Empty attribute columns of the kinds the names fill.
    pub(crate) fn attributes(&self) -> Attributes {
        let mut a = Attributes::default();
        for t in &self.targets {
            match t {
                Target::Intensity => a.intensity = Some(Vec::new()),
                Target::Classification => a.classification = Some(Vec::new()),
                Target::Color(_) => a.color = Some(Vec::new()),
                Target::GpsTime => a.gps_time = Some(Vec::new()),
                Target::Normal(_) => a.normal = Some(Vec::new()),
                _ => {}
            }
        }
        a.extra = self
            .extra
            .iter()
            .map(|name| Column {
                name: name.clone(),
                values: Vec::new(),
            })
            .collect();
        a
    }

    /// Appends the point whose column values are `values` to `cloud` (whose attributes came
    /// from [`Columns::attributes`]). `Err(i)` when value `i` does not fit its target exactly:
    /// a coordinate that is not finite or not a value of `S`, an intensity or colour outside
    /// 0..=65535 or not an integer, a class outside 0..=255, a normal component that is not an
    /// `f32`. Nothing is appended then.
    pub(crate) fn push<S: Scalar>(
        &self,
        values: &[f64],
        cloud: &mut Cloud<S>,
    ) -> Result<(), usize> {
        let integer = |i: usize, max: f64| {
            let v = values[i];
            ((0.0..=max).contains(&v) && v.fract() == 0.0)
                .then_some(v)
                .ok_or(i)
        };
        let mut position = [S::zero(); 3];
        let mut color = [0u16; 3];
        let mut normal = [0f32; 3];
        let (mut intensity, mut class, mut gps) = (0u16, 0u8, 0f64);
        for (i, t) in self.targets.iter().enumerate() {
            let v = values[i];
            match *t {
                Target::Position(axis) => {
                    let s: Option<S> = num_traits::NumCast::from(v);
                    match s {
                        Some(s) if v.is_finite() && s.to_f64() == v => position[axis] = s,
                        _ => return Err(i),
                    }
                }
                Target::Intensity => intensity = integer(i, 65535.0)? as u16,
                Target::Classification => class = integer(i, 255.0)? as u8,
                Target::Color(c) => color[c] = integer(i, 65535.0)? as u16,
                Target::GpsTime => gps = v,
                Target::Normal(c) => {
                    if !v.is_nan() && f64::from(v as f32) != v {
                        return Err(i);
                    }
                    normal[c] = v as f32;
                }
                Target::Extra(_) => {}
            }
        }
        let a = &mut cloud.attributes;
        push_to(&mut a.intensity, intensity);
        push_to(&mut a.classification, class);
        push_to(&mut a.color, color);
        push_to(&mut a.gps_time, gps);
        push_to(&mut a.normal, normal);
        for (i, t) in self.targets.iter().enumerate() {
            if let Target::Extra(c) = *t {
                a.extra[c].values.push(values[i]);
            }
        }
        cloud.points.push(position);
        Ok(())
    }
}

fn push_to<V>(column: &mut Option<Vec<V>>, v: V) {
    if let Some(c) = column {
        c.push(v);
    }
}

/// The column names the writers use for `a`'s present columns, after `x y z`, with the PLY type
/// of the values each holds (the attributes' own type).
pub(crate) fn attribute_names(a: &Attributes) -> Vec<(String, Kind)> {
    let fixed: [(bool, &[&str], Kind); 5] = [
        (a.intensity.is_some(), &["intensity"], Kind::U16),
        (a.classification.is_some(), &["classification"], Kind::U8),
        (a.color.is_some(), &["red", "green", "blue"], Kind::U16),
        (a.gps_time.is_some(), &["gps_time"], Kind::F64),
        (a.normal.is_some(), &["nx", "ny", "nz"], Kind::F32),
    ];
    let present = fixed.into_iter().filter(|f| f.0);
    let named =
        present.flat_map(|(_, names, kind)| names.iter().map(move |n| (n.to_string(), kind)));
    let extra = a.extra.iter().map(|c| (c.name.clone(), Kind::F64));
    named.chain(extra).collect()
}

/// Point `i`'s values in the order of [`attribute_names`], after its coordinates, into `out`
/// (cleared first).
pub(crate) fn row<S: Scalar>(cloud: &Cloud<S>, i: usize, out: &mut Vec<f64>) {
    let a = &cloud.attributes;
    out.clear();
    out.extend(cloud.points[i].iter().map(|c| Scalar::to_f64(*c)));
    if let Some(v) = &a.intensity {
        out.push(f64::from(v[i]));
    }
    if let Some(v) = &a.classification {
        out.push(f64::from(v[i]));
    }
    if let Some(v) = &a.color {
        out.extend(v[i].map(f64::from));
    }
    if let Some(v) = &a.gps_time {
        out.push(v[i]);
    }
    if let Some(v) = &a.normal {
        out.extend(v[i].map(f64::from));
    }
    out.extend(a.extra.iter().map(|c| c.values[i]));
}
