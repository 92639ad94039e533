//! Reading a scene: TOML text, `--set` overrides, the known keys, where each key came from.

use super::*;

impl Scene {
    /// Loads a scene from an optional TOML file, applies `--set KEY=VALUE` overrides and
    /// validates every field ([`Scene::validate`]).
    ///
    /// A value is read as a TOML value (`1.5`, `true`, `"text"`); anything that is not valid
    /// TOML is taken as a string, so `--set obstacle.u=2*sin(t)` needs no quotes.
    ///
    /// Errors about a value that came from the file name its line (`scene.toml:12`); values
    /// from `--set` are named as `--set`.
    ///
    /// # Errors
    /// [`CliError::Io`] if the file cannot be read, [`CliError::Scene`] for malformed TOML,
    /// unknown keys, wrong types or values outside their allowed range (naming the key, the
    /// value and the range), [`CliError::Set`] for a malformed override.
    pub fn load(path: Option<&Path>, sets: &[String]) -> Result<Self, CliError> {
        let file = match path {
            Some(p) => {
                let text = std::fs::read_to_string(p).map_err(|source| {
                    if source.kind() == std::io::ErrorKind::InvalidData {
                        CliError::Scene {
                            origin: p.display().to_string(),
                            message: "not a text file (a TOML scene must be UTF-8)".into(),
                        }
                    } else {
                        CliError::Io {
                            path: p.display().to_string(),
                            source,
                        }
                    }
                })?;
                Some((p.display().to_string(), text))
            }
            None => None,
        };
        Self::from_text(file.as_ref().map(|(n, t)| (n.as_str(), t.as_str())), sets)
    }

    /// [`Scene::load`] on the text of a scene file already read: `file` is `(name, text)`,
    /// the name used in error messages (`name:line`).
    ///
    /// # Errors
    /// As [`Scene::load`], without the I/O errors.
    ///
    /// # Example
    /// ```
    /// use capstan::scene::Scene;
    /// let s = Scene::from_text(Some(("s.toml", "[friction]\nmu = 0.3\n")), &["membrane.t0=2".into()]).unwrap();
    /// assert_eq!((s.friction.mu, s.membrane.t0), (0.3, 2.0));
    /// ```
    pub fn from_text(file: Option<(&str, &str)>, sets: &[String]) -> Result<Self, CliError> {
        let mut origins = Origins::default();
        let mut text = "";
        let mut table = match file {
            Some((name, file_text)) => {
                text = file_text;
                origins.file = Some(name.to_string());
                let table = text.parse::<toml::Table>().map_err(|e| CliError::Scene {
                    origin: name.to_string(),
                    message: e.to_string(),
                })?;
                origins.lines = key_lines(text);
                table
            }
            None => toml::Table::new(),
        };
        for set in sets {
            let key = apply_set(&mut table, set)?;
            origins.set.insert(key);
        }
        check_known_keys(&table, &origins)?;
        let scene = match Scene::deserialize(toml::Value::Table(table)) {
            Ok(scene) => scene,
            Err(e) => {
                // The merged table carries no spans: when the file alone is already wrong,
                // report the file's error, which points to the line.
                if let Some(file) = &origins.file
                    && let Err(file_error) = toml::from_str::<Scene>(text)
                {
                    return Err(CliError::Scene {
                        origin: file.clone(),
                        message: file_error.to_string(),
                    });
                }
                let origin = if sets.is_empty() {
                    origins.file.clone().unwrap_or_else(|| "scene".into())
                } else {
                    "--set".into()
                };
                return Err(CliError::Scene {
                    origin,
                    message: e.to_string(),
                });
            }
        };
        scene.validate_with(&origins)?;
        Ok(scene)
    }
}

/// Every key a scene accepts, as dotted names (from the defaults, plus optional keys).
pub fn known_keys() -> Vec<String> {
    let table = toml::Table::try_from(Scene::default()).expect("the default scene serialises");
    let mut keys = vec![
        "membrane.t_max".to_string(),
        "solver.max_sweeps".to_string(),
    ];
    for law in capstan_friction::registry::registry() {
        keys.extend(law.parameters.iter().map(|p| format!("friction.{p}")));
    }
    for (section, value) in &table {
        if let toml::Value::Table(t) = value {
            keys.extend(t.keys().map(|k| format!("{section}.{k}")));
        }
    }
    keys.sort();
    keys.dedup();
    keys
}

fn check_known_keys(table: &toml::Table, origins: &Origins) -> Result<(), CliError> {
    let known = known_keys();
    for (section, value) in table {
        let toml::Value::Table(t) = value else {
            return Err(CliError::Scene {
                origin: origins.locate(section),
                message: format!("`{section}` must be a table such as [{section}]"),
            });
        };
        for key in t.keys() {
            let dotted = format!("{section}.{key}");
            if !known.contains(&dotted) {
                let hint: Vec<&str> = known
                    .iter()
                    .filter(|k| k.starts_with(&format!("{section}.")))
                    .map(String::as_str)
                    .collect();
                return Err(CliError::Scene {
                    origin: origins.locate(&dotted),
                    message: if hint.is_empty() {
                        format!("unknown key `{dotted}` (unknown table `[{section}]`)")
                    } else {
                        format!(
                            "unknown key `{dotted}`; expected one of {}",
                            hint.join(", ")
                        )
                    },
                });
            }
        }
    }
    Ok(())
}

/// Applies one `--set KEY=VALUE`; returns the dotted key.
fn apply_set(table: &mut toml::Table, set: &str) -> Result<String, CliError> {
    let bad = |why: &str| CliError::Set {
        set: set.to_string(),
        message: why.to_string(),
    };
    let (key, raw) = set
        .split_once('=')
        .ok_or_else(|| bad("expected KEY=VALUE"))?;
    let key = key.trim();
    let (section, field) = key
        .split_once('.')
        .ok_or_else(|| bad("KEY must be `table.key`, e.g. obstacle.radius"))?;
    if section.is_empty() || field.is_empty() || field.contains('.') {
        return Err(bad("KEY must be `table.key`, e.g. obstacle.radius"));
    }
    let raw = raw.trim();
    let value = format!("v = {raw}")
        .parse::<toml::Table>()
        .ok()
        .and_then(|mut t| t.remove("v"))
        .unwrap_or_else(|| toml::Value::String(raw.to_string()));
    let entry = table
        .entry(section.to_string())
        .or_insert_with(|| toml::Value::Table(toml::Table::new()));
    let toml::Value::Table(t) = entry else {
        return Err(bad("that table is not a table in the scene file"));
    };
    t.insert(field.to_string(), value);
    Ok(format!("{section}.{field}"))
}

/// Where each key's value came from, for error messages: a line of the scene file, `--set`,
/// or the built-in default.
#[derive(Debug, Clone, Default)]
pub struct Origins {
    /// The scene file, if any.
    file: Option<String>,
    /// 1-based line of each dotted key in the file.
    lines: HashMap<String, usize>,
    /// Dotted keys given by `--set` (they override the file).
    set: HashSet<String>,
}

impl Origins {
    /// `file:line` for a key from the file, `--set` for an override, else
    /// `(built-in default)` (a default or a scene built in code).
    pub fn locate(&self, key: &str) -> String {
        if self.set.contains(key) {
            return "--set".into();
        }
        match (&self.file, self.lines.get(key)) {
            (Some(file), Some(line)) => format!("{file}:{line}"),
            (Some(file), None) if !key.contains('.') => file.clone(),
            _ => "(built-in default)".into(),
        }
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
