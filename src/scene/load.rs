//! Reading a scene: TOML text, `--set` overrides, the known keys, where each key came from.

use std::path::Path;

use serde::Deserialize;

use super::origins::{Origins, key_lines};
use super::{Scene, known_keys};
use crate::error::CliError;

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
        match path {
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
                Self::from_text(Some((&text, &p.display().to_string())), sets)
            }
            None => Self::from_text(None, sets),
        }
    }

    /// A scene from TOML text (as a scene file holds it) and `KEY=VALUE` overrides; errors
    /// name the key as [`Scene::load`] does, with `origin` in place of the file name.
    ///
    /// # Example
    /// ```
    /// use capstan::Scene;
    /// let s = Scene::from_toml_str("[body]\npoisson = 0.3\n", "scene", &["grid.n2=41".into()]).unwrap();
    /// assert_eq!((s.body.poisson, s.grid.n2), (0.3, 41));
    /// let e = Scene::from_toml_str("[body]\npoisson = 0.7\n", "scene", &[]).unwrap_err();
    /// assert!(e.to_string().contains("body.poisson"), "{e}");
    /// ```
    ///
    /// # Errors
    /// As [`Scene::load`] (no I/O).
    pub fn from_toml_str(text: &str, origin: &str, sets: &[String]) -> Result<Self, CliError> {
        Self::from_text(Some((text, origin)), sets)
    }

    /// This scene with one key replaced: `key` is `table.key`, `value` any TOML value; the
    /// result is checked and validated as a `--set` is (`label` names the change in errors,
    /// e.g. `--set` or `Scene.set`). Keys pass through generically: any key the scene knows.
    ///
    /// # Example
    /// ```
    /// use capstan::Scene;
    /// let s = Scene::default().with_value("body.poisson", toml::Value::Float(0.3), "set").unwrap();
    /// assert_eq!(s.body.poisson, 0.3);
    /// let e = s.with_value("body.poissons", toml::Value::Float(0.3), "set").unwrap_err();
    /// assert!(e.to_string().contains("body.poissons"), "{e}");
    /// ```
    ///
    /// # Errors
    /// As [`Scene::load`]: an unknown key, a wrong type or a value outside its range.
    pub fn with_value(&self, key: &str, value: toml::Value, label: &str) -> Result<Self, CliError> {
        let mut table = self.to_table()?;
        let key = insert_dotted(&mut table, key, value).map_err(|message| CliError::Scene {
            origin: label.into(),
            message,
        })?;
        let mut origins = Origins {
            label: Some(label.to_owned()),
            ..Origins::default()
        };
        origins.set.insert(key);
        Self::resolve(table, &origins, None, label)
    }

    /// This scene with `key` set to `raw` read as `--set key=raw` reads it (a TOML value, or
    /// else a string): a sweep point of `capstan sweep`.
    ///
    /// # Errors
    /// As [`Scene::with_value`].
    pub fn with_raw(&self, key: &str, raw: &str, label: &str) -> Result<Self, CliError> {
        self.with_value(key, set_value(raw), label)
    }

    /// A scene from a table of tables (`{section: {key: value}}`), as a TOML document parses;
    /// checked and validated as a scene file (`origin` names it in errors).
    ///
    /// # Errors
    /// As [`Scene::load`].
    pub fn from_table(table: toml::Table, origin: &str) -> Result<Self, CliError> {
        let mut origins = Origins {
            label: Some(origin.to_owned()),
            ..Origins::default()
        };
        for (section, value) in &table {
            origins.set.insert(section.clone());
            if let toml::Value::Table(t) = value {
                origins
                    .set
                    .extend(t.keys().map(|k| format!("{section}.{k}")));
            }
        }
        Self::resolve(table, &origins, None, origin)
    }

    /// The resolved scene as a TOML table (every key, defaults filled in).
    ///
    /// # Errors
    /// [`CliError::Scene`] if the scene does not serialise (it always does).
    pub fn to_table(&self) -> Result<toml::Table, CliError> {
        toml::Table::try_from(self).map_err(|e| CliError::Scene {
            origin: "scene".into(),
            message: format!("the resolved scene does not serialise to TOML: {e}"),
        })
    }

    /// [`Scene::load`] on the text of a scene file already read: `text` is `(text, origin)`,
    /// the origin (a file name) used in error messages (`origin:line`), and `sets` the
    /// `KEY=VALUE` overrides.
    ///
    /// # Errors
    /// As [`Scene::load`], without the I/O errors.
    ///
    /// # Example
    /// ```
    /// use capstan::scene::Scene;
    /// let s = Scene::from_text(Some(("[friction]\nmu = 0.3\n", "s.toml")), &["membrane.t0=2".into()]).unwrap();
    /// assert_eq!((s.friction.mu, s.membrane.t0), (0.3, 2.0));
    /// ```
    pub fn from_text(text: Option<(&str, &str)>, sets: &[String]) -> Result<Self, CliError> {
        let mut origins = Origins::default();
        let mut table = match text {
            Some((text, origin)) => {
                origins.file = Some(origin.to_owned());
                let table = text.parse::<toml::Table>().map_err(|e| CliError::Scene {
                    origin: origin.to_owned(),
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
        let fallback = if sets.is_empty() {
            origins.file.clone().unwrap_or_else(|| "scene".into())
        } else {
            "--set".into()
        };
        Self::resolve(table, &origins, text.map(|(t, _)| t), &fallback)
    }

    /// Checks the keys, deserialises and validates `table`; `text` is the file's own text
    /// (for an error pointing to its line), `origin` names a type error otherwise.
    fn resolve(
        table: toml::Table,
        origins: &Origins,
        text: Option<&str>,
        origin: &str,
    ) -> Result<Self, CliError> {
        check_known_keys(&table, origins)?;
        let mut scene = match Scene::deserialize(toml::Value::Table(table)) {
            Ok(scene) => scene,
            Err(e) => {
                // The merged table carries no spans: when the file alone is already wrong,
                // report the file's error, which points to the line.
                if let (Some(file), Some(text)) = (&origins.file, text)
                    && let Err(file_error) = toml::from_str::<Scene>(text)
                {
                    return Err(CliError::Scene {
                        origin: file.clone(),
                        message: file_error.to_string(),
                    });
                }
                return Err(CliError::Scene {
                    origin: origin.to_owned(),
                    message: e.to_string(),
                });
            }
        };
        scene.follow_defaults(origins);
        scene.validate_with(origins)?;
        Ok(scene)
    }
}

/// Inserts `value` at the dotted `key` (`table.key`) of `table`; returns the key.
fn insert_dotted(table: &mut toml::Table, key: &str, value: toml::Value) -> Result<String, String> {
    let key = key.trim();
    let (section, field) = key
        .split_once('.')
        .filter(|(s, f)| !s.is_empty() && !f.is_empty() && !f.contains('.'))
        .ok_or_else(|| format!("key `{key}` must be `table.key`, e.g. obstacle.radius"))?;
    let entry = table
        .entry(section.to_string())
        .or_insert_with(|| toml::Value::Table(toml::Table::new()));
    let toml::Value::Table(t) = entry else {
        return Err(format!("`{section}` is not a table in the scene"));
    };
    t.insert(field.to_string(), value);
    Ok(format!("{section}.{field}"))
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

/// The value of a `--set KEY=VALUE`: `raw` read as a TOML value, or else taken as a string.
pub(super) fn set_value(raw: &str) -> toml::Value {
    let raw = raw.trim();
    format!("v = {raw}")
        .parse::<toml::Table>()
        .ok()
        .and_then(|mut t| t.remove("v"))
        .unwrap_or_else(|| toml::Value::String(raw.to_string()))
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
    let value = set_value(raw);
    let entry = table
        .entry(section.to_string())
        .or_insert_with(|| toml::Value::Table(toml::Table::new()));
    let toml::Value::Table(t) = entry else {
        return Err(bad("that table is not a table in the scene file"));
    };
    t.insert(field.to_string(), value);
    Ok(format!("{section}.{field}"))
}
