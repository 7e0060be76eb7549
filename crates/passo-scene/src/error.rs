//! Scene errors: what was wrong and where.

use std::fmt;

/// Why a scene could not be loaded.
#[derive(Clone, Debug, PartialEq)]
pub enum SceneError {
    /// The file could not be read.
    Io {
        /// The file.
        source_name: String,
        /// The operating system's message.
        message: String,
    },
    /// The text is not valid RON, or a value has the wrong type.
    Syntax {
        /// The file.
        source_name: String,
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// The field being read, if known.
        field: Option<String>,
        /// What was wrong.
        message: String,
    },
    /// A value is out of its allowed range.
    Invalid {
        /// The file.
        source_name: String,
        /// Path of the field, e.g. `bodies[3].mass`.
        field: String,
        /// What was wrong and the allowed range.
        message: String,
    },
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Io {
                source_name,
                message,
            } => write!(f, "{source_name}: cannot read: {message}"),
            Self::Syntax {
                source_name,
                line,
                column,
                field,
                message,
            } => {
                write!(f, "{source_name}:{line}:{column}: ")?;
                if let Some(field) = field {
                    write!(f, "in field `{field}`: ")?;
                }
                f.write_str(message)
            }
            Self::Invalid {
                source_name,
                field,
                message,
            } => write!(f, "{source_name}: `{field}` {message}"),
        }
    }
}

impl std::error::Error for SceneError {}

/// The closest of `candidates` to `word`: one it abbreviates (`rate` for
/// `rate_hz`), else the nearest by edit distance if close enough to be a
/// plausible typo.
pub(crate) fn closest<'a>(word: &str, candidates: &[&'a str]) -> Option<&'a str> {
    if word.len() >= 3
        && let Some(prefixed) = candidates
            .iter()
            .filter(|c| c.starts_with(word))
            .min_by_key(|c| c.len())
    {
        return Some(prefixed);
    }
    candidates
        .iter()
        .map(|c| (edit_distance(word, c), *c))
        .filter(|(d, c)| *d <= (c.len().max(word.len()) / 2).max(1))
        .min_by_key(|(d, _)| *d)
        .map(|(_, c)| c)
}

/// Levenshtein distance.
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diag = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let up = row[j + 1];
            row[j + 1] = (diag + usize::from(ca != *cb)).min(up + 1).min(row[j] + 1);
            diag = up;
        }
    }
    row[b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn typos_find_their_field() {
        let fields = ["mass", "density", "position", "velocity"];
        assert_eq!(closest("mas", &fields), Some("mass"));
        assert_eq!(closest("postion", &fields), Some("position"));
        assert_eq!(closest("colour", &fields), None);
        assert_eq!(edit_distance("kitten", "sitting"), 3);
    }
}
