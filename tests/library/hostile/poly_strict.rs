//! Every item of a `.poly` file is used or refused: holes and regional attributes (not supported
//! yet), vertices on no segment, attribute and marker counts that the lines do not match, junk
//! fields, ids that are not integers, size comments that are not exactly `# size U`, and counts
//! that do not match their sections (blamed on the count's line). Each input is made from one
//! valid file by the code below.

use orthtree::io::poly::read_poly;
use orthtree::mesh::BoardError;

/// A valid file: a header with `attributes` attributes and `markers` markers, four vertices,
/// four segments (with `segment_markers` markers), then `tail` (the hole and region sections).
/// Line 1 is the vertex header, lines 2-5 the vertices, line 6 the segment header, lines 7-10
/// the segments, the tail from line 11.
fn poly(attributes: usize, markers: usize, segment_markers: usize, tail: &str) -> String {
    let mut s = format!("4 2 {attributes} {markers}\n");
    for (i, [x, y]) in [[1, 1], [5, 1], [5, 5], [1, 5]].iter().enumerate() {
        s += &format!("{} {x} {y}", i + 1);
        s += &" 0.25".repeat(attributes);
        s += &" 7".repeat(markers);
        s += "\n";
    }
    s += &format!("4 {segment_markers}\n");
    for i in 0..4 {
        s += &format!("{} {} {}", i + 1, i + 1, (i + 1) % 4 + 1);
        s += &" 2".repeat(segment_markers);
        s += "\n";
    }
    s + tail
}

/// The file with line `number` (from 1) replaced by `with`.
fn replace_line(text: &str, number: usize, with: &str) -> String {
    let mut lines: Vec<&str> = text.lines().collect();
    lines[number - 1] = with;
    lines.join("\n") + "\n"
}

fn parse_error(text: &str) -> (usize, String) {
    match read_poly(text, None) {
        Err(BoardError::Parse { line, message }) => (line, message),
        other => panic!("{text:?}: {other:?}"),
    }
}

fn assert_parse_error(text: &str, line: usize, needles: &[&str]) {
    let (l, message) = parse_error(text);
    assert_eq!(l, line, "{text:?}: {message}");
    for needle in needles {
        assert!(message.contains(needle), "{text:?}: {message}");
    }
}

#[test]
fn the_valid_files_read() {
    for (a, m, s) in [(0, 0, 0), (1, 0, 0), (0, 1, 1), (3, 1, 0), (2, 0, 1)] {
        for tail in ["", "0\n", "0\n0\n", "0 # no holes\n\n0   # no regions\n"] {
            let b = read_poly(&poly(a, m, s, tail), None).unwrap();
            assert_eq!(b.size(), 8);
            assert_eq!(b.components()[0].outline.len(), 4);
        }
    }
}

#[test]
fn holes_are_refused_naming_the_line() {
    for count in [1usize, 2, 7] {
        let holes: String = (1..=count).map(|i| format!("{i} 3 3\n")).collect();
        let text = poly(0, 0, 0, &format!("{count}\n{holes}0\n"));
        let e = read_poly(&text, None).unwrap_err();
        assert_eq!(e, BoardError::HolesNotSupported { line: 11, count });
        let message = e.to_string();
        assert!(
            message.starts_with("line 11: ") && message.contains("holes are not supported yet"),
            "{message}"
        );
    }
    // a comment and blank lines before the count move its line
    let text = poly(0, 0, 0, "# holes\n\n1\n1 3 3\n");
    assert_eq!(
        read_poly(&text, None).unwrap_err(),
        BoardError::HolesNotSupported { line: 13, count: 1 }
    );
    // a hole count with more fields
    assert_parse_error(&poly(0, 0, 0, "0 5\n"), 11, &["unexpected field `5`"]);
    assert_parse_error(&poly(0, 0, 0, "-1\n"), 11, &["hole count `-1`"]);
}

#[test]
fn regional_attributes_are_refused_naming_the_line() {
    for count in [1usize, 3] {
        let regions: String = (1..=count).map(|i| format!("{i} 3 3 1.0 0.5\n")).collect();
        let text = poly(0, 0, 0, &format!("0\n{count}\n{regions}"));
        let e = read_poly(&text, None).unwrap_err();
        assert_eq!(e, BoardError::RegionsNotSupported { line: 12, count });
        assert!(e.to_string().contains("not supported"), "{e}");
    }
    assert_parse_error(&poly(0, 0, 0, "0\n0 0\n"), 12, &["unexpected field"]);
    // nothing may follow the regional attribute count
    for extra in ["5\n", "1 3 3\n", "size 8\n", "junk\n"] {
        assert_parse_error(
            &poly(0, 0, 0, &format!("0\n0\n{extra}")),
            13,
            &["unexpected data after the regional attribute count"],
        );
    }
}

#[test]
fn a_vertex_on_no_segment_is_refused() {
    // an extra vertex first, in the middle or last, numbered from 1 or from 0
    for (vertices, segments, unused, line) in [
        (
            "5 2 0 0\n1 9 9\n2 1 1\n3 5 1\n4 5 5\n5 1 5\n",
            "4 0\n1 2 3\n2 3 4\n3 4 5\n4 5 2\n",
            1,
            2,
        ),
        (
            "5 2 0 0\n1 1 1\n2 5 1\n3 9 9\n4 5 5\n5 1 5\n",
            "4 0\n1 1 2\n2 2 4\n3 4 5\n4 5 1\n",
            3,
            4,
        ),
        (
            "5 2 0 0\n1 1 1\n2 5 1\n3 5 5\n4 1 5\n5 9 9\n",
            "4 0\n1 1 2\n2 2 3\n3 3 4\n4 4 1\n",
            5,
            6,
        ),
        (
            "5 2 0 0\n0 1 1\n1 5 1\n2 5 5\n3 1 5\n4 9 9\n",
            "4 0\n0 0 1\n1 1 2\n2 2 3\n3 3 0\n",
            4,
            6,
        ),
    ] {
        let text = format!("{vertices}{segments}0\n");
        let e = read_poly(&text, Some(16)).unwrap_err();
        assert_eq!(
            e,
            BoardError::UnusedVertex {
                vertex: unused,
                line
            },
            "{text:?}"
        );
        assert!(e
            .to_string()
            .contains(&format!("vertex {unused} is on no segment")));
    }
}

#[test]
fn attribute_and_marker_counts_must_match_the_lines() {
    // declared but missing, present but not declared, one too many
    for (header, vertex_line, have, expected) in [
        ("4 2 1 0", "1 1 1", 3, 4u64),
        ("4 2 0 1", "1 1 1", 3, 4),
        ("4 2 2 1", "1 1 1 0.5 7", 5, 6),
        ("4 2 0 0", "1 1 1 0.5", 4, 3),
        ("4 2 1 0", "1 1 1 0.5 7", 5, 4),
        ("4 2 1000000000000 0", "1 1 1", 3, 1000000000003),
    ] {
        let text = replace_line(&replace_line(&poly(0, 0, 0, ""), 1, header), 2, vertex_line);
        assert_parse_error(
            &text,
            2,
            &[&format!("this line has {have} fields, expected {expected}")],
        );
    }
    // segment markers
    let text = replace_line(&poly(0, 0, 0, ""), 6, "4 1");
    assert_parse_error(&text, 7, &["this line has 3 fields, expected 4"]);
    let text = replace_line(&poly(0, 0, 1, ""), 6, "4 0");
    assert_parse_error(&text, 7, &["this line has 4 fields, expected 3"]);
    // a marker count other than 0 or 1
    for bad in ["2", "-1", "1.0", "x"] {
        let text = replace_line(&poly(0, 0, 0, ""), 1, &format!("4 2 0 {bad}"));
        assert_parse_error(&text, 1, &["boundary marker count", "expected 0 or 1"]);
        let text = replace_line(&poly(0, 0, 0, ""), 6, &format!("4 {bad}"));
        assert_parse_error(&text, 6, &["boundary marker count", "expected 0 or 1"]);
    }
    // attribute values must be finite numbers, markers integers
    for (line, bad, needle) in [
        ("1 1 1 abc 7", "`abc`", "attribute"),
        ("1 1 1 nan 7", "`nan`", "attribute"),
        ("1 1 1 inf 7", "`inf`", "attribute"),
        ("1 1 1 0.5 7.5", "`7.5`", "boundary marker"),
        ("1 1 1 0.5 x", "`x`", "boundary marker"),
    ] {
        let text = replace_line(&poly(1, 1, 0, ""), 2, line);
        assert_parse_error(&text, 2, &[needle, bad]);
    }
    let text = replace_line(&poly(0, 0, 1, ""), 8, "2 2 3 two");
    assert_parse_error(&text, 8, &["boundary marker `two`"]);
}

#[test]
fn junk_fields_are_refused() {
    let cases: &[(usize, &str, usize, &str)] = &[
        (1, "4 2 0 0 0", 1, "unexpected field `0`"),
        (1, "4 2 0 0 junk", 1, "unexpected field `junk`"),
        (6, "4 0 x", 6, "unexpected field `x`"),
        (6, "4 0 0", 6, "unexpected field `0`"),
        (3, "2 5 1 junk", 3, "this line has 4 fields, expected 3"),
        (8, "2 2 3 junk", 8, "this line has 4 fields, expected 3"),
        (1, "4 3 0 0", 1, "only 2"),
        (1, "4 2.0 0 0", 1, "only 2"),
        (1, "4 2 x 0", 1, "attribute count `x`"),
        (1, "4.0 2 0 0", 1, "vertex count `4.0`"),
        (6, "4.5 0", 6, "segment count `4.5`"),
    ];
    for &(number, with, line, needle) in cases {
        let text = replace_line(&poly(0, 0, 0, "0\n"), number, with);
        assert_parse_error(&text, line, &[needle]);
    }
}

#[test]
fn ids_must_be_integers() {
    let cases: &[(usize, &str, &str)] = &[
        (3, "2.0 5 1", "vertex id `2.0`"),
        (3, "4.5 5 1", "vertex id `4.5`"),
        (3, "two 5 1", "vertex id `two`"),
        (2, "1e0 1 1", "vertex id `1e0`"),
        (8, "2.5 2 3", "segment id `2.5`"),
        (8, "x 2 3", "segment id `x`"),
        (8, "2 2.0 3", "segment endpoint `2.0`"),
        (8, "2 2 3.5", "segment endpoint `3.5`"),
        (8, "2 2 9", "not a vertex id"),
        (8, "2 2 0", "not a vertex id"),
        (3, "3 5 1", "out of sequence"),
        (2, "2 1 1", "must be 0 or 1"),
    ];
    for &(number, with, needle) in cases {
        let text = replace_line(&poly(0, 0, 0, "0\n"), number, with);
        assert_parse_error(&text, number, &[needle]);
    }
}

#[test]
fn size_comments_must_be_exact() {
    let valid = poly(0, 0, 0, "0\n");
    for comment in [
        "# size 32 please",
        "# size: 32",
        "# size=32",
        "# SIZE 32 32",
        "# size",
        "# size 3.0",
        "# size thirty-two",
        "# size of the board",
        "#size32",
    ] {
        let text = format!("{comment}\n{valid}");
        assert_parse_error(&text, 1, &["a size comment must read `# size U`"]);
        // after the data too
        let text = format!("{valid}{comment}\n");
        assert_parse_error(&text, 12, &["a size comment must read `# size U`"]);
    }
    // a size comment after data on the same line
    let text = replace_line(&valid, 3, "2 5 1   # size 16");
    assert_parse_error(&text, 3, &["on a line of its own"]);
    // exact forms are read, in any case, anywhere, with spaces or tabs
    for comment in ["# size 32", "#size 32", "#\tSIZE\t32\t", "# Size 32   "] {
        for text in [format!("{comment}\n{valid}"), format!("{valid}{comment}\n")] {
            assert_eq!(read_poly(&text, None).unwrap().size(), 32, "{text:?}");
        }
    }
    // words that merely start with "size" are comments
    for comment in ["# sizes in units of 0.1 mm", "# sized for a 2-layer board"] {
        let text = format!("{comment}\n{valid}");
        assert_eq!(read_poly(&text, None).unwrap().size(), 8);
    }
    // two size comments must agree
    let text = format!("# size 32\n{valid}# size 32\n");
    assert_eq!(read_poly(&text, None).unwrap().size(), 32);
    let text = format!("# size 32\n{valid}# size 64\n");
    assert_parse_error(&text, 13, &["contradicts size 32 given on line 1"]);
}

#[test]
fn wrong_counts_are_blamed_on_the_count() {
    let valid = poly(0, 0, 0, "0\n");
    // vertex count too large: the section ends early, or the file ends
    for count in [5, 6, 100, 1_000_000_000_000usize] {
        let text = replace_line(&valid, 1, &format!("{count} 2 0 0"));
        assert_parse_error(
            &text,
            1,
            &[&format!(
                "the vertex count is {count}, but only 4 vertex lines follow: line 6"
            )],
        );
        let text = format!("{count} 2 0 0\n1 1 1\n2 5 1\n");
        assert_parse_error(
            &text,
            1,
            &[&format!(
                "the vertex count is {count}, but the input ends after 2 vertex lines"
            )],
        );
    }
    // vertex count too small: the next line continues the vertices
    for count in [1, 2, 3] {
        let text = replace_line(&valid, 1, &format!("{count} 2 0 0"));
        assert_parse_error(
            &text,
            1,
            &[&format!(
                "the vertex count is {count}, but line {} continues",
                count + 2
            )],
        );
    }
    // segment count too large or too small
    for count in [5, 9, 1_000_000_000_000usize] {
        let text = replace_line(&valid, 6, &format!("{count} 0"));
        assert_parse_error(
            &text,
            6,
            &[&format!(
                "the segment count is {count}, but only 4 segment lines follow"
            )],
        );
        let text = replace_line(&poly(0, 0, 0, ""), 6, &format!("{count} 0"));
        assert_parse_error(
            &text,
            6,
            &[&format!(
                "the segment count is {count}, but the input ends after 4"
            )],
        );
    }
    for count in [1, 3] {
        let text = replace_line(&valid, 6, &format!("{count} 0"));
        assert_parse_error(
            &text,
            6,
            &[&format!(
                "the segment count is {count}, but line {} continues",
                7 + count
            )],
        );
    }
    // a vertex line with a coordinate missing is blamed on its own line
    let text = replace_line(&valid, 4, "3 5");
    assert_parse_error(&text, 4, &["this line has 2 fields, expected 3"]);
}
