//! The records of a `.poly` file: its data lines with the size comments taken out, and the
//! checks of fields and counts the sections share.

use super::super::board_syntax::{parse_error, Line, Lines, Quoted};
use crate::mesh::BoardError;

/// The data lines of a `.poly` file, with the `# size U` comments taken out on the way.
pub(super) struct Records<'a> {
    lines: Lines<'a>,
    /// The size a comment gives, and its line.
    size: Option<(i64, usize)>,
}

impl<'a> Records<'a> {
    /// The records of `bytes`.
    pub(super) fn new(bytes: &'a [u8]) -> Self {
        Records {
            lines: Lines::new(bytes),
            size: None,
        }
    }

    /// The size a `# size U` comment gave, with its line.
    pub(super) fn size(&self) -> Option<(i64, usize)> {
        self.size
    }

    /// The next line holding data, checking every comment before it.
    pub(super) fn next(&mut self) -> Result<Option<Line<'a>>, BoardError> {
        while let Some(line) = self.lines.next() {
            let line = line?;
            if let Some(comment) = line.comment {
                self.size_comment(&line, comment)?;
            }
            if !line.is_blank() {
                return Ok(Some(line));
            }
        }
        Ok(None)
    }

    /// The next data line, or [`Records::end_of_input`].
    pub(super) fn expect(&mut self, expected: &str) -> Result<Line<'a>, BoardError> {
        self.next()?.ok_or_else(|| self.end_of_input(expected))
    }

    /// The error for input that ends where `expected` should be, on the last line.
    pub(super) fn end_of_input(&self, expected: &str) -> BoardError {
        parse_error(
            self.lines.last_number().max(1),
            format!("unexpected end of input: expected {expected}"),
        )
    }

    fn size_comment(&mut self, line: &Line<'_>, comment: &str) -> Result<(), BoardError> {
        let Some(u) = size_directive(comment) else {
            return Ok(());
        };
        let u = u.map_err(|m| parse_error(line.number, m))?;
        if !line.is_blank() {
            return Err(parse_error(
                line.number,
                "a `# size U` comment must be on a line of its own, not after data",
            ));
        }
        // The first size is kept; a later one must agree with it.
        match *self.size.get_or_insert((u, line.number)) {
            (v, first) if v != u => Err(parse_error(
                line.number,
                format!("size {u} contradicts size {v} given on line {first}"),
            )),
            _ => Ok(()),
        }
    }
}

/// `None` for a comment (the text after `#`) that is not about the size; `Some(Ok(U))` for
/// exactly `size U` with an integer U; `Some(Err(message))` for any other comment whose first
/// word is `size` (in any case, followed by anything but a letter).
pub(super) fn size_directive(comment: &str) -> Option<Result<i64, String>> {
    let text = comment.trim_matches([' ', '\t']);
    let keyword = text.get(..4)?;
    let rest = &text[4..];
    if !keyword.eq_ignore_ascii_case("size") || rest.starts_with(|c: char| c.is_alphabetic()) {
        return None;
    }
    let mut fields = rest.split([' ', '\t']).filter(|f| !f.is_empty());
    let value = match (rest.starts_with([' ', '\t']), fields.next(), fields.next()) {
        (true, Some(value), None) => value.parse::<i64>().ok(),
        _ => None,
    };
    Some(value.ok_or_else(|| {
        format!(
            "a size comment must read `# size U` with an integer U, not {}",
            Quoted(&format!("#{comment}"))
        )
    }))
}

/// The error for a count that does not match its section, on the count's line.
pub(super) fn count_error(line: usize, what: &str, count: usize, detail: String) -> BoardError {
    parse_error(line, format!("the {what} count is {count}, but {detail}"))
}

/// True when `line` has `fields` fields (at least 3) and, if `id` is given, starts with it: a
/// record continuing a section past its count.
pub(super) fn continues(line: &Line<'_>, fields: usize, id: Option<i64>) -> bool {
    fields >= 3
        && line.fields().count() == fields
        && id.is_none_or(|id| line.fields().next().and_then(|f| f.parse().ok()) == Some(id))
}

/// True when `line` cannot be a record of at least 3 fields, nor, if `id` is given, the record
/// of that id with fields missing: the section ended before its count.
pub(super) fn ends_section(line: &Line<'_>, id: Option<i64>) -> bool {
    line.fields().nth(2).is_none()
        && id.is_none_or(|id| line.fields().next().and_then(|f| f.parse().ok()) != Some(id))
}

/// The fields after a record's first three must be `numbers` numbers then `integers` integers
/// and nothing more; `wanted` describes the record for the message.
pub(super) fn check_fields(
    line: &Line<'_>,
    numbers: usize,
    integers: usize,
    wanted: &str,
) -> Result<(), BoardError> {
    let have = line.fields().count();
    let expected = 3usize.saturating_add(numbers).saturating_add(integers);
    if have != expected {
        return Err(parse_error(
            line.number,
            format!("this line has {have} fields, expected {expected}: {wanted}"),
        ));
    }
    for (k, field) in line.fields().skip(3).enumerate() {
        let (ok, what, kind) = if k < numbers {
            let finite = field.parse::<f64>().is_ok_and(f64::is_finite);
            (finite, "attribute", "a finite number")
        } else {
            let integer = field.parse::<i64>().is_ok();
            (integer, "boundary marker", "an integer")
        };
        if !ok {
            let message = format!("{what} {} is not {kind}", Quoted(field));
            return Err(parse_error(line.number, message));
        }
    }
    Ok(())
}

/// The first field of a data line (which has at least one).
pub(super) fn first_field<'a>(line: &Line<'a>) -> &'a str {
    line.fields().next().unwrap_or_default()
}

/// A line holding one count and nothing else.
pub(super) fn single_count(line: &Line<'_>, what: &str, record: &str) -> Result<usize, BoardError> {
    let count = parse_count(first_field(line), line.number, what)?;
    extra_field(line.number, line.fields().nth(1), record)?;
    Ok(count)
}

/// The error for a field after the last one a count line may hold.
pub(super) fn extra_field(
    line: usize,
    extra: Option<&str>,
    record: &str,
) -> Result<(), BoardError> {
    match extra {
        None => Ok(()),
        Some(extra) => Err(parse_error(
            line,
            format!("unexpected field {} after `{record}`", Quoted(extra)),
        )),
    }
}

pub(super) fn parse_count(field: &str, line: usize, what: &str) -> Result<usize, BoardError> {
    field.parse().map_err(|_| {
        parse_error(
            line,
            format!("{what} {} is not a non-negative integer", Quoted(field)),
        )
    })
}

pub(super) fn parse_marker_count(field: &str, line: usize) -> Result<usize, BoardError> {
    match field {
        "0" => Ok(0),
        "1" => Ok(1),
        _ => Err(parse_error(
            line,
            format!("boundary marker count {}: expected 0 or 1", Quoted(field)),
        )),
    }
}

pub(super) fn parse_id(field: &str, line: usize, what: &str) -> Result<i64, BoardError> {
    field
        .parse()
        .map_err(|_| parse_error(line, format!("{what} {} is not an integer", Quoted(field))))
}
