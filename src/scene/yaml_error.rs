//! The YAML reader's errors in the scene format's words: the line, the dotted key the error
//! sits at (read back from the text, since the reader reports only a position), and one
//! sentence of what is wrong, never the reader's advice to its own programmers.

use crate::error::quote;

/// The sentence for a reader error at (`line`, `column`), 1-based, in `text`, and the line it
/// names (none where the mapping that lacks a key is the whole file).
pub fn describe(text: &str, message: &str, line: Option<(u64, u64)>) -> (Option<u64>, String) {
    let first = message
        .lines()
        .next()
        .unwrap_or("not a valid scene")
        .trim()
        .trim_start_matches("error: ");
    let what = first
        .split_once(": ")
        .filter(|(head, _)| head.starts_with("line "))
        .map_or(first, |(_, rest)| rest);
    // The file's first value, where the whole file is what the reader refused, has no key.
    let root = line.is_some_and(|(l, c)| c == 1 && first_content_line(text) == Some(l as usize));
    let path = line
        .filter(|_| !root)
        .and_then(|(l, c)| path_at(text, l as usize, c as usize));
    let key = |path: &[String]| dotted(&path.join("."));
    let at = |sentence: String| (line.map(|(l, _)| l), sentence);
    if what.starts_with("multiple YAML documents") {
        return at(
            "a second YAML document starts here (after a `---` line); a scene is one document"
                .into(),
        );
    }
    if let Some(field) = what.strip_prefix("missing field `") {
        let field = field.trim_end_matches('`');
        // The reader points into the mapping that lacks the field.
        return match path {
            Some(mut p) if p.len() > 1 => {
                p.pop();
                p.push(field.to_string());
                at(format!("{} is missing", key(&p)))
            }
            // The mapping that lacks it is the whole file: no line says more.
            Some(_) => (None, format!("`{field}` is missing")),
            None if root => (None, format!("`{field}` is missing")),
            None => at(format!("`{field}` is missing")),
        };
    }
    let wrong = reworded(what, path.is_none());
    at(match path {
        Some(p) => format!("{} {wrong}", key(&p)),
        None => wrong,
    })
}

/// What is wrong with a value, in the scene format's words; `unplaced` when no key could be
/// read back, so an unknown key's own text must be quoted.
fn reworded(what: &str, unplaced: bool) -> String {
    if what.starts_with("expected mapping start") && unplaced {
        return "a scene file is a map of keys (`key: value` lines), and this is not one".into();
    }
    if let Some((_, sentence)) = WORDS.iter().find(|(said, _)| what.starts_with(said)) {
        return (*sentence).into();
    }
    if let Some(rest) = what.strip_prefix("unknown field `") {
        // The field's own text may hold anything, the reader's list of keys comes last.
        let (field, expected) = rest
            .rsplit_once("`, expected ")
            .unwrap_or((rest.trim_end_matches('`'), "a key of the scene format"));
        let named = if unplaced {
            format!("{} ", quote(field))
        } else {
            String::new()
        };
        format!(
            "{named}is not a key of the scene format here (expected {})",
            clip(expected)
        )
    } else if let Some(breach) = what.strip_prefix("budget breached: ") {
        beyond_the_readers_budget(breach)
    } else if let Some(rest) = what.strip_prefix("invalid length ") {
        let got = rest.split(',').next().unwrap_or("");
        format!("must hold exactly two numbers, [x, y], not {got}")
    } else {
        format!("cannot be read: {}", clip(what))
    }
}

/// The reader's words (how its message starts) and the scene format's for the same fault.
/// "invalid floating point" is its answer to text, a flag, a null or an overflow where a number
/// belongs; "expected string scalar" to a list or a map where one value belongs, whatever the
/// value's kind.
const WORDS: [(&str, &str); 9] = [
    ("invalid i64", "must be a whole number"),
    ("invalid u64", "must be a whole number"),
    ("duplicate mapping key", "is given twice"),
    (
        "cannot deserialize null into string",
        "is empty; it needs a name",
    ),
    ("invalid floating point", "must be a number"),
    (
        "expected string scalar",
        "must be one value, not a list or a map",
    ),
    (
        "expected sequence start",
        "must be a list (`[a, b]`, or lines that start with `- `)",
    ),
    (
        "expected mapping start",
        "must be a map of keys (`{key: value}`, or `key: value` lines indented under it)",
    ),
    (
        "data did not match any variant of untagged enum AxleLoads",
        "must be a number (N on every axle) or a list of numbers, one per axle",
    ),
];

/// A reader message cut to one short line: its echoes of the scene's text are quoted and
/// shortened like every other excerpt.
/// A key path as a message names it: in backticks, or quoted and cut where it is longer than
/// any key of the format (a flow of nested garbage can make it thousands of characters).
fn dotted(path: &str) -> String {
    if path.chars().count() <= 80 && !path.chars().any(char::is_control) {
        return format!("`{path}`");
    }
    quote(path)
}

/// The reader's budget breached (`Nodes { nodes: 250001 }`), in words: which count, and how
/// far it had come.
fn beyond_the_readers_budget(breach: &str) -> String {
    let (kind, count) = breach.split_once(' ').unwrap_or((breach, ""));
    let count: String = count.chars().filter(char::is_ascii_digit).collect();
    let what = match kind {
        "Nodes" => "values (each number, list and map one)",
        "Events" => "YAML events",
        "Depth" => "levels of nesting",
        "Aliases" => "aliases (`*name`)",
        "Anchors" => "anchors (`&name`)",
        "Documents" => "documents",
        _ => "of what the reader counts",
    };
    format!("holds more {what} than the scene reader takes ({count} by here)")
}

fn clip(message: &str) -> String {
    if message.chars().count() <= 160 && !message.chars().any(char::is_control) {
        return message.to_string();
    }
    quote(message)
}

/// The first line (1-based) that holds more than blanks and a comment.
fn first_content_line(text: &str) -> Option<usize> {
    text.lines()
        .position(|l| {
            let l = l.trim();
            !l.is_empty() && !l.starts_with('#') && l != "---"
        })
        .map(|i| i + 1)
}

/// The dotted key whose value holds position (`line`, `column`): the block keys above it by
/// indentation, then the flow mappings open on its own line, then the key at or before it.
fn path_at(text: &str, line: usize, column: usize) -> Option<Vec<String>> {
    let lines: Vec<&str> = text.lines().collect();
    let here = *lines.get(line.checked_sub(1)?)?;
    let mut path = parents(&lines[..line - 1], indent(here));
    let cut = here
        .char_indices()
        .nth(column.saturating_sub(1))
        .map_or(here.len(), |(i, _)| i);
    // The key that starts at the position, if one does, belongs to the prefix.
    let through = here[cut..]
        .find(':')
        .filter(|&i| is_key(here[cut..cut + i].trim()))
        .map_or(cut, |i| cut + i + 1);
    let mut open: Vec<Option<String>> = Vec::new();
    let mut last: Option<String> = None;
    let mut word = String::new();
    for ch in here[..through].chars() {
        match ch {
            '{' | '[' => {
                open.push(last.take());
                word.clear();
            }
            '}' | ']' => {
                open.pop();
                last = None;
                word.clear();
            }
            ':' if is_key(word.trim()) => {
                last = Some(key_name(word.trim()).to_string());
                word.clear();
            }
            ',' => word.clear(),
            c => word.push(c),
        }
    }
    path.extend(open.into_iter().flatten());
    path.extend(last);
    (!path.is_empty()).then_some(path)
}

/// The block keys that enclose a line of this indentation, outermost first.
fn parents(above: &[&str], mut depth: usize) -> Vec<String> {
    let mut keys = Vec::new();
    for l in above.iter().rev() {
        let t = l.trim_start();
        if t.is_empty() || t.starts_with('#') || indent(l) >= depth {
            continue;
        }
        depth = indent(l);
        if let Some((k, _)) = t.trim_start_matches("- ").split_once(':') {
            if is_key(k) {
                keys.push(key_name(k).to_string());
            }
        }
        if depth == 0 {
            break;
        }
    }
    keys.reverse();
    keys
}

fn indent(line: &str) -> usize {
    line.len() - line.trim_start_matches([' ', '-']).len()
}

fn is_key(word: &str) -> bool {
    let w = key_name(word);
    !w.is_empty() && w.len() <= 40 && w.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// A key as written, without a list item's dash or the quotes around it: JSON, which the
/// Python package writes a scene dict as, quotes every key.
fn key_name(word: &str) -> &str {
    let w = word.trim_start_matches("- ");
    ['"', '\'']
        .iter()
        .find_map(|&q| w.strip_prefix(q).and_then(|w| w.strip_suffix(q)))
        .unwrap_or(w)
}

#[cfg(test)]
mod tests {
    use super::{dotted, path_at};

    /// A key path nested past any the format has is cut in the message, which stays one short
    /// line (found by fuzzing: a flow of nested keys made a sentence of 834 characters).
    #[test]
    fn a_long_key_path_is_cut() {
        assert_eq!(dotted("track.beam.E"), "`track.beam.E`");
        let long = ["k".repeat(50), "k".repeat(50)].join(".");
        let named = dotted(&long);
        assert!(named.chars().count() < 50 && named.contains('…'), "{named}");
        assert!(!dotted("a\nb").contains('\n'));
    }

    #[test]
    fn keys_are_found_by_indentation_and_flow() {
        let text = "duration: 1\ntrack:\n  beam:\n    elements: 8.0\n    supports: {from: pinned, to: rock}\ndisk: {radius: 0.1}\n";
        let at = |l, c| path_at(text, l, c).map(|p| p.join("."));
        assert_eq!(at(1, 1).as_deref(), Some("duration"));
        assert_eq!(at(4, 15).as_deref(), Some("track.beam.elements"));
        assert_eq!(at(5, 34).as_deref(), Some("track.beam.supports.to"));
        assert_eq!(at(6, 8).as_deref(), Some("disk.radius"));
    }

    /// A scene dict from Python arrives as JSON, every key quoted and every map in braces:
    /// its keys are found as a block file's are.
    #[test]
    fn quoted_keys_are_found() {
        let text = "{\n \"track\": {\n  \"beam\": {\n   \"from\": [\n    0.0\n   ],\n   \"elements\": 8.5\n  }\n }\n}\n";
        let at = |l, c| path_at(text, l, c).map(|p| p.join("."));
        assert_eq!(at(4, 12).as_deref(), Some("track.beam.from"));
        assert_eq!(at(7, 16).as_deref(), Some("track.beam.elements"));
    }
}
