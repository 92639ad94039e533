//! Where each key of a scene came from (a line of the file, `--set`, the default), for
//! error messages.

use std::collections::{HashMap, HashSet};

/// Where each key's value came from, for error messages: a line of the scene file, `--set`,
/// or the built-in default.
#[derive(Debug, Clone, Default)]
pub struct Origins {
    /// The scene file, if any.
    pub(super) file: Option<String>,
    /// 1-based line of each dotted key in the file.
    pub(super) lines: HashMap<String, usize>,
    /// Dotted keys given by `--set` (they override the file).
    pub(super) set: HashSet<String>,
    /// How those keys are named in errors (`--set` unless given).
    pub(super) label: Option<String>,
}

impl Origins {
    /// `file:line` for a key from the file, `--set` for an override, else
    /// `(built-in default)` (a default or a scene built in code).
    pub fn locate(&self, key: &str) -> String {
        if self.set.contains(key) {
            return self.label.clone().unwrap_or_else(|| "--set".into());
        }
        match (&self.file, self.lines.get(key)) {
            (Some(file), Some(line)) => format!("{file}:{line}"),
            (Some(file), None) if !key.contains('.') => file.clone(),
            _ => "(built-in default)".into(),
        }
    }

    /// Whether `key` (dotted) was given: in the file or by an override.
    pub fn given(&self, key: &str) -> bool {
        self.set.contains(key) || self.lines.contains_key(key)
    }
}

/// The 1-based line of every key of a TOML text, as dotted names (`section` and
/// `section.key`); empty if the text does not parse.
pub(super) fn key_lines(text: &str) -> HashMap<String, usize> {
    let line_of = |offset: usize| text[..offset.min(text.len())].matches('\n').count() + 1;
    let mut lines = HashMap::new();
    let Ok(doc) = toml::de::DeTable::parse(text) else {
        return lines;
    };
    for (section, value) in doc.get_ref() {
        lines.insert(section.get_ref().to_string(), line_of(section.span().start));
        if let Some(t) = value.get_ref().as_table() {
            for (key, _) in t {
                lines.insert(
                    format!("{}.{}", section.get_ref(), key.get_ref()),
                    line_of(key.span().start),
                );
            }
        }
    }
    lines
}
