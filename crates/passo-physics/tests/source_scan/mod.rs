//! Reading the crate's sources as code for the tests that check them
//! (`module_graph.rs`): comments, the insides of
//! literals and test-only code blanked out, line numbers kept.

/// The code of a file without comments, without the insides of string and
/// character literals, and without test-only code: each item, field,
/// statement or match arm marked `#[cfg(test)]`. Everything left out turns
/// into spaces, line breaks kept, so line numbers still hold.
pub fn strip(text: &str) -> String {
    let mut code = without_comments_and_literals(text);
    let mark: Vec<char> = "#[cfg(test)]".chars().collect();
    let mut i = 0;
    while i < code.len() {
        if code[i..].starts_with(&mark) {
            let end = end_of_marked(&code, i + mark.len());
            blank(&mut code[i..end]);
            i = end;
        } else {
            i += 1;
        }
    }
    code.into_iter().collect()
}

/// Turns text into spaces, keeping line breaks.
fn blank(text: &mut [char]) {
    for c in text.iter_mut().filter(|c| **c != '\n') {
        *c = ' ';
    }
}

/// The characters of `text` with comments and the insides of string and
/// character literals blanked, so that braces and marks in them do not
/// count.
fn without_comments_and_literals(text: &str) -> Vec<char> {
    let src: Vec<char> = text.chars().collect();
    let mut out = src.clone();
    let at = |i: usize| src.get(i).copied();
    let mut i = 0;
    while i < src.len() {
        let in_word = i > 0 && (src[i - 1].is_alphanumeric() || src[i - 1] == '_');
        // A raw string: `r"…"`, `r#"…"#`, `br"…"`.
        let raw_start = match (src[i], at(i + 1)) {
            ('r', _) if !in_word => Some(i + 1),
            ('b', Some('r')) if !in_word => Some(i + 2),
            _ => None,
        };
        let hashes = raw_start.map_or(0, |s| src[s..].iter().take_while(|&&c| c == '#').count());
        let end = match (src[i], at(i + 1)) {
            ('/', Some('/')) => {
                let end = src[i..]
                    .iter()
                    .position(|&c| c == '\n')
                    .map_or(src.len(), |n| i + n);
                blank(&mut out[i..end]);
                end
            }
            ('/', Some('*')) => {
                // Block comments nest.
                let (mut depth, mut j) = (0, i);
                while j < src.len() {
                    match (src[j], at(j + 1)) {
                        ('/', Some('*')) => (depth, j) = (depth + 1, j + 2),
                        ('*', Some('/')) => (depth, j) = (depth - 1, j + 2),
                        _ => j += 1,
                    }
                    if depth == 0 {
                        break;
                    }
                }
                let end = j.min(src.len());
                blank(&mut out[i..end]);
                end
            }
            _ if raw_start.is_some_and(|s| at(s + hashes) == Some('"')) => {
                let open = raw_start.unwrap() + hashes + 1;
                let close: Vec<char> = ['"'].into_iter().chain(vec!['#'; hashes]).collect();
                let mut j = open;
                while j < src.len() && !src[j..].starts_with(&close) {
                    j += 1;
                }
                blank(&mut out[open..j.min(src.len())]);
                j + 1 + hashes
            }
            ('"', _) => {
                let mut j = i + 1;
                while j < src.len() && src[j] != '"' {
                    j += if src[j] == '\\' { 2 } else { 1 };
                }
                let end = j.min(src.len());
                blank(&mut out[i + 1..end]);
                end + 1
            }
            // A character literal, `'x'` or `'\n'`; otherwise a lifetime.
            ('\'', Some('\\')) => {
                let close = src[i + 3..]
                    .iter()
                    .position(|&c| c == '\'')
                    .map_or(src.len(), |n| i + 3 + n);
                blank(&mut out[i + 1..close]);
                close + 1
            }
            ('\'', Some(_)) if at(i + 2) == Some('\'') => {
                blank(&mut out[i + 1..i + 2]);
                i + 3
            }
            _ => i + 1,
        };
        i = end.max(i + 1);
    }
    out
}

/// Where the thing marked `#[cfg(test)]` that starts at `from` ends: an
/// item (brace-matched, or up to its `;`), a `let` statement (up to its
/// `;`), or a field, variant, match arm, block or statement (up to its `,`
/// or `;`, up to its closing brace, or up to the end of the list or block
/// it is the last of).
fn end_of_marked(code: &[char], from: usize) -> usize {
    let start = after_attributes(code, from);
    let first: String = code[start..]
        .iter()
        .take_while(|c| c.is_alphanumeric() || **c == '_')
        .collect();
    let up_to_semicolon = ["let", "const", "static", "use", "type"].contains(&first.as_str());
    let item = [
        "fn", "mod", "struct", "enum", "union", "impl", "trait", "extern",
    ]
    .contains(&first.as_str());
    let mut depth = 0usize;
    for (i, &c) in code.iter().enumerate().skip(start) {
        match c {
            '(' | '[' | '{' => depth += 1,
            // The end of the list or block the marked thing is the last of.
            ')' | ']' | '}' if depth == 0 => return i,
            ')' | ']' => depth -= 1,
            '}' => {
                depth -= 1;
                let next = skip_space(code, i + 1);
                let after = code.get(next).copied();
                let goes_on = matches!(after, Some('.' | '?'))
                    || code[next..].starts_with(&['e', 'l', 's', 'e']);
                if depth == 0 && !up_to_semicolon && !goes_on {
                    // A match arm's block may take a comma.
                    return if after == Some(',') && !item {
                        next + 1
                    } else {
                        i + 1
                    };
                }
            }
            ';' if depth == 0 => return i + 1,
            ',' if depth == 0 && !up_to_semicolon && !item => return i + 1,
            _ => {}
        }
    }
    code.len()
}

/// The first character at or after `i` that is not white space.
fn skip_space(code: &[char], i: usize) -> usize {
    i + code[i..].iter().take_while(|c| c.is_whitespace()).count()
}

/// Where the code at `i` starts once any attributes and visibility before
/// it are passed.
fn after_attributes(code: &[char], mut i: usize) -> usize {
    loop {
        i = skip_space(code, i);
        let rest = &code[i..];
        let (open, close) = if rest.starts_with(&['#', '[']) {
            ('[', ']')
        } else if rest.starts_with(&['p', 'u', 'b', '(']) {
            ('(', ')')
        } else if rest.starts_with(&['p', 'u', 'b', ' ']) {
            i += 3;
            continue;
        } else {
            return i;
        };
        let mut depth = 0i32;
        let mut end = code.len();
        for (j, &c) in code.iter().enumerate().skip(i) {
            if c == open {
                depth += 1;
            } else if c == close {
                depth -= 1;
                if depth == 0 {
                    end = j + 1;
                    break;
                }
            }
        }
        i = end;
    }
}

/// Every `.rs` file under `dir`, depth first.
pub fn rust_files(dir: &std::path::Path, out: &mut Vec<std::path::PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}
