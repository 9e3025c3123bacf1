//! Sizes of the harness's files and functions, test code aside: a file's lines outside
//! `#[cfg(test)]` items, a function's lines from `fn` to its closing brace.

use super::source::{is_test_file, non_test_lines};

/// Most lines of a file.
pub const FILE_MAX: usize = 500;
/// Most lines of a function.
pub const FUNCTION_MAX: usize = 120;

/// `line` with string and character literals emptied, and without its `//` comment, so
/// that braces inside them do not count.
fn bare(line: &str) -> String {
    let mut out = String::new();
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '"' => {
                while let Some(d) = chars.next() {
                    if d == '\\' {
                        chars.next();
                    } else if d == '"' {
                        break;
                    }
                }
                out.push_str("\"\"");
            }
            '\'' if matches!(chars.clone().nth(1), Some('\'')) => {
                chars.nth(1); // 'x'
            }
            '/' if chars.peek() == Some(&'/') => break,
            _ => out.push(c),
        }
    }
    out
}

/// The name of the function a line starts, if it does (`pub(crate) unsafe fn name(`).
fn function_name(line: &str) -> Option<String> {
    let words: Vec<&str> = line.split_whitespace().collect();
    let at = words.iter().position(|w| *w == "fn")?;
    let qualifiers = &words[..at];
    let ok = qualifiers.iter().all(|w| {
        w.starts_with("pub") || matches!(*w, "const" | "unsafe" | "async" | "extern" | "\"C\"")
    });
    let name: String = words
        .get(at + 1)?
        .chars()
        .take_while(|c| c.is_alphanumeric() || *c == '_')
        .collect();
    (ok && !name.is_empty()).then_some(name)
}

/// Every file over [`FILE_MAX`] lines and every function over [`FUNCTION_MAX`], as
/// `file` → lines and `file::function` → lines.
pub fn oversized(files: &[(String, String)]) -> Vec<(String, usize)> {
    let mut out = Vec::new();
    for (file, text) in files.iter().filter(|(f, _)| !is_test_file(f)) {
        let lines = non_test_lines(text);
        if lines.len() > FILE_MAX {
            out.push((file.clone(), lines.len()));
        }
        let mut k = 0;
        while k < lines.len() {
            let Some(name) = function_name(lines[k].1) else {
                k += 1;
                continue;
            };
            let (mut depth, mut opened, mut end) = (0i64, false, k);
            for (e, (_, l)) in lines.iter().enumerate().skip(k) {
                let b = bare(l);
                depth += b.matches('{').count() as i64 - b.matches('}').count() as i64;
                opened |= b.contains('{');
                end = e;
                if (opened && depth <= 0) || (!opened && b.trim_end().ends_with(';')) {
                    break;
                }
            }
            let span = lines[end].0 - lines[k].0 + 1;
            if span > FUNCTION_MAX {
                out.push((format!("{file}::{name}"), span));
            }
            k += 1;
        }
    }
    out.sort();
    out
}
