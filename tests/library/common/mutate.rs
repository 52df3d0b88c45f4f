//! Mutations of a serialized document (a `serde_json::Value`) for the serde fuzz tests: a number
//! replaced by a value at or beyond some limit, an array element dropped or duplicated, an array
//! emptied or grown. Each test then asserts that reading the mutated document either fails with
//! an error or gives a structure that passes `validate`.

use serde_json::{json, Value};

/// The replacements for a number: limits of the integer types, extremes and neighbours.
fn replacement(old: &Value, pick: u8) -> Value {
    let x = old.as_f64().unwrap_or(0.0);
    match pick % 12 {
        0 => json!(0),
        1 => json!(-1),
        2 => json!(1),
        3 => json!(u32::MAX),
        4 => json!(u32::MAX as u64 + 1),
        5 => json!(1e300),
        6 => json!(-1e300),
        7 => json!(0.5),
        8 => json!(x + 1.0),
        9 => json!(x - 1.0),
        10 => json!(x * 2.0),
        _ => json!(u64::MAX),
    }
}

/// One step from a value to a part of it.
#[derive(Clone, Debug)]
enum Step {
    Index(usize),
    Key(String),
}

/// The numbers and arrays of `doc`, as paths, in a pre-order walk (an explicit stack).
fn places(doc: &Value) -> Vec<Vec<Step>> {
    let mut found = Vec::new();
    let mut stack: Vec<(Vec<Step>, &Value)> = vec![(Vec::new(), doc)];
    while let Some((path, v)) = stack.pop() {
        let child = |step: Step| {
            let mut p = path.clone();
            p.push(step);
            p
        };
        match v {
            Value::Number(_) => found.push(path),
            Value::Array(a) => {
                stack.extend(
                    a.iter()
                        .enumerate()
                        .map(|(i, x)| (child(Step::Index(i)), x)),
                );
                found.push(path);
            }
            Value::Object(o) => {
                stack.extend(o.iter().map(|(k, x)| (child(Step::Key(k.clone())), x)))
            }
            _ => {}
        }
    }
    found
}

/// Applies mutation `kind` (see the module doc) at the `at`-th place (modulo the number of
/// places) of `doc`, numbers and arrays counted in a pre-order walk. Returns what it did.
pub fn mutate(doc: &mut Value, at: u64, kind: u8) -> String {
    let all = places(doc);
    if all.is_empty() {
        return "nothing to mutate".into();
    }
    let mut target = doc;
    for step in &all[(at % all.len() as u64) as usize] {
        target = match step {
            Step::Index(i) => &mut target[*i],
            Step::Key(k) => &mut target[k.as_str()],
        };
    }
    match target {
        Value::Array(a) if !a.is_empty() => {
            let i = (at / 7) as usize % a.len();
            match kind % 4 {
                0 => {
                    a.remove(i);
                    format!("dropped element {i}")
                }
                1 => {
                    let copy = a[i].clone();
                    a.insert(i, copy);
                    format!("duplicated element {i}")
                }
                2 => {
                    a.clear();
                    "emptied an array".into()
                }
                _ => {
                    let copy = a[i].clone();
                    a.push(copy);
                    format!("appended a copy of element {i}")
                }
            }
        }
        Value::Array(a) => {
            a.push(json!(0));
            "pushed 0 into an empty array".into()
        }
        number => {
            let new = replacement(number, kind);
            let done = format!("replaced {number} by {new}");
            *number = new;
            done
        }
    }
}
