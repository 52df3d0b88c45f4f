//! [`Attributes`]: the per-point values a scan carries besides its position (intensity,
//! classification, colour, GPS time, normals, and any other named column), held column by
//! column so that a column the file does not have costs nothing.

use super::CloudError;

/// A named column of numbers a file carries that has no field of its own in [`Attributes`]
/// (a PLY property such as `confidence`, a LAS field such as `return_number`). Every value a
/// reader takes (integers up to 32 bits, `f32`, `f64`) is held exactly by an `f64`.
#[derive(Clone, Debug, PartialEq)]
pub struct Column {
    /// The column's name, as the file spells it.
    pub name: String,
    /// One value per point.
    pub values: Vec<f64>,
}

/// The attributes of a cloud's points, one optional column per kind: `None` when the file has
/// no such values. Each present column has one entry per point ([`Attributes::check`]).
///
/// ```
/// use orthtree::cloud::Attributes;
/// let mut a = Attributes::default();
/// a.intensity = Some(vec![10, 20, 30]);
/// assert!(a.check(3).is_ok());
/// assert_eq!(a.check(2).unwrap_err().to_string(), "attribute column intensity has 3 values for 2 points");
/// let b = a.select(&[2, 0]);
/// assert_eq!(b.intensity, Some(vec![30, 10]));
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Attributes {
    /// Return strength (LAS `intensity`, 16 bits).
    pub intensity: Option<Vec<u16>>,
    /// ASPRS class code (LAS `classification`).
    pub classification: Option<Vec<u8>>,
    /// Red, green, blue (16 bits each, as in LAS; 8-bit files keep their 0-255 values).
    pub color: Option<Vec<[u16; 3]>>,
    /// GPS time of the return.
    pub gps_time: Option<Vec<f64>>,
    /// Unit surface normals (PLY `nx ny nz`; [`crate::cloud::normals`] computes them).
    pub normal: Option<Vec<[f32; 3]>>,
    /// Every other column, in the file's order.
    pub extra: Vec<Column>,
}

impl Attributes {
    /// The fixed columns by name, in the order the writers use, with their lengths when present.
    fn fixed_lengths(&self) -> [(&'static str, Option<usize>); 5] {
        [
            ("intensity", self.intensity.as_ref().map(Vec::len)),
            ("classification", self.classification.as_ref().map(Vec::len)),
            ("color", self.color.as_ref().map(Vec::len)),
            ("gps_time", self.gps_time.as_ref().map(Vec::len)),
            ("normal", self.normal.as_ref().map(Vec::len)),
        ]
    }

    /// Checks that every present column has `len` values.
    ///
    /// # Errors
    /// [`CloudError::ColumnLength`] naming the first column of another length.
    pub fn check(&self, len: usize) -> Result<(), CloudError> {
        for (name, found) in self.fixed_lengths() {
            if let Some(found) = found.filter(|&n| n != len) {
                return Err(CloudError::ColumnLength {
                    column: name.to_string(),
                    values: found,
                    points: len,
                });
            }
        }
        if let Some(c) = self.extra.iter().find(|c| c.values.len() != len) {
            return Err(CloudError::ColumnLength {
                column: c.name.clone(),
                values: c.values.len(),
                points: len,
            });
        }
        Ok(())
    }

    /// The attributes of the points at `indices`, in that order.
    ///
    /// # Panics
    /// When an index is out of range of a present column.
    pub fn select(&self, indices: &[usize]) -> Attributes {
        fn pick<V: Copy>(column: &Option<Vec<V>>, indices: &[usize]) -> Option<Vec<V>> {
            column
                .as_ref()
                .map(|c| indices.iter().map(|&i| c[i]).collect())
        }
        Attributes {
            intensity: pick(&self.intensity, indices),
            classification: pick(&self.classification, indices),
            color: pick(&self.color, indices),
            gps_time: pick(&self.gps_time, indices),
            normal: pick(&self.normal, indices),
            extra: self
                .extra
                .iter()
                .map(|c| Column {
                    name: c.name.clone(),
                    values: indices.iter().map(|&i| c.values[i]).collect(),
                })
                .collect(),
        }
    }

    /// Empty columns of the same kinds as these, for a reader or an operation to fill.
    pub fn same_kinds(&self) -> Attributes {
        self.select(&[])
    }

    /// Whether no column is present.
    ///
    /// ```
    /// use orthtree::cloud::Attributes;
    /// let mut a = Attributes::default();
    /// assert!(a.is_empty());
    /// a.gps_time = Some(vec![1.5]);
    /// assert!(!a.is_empty());
    /// ```
    pub fn is_empty(&self) -> bool {
        self.fixed_lengths().iter().all(|f| f.1.is_none()) && self.extra.is_empty()
    }

    /// The names of the present columns, in the order the writers use.
    pub fn names(&self) -> Vec<String> {
        let fixed = self.fixed_lengths().into_iter().filter(|f| f.1.is_some());
        let extra = self.extra.iter().map(|c| c.name.clone());
        fixed.map(|f| f.0.to_string()).chain(extra).collect()
    }

    /// The extra column called `name`, if any.
    pub fn extra_column(&self, name: &str) -> Option<&[f64]> {
        self.extra
            .iter()
            .find(|c| c.name == name)
            .map(|c| &c.values[..])
    }
}
