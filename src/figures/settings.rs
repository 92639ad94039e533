//! How `capstan figure` is aimed: the grid, the scene (file and `--set`), and a `--range`
//! that replaces a figure's swept key and values.

use std::path::PathBuf;
use std::str::FromStr;

use crate::error::CliError;
use crate::scene::Scene;

/// `--range KEY=A:B:N`: `N` evenly spaced values of the scene key `KEY` from `A` to `B`
/// (both included).
#[derive(Debug, Clone, PartialEq)]
pub struct FigureRange {
    /// The swept scene key (`table.key`).
    pub key: String,
    /// First value.
    pub from: f64,
    /// Last value.
    pub to: f64,
    /// Number of values, `>= 1`.
    pub steps: usize,
}

impl FromStr for FigureRange {
    type Err = CliError;

    /// Parses `KEY=A:B:N`.
    fn from_str(text: &str) -> Result<Self, CliError> {
        let bad = |why: &str| CliError::Scene {
            origin: "--range".into(),
            message: format!("`{text}`: {why}; expected KEY=A:B:N, e.g. body.poisson=0:0.45:10"),
        };
        let (key, spec) = text.split_once('=').ok_or_else(|| bad("no `=`"))?;
        let key = key.trim();
        if key
            .split_once('.')
            .is_none_or(|(t, k)| t.is_empty() || k.is_empty())
        {
            return Err(bad("KEY must be `table.key`"));
        }
        let parts: Vec<&str> = spec.split(':').map(str::trim).collect();
        let [a, b, n] = parts[..] else {
            return Err(bad("need three fields A:B:N"));
        };
        let number = |x: &str| {
            x.parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| bad("A and B must be finite numbers"))
        };
        let steps = n
            .parse::<usize>()
            .ok()
            .filter(|&n| (1..=10_000).contains(&n))
            .ok_or_else(|| bad("N must be an integer in [1, 10000]"))?;
        Ok(Self {
            key: key.to_owned(),
            from: number(a)?,
            to: number(b)?,
            steps,
        })
    }
}

impl FigureRange {
    /// The values.
    pub fn values(&self) -> Vec<f64> {
        (0..self.steps)
            .map(|i| {
                if self.steps == 1 {
                    self.from
                } else if i + 1 == self.steps {
                    self.to
                } else {
                    self.from + (self.to - self.from) * i as f64 / (self.steps - 1) as f64
                }
            })
            .collect()
    }
}

/// How to run the figures.
///
/// Without a scene file each figure starts from the paper's scene (the default scene, plus
/// the figure's own keys, e.g. the contact interval `[-pi/4, pi/4]` of `tension-ratio`); with
/// one it starts from that file as it is. `--set` then overrides, and `grid` (from `--n2`,
/// `--n3`, `--quick`) overrides the grid last.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct FigureSettings {
    /// `[n2, n3]` forced on every scene (`--n2`, `--n3`, `--quick`); `None`: the scene's grid
    /// (the default scene has the paper's 250 x 41).
    pub grid: Option<[usize; 2]>,
    /// Fewer sweep points (for tests and a first look).
    pub quick: bool,
    /// The scene file, if any.
    pub scene: Option<PathBuf>,
    /// `--set KEY=VALUE` overrides.
    pub sets: Vec<String>,
    /// `--range`: replaces the swept key and values of a sweep figure.
    pub range: Option<FigureRange>,
}

impl FigureSettings {
    /// The paper's scene and grid, full sweeps.
    pub fn paper() -> Self {
        Self::default()
    }

    /// A coarse grid (40 x 9) and short sweeps: seconds, for tests.
    pub fn quick() -> Self {
        Self {
            grid: Some([40, 9]),
            quick: true,
            ..Self::default()
        }
    }

    /// `full` sweep points, or `quick` ones with `--quick`.
    pub(crate) fn steps(&self, full: usize, quick: usize) -> usize {
        if self.quick { quick } else { full }
    }

    /// The overrides of a figure whose own keys are `defaults` (applied only without a scene
    /// file), then `--set`, then the grid.
    pub(crate) fn sets_with(&self, defaults: &[String]) -> Vec<String> {
        let mut sets = if self.scene.is_none() {
            defaults.to_vec()
        } else {
            Vec::new()
        };
        sets.extend(self.sets.iter().cloned());
        if let Some([n2, n3]) = self.grid {
            sets.push(format!("grid.n2={n2}"));
            sets.push(format!("grid.n3={n3}"));
        }
        sets
    }

    /// The scene of a figure whose own keys are `defaults`.
    ///
    /// # Errors
    /// As [`Scene::load`].
    pub(crate) fn scene_with(&self, defaults: &[String]) -> Result<Scene, CliError> {
        Scene::load(self.scene.as_deref(), &self.sets_with(defaults))
    }

    /// The swept key and values: `--range` if given, else the figure's own.
    pub(crate) fn sweep(&self, key: &str, range: (f64, f64), steps: usize) -> (String, Vec<f64>) {
        match &self.range {
            Some(r) => (r.key.clone(), r.values()),
            None => (
                key.to_owned(),
                FigureRange {
                    key: key.to_owned(),
                    from: range.0,
                    to: range.1,
                    steps,
                }
                .values(),
            ),
        }
    }

    /// Whether `--range` replaces the figure's own key.
    pub(crate) fn re_aimed(&self, key: &str) -> bool {
        self.range.as_ref().is_some_and(|r| r.key != key)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn range_parses_key_bounds_and_steps() {
        let r: FigureRange = "body.poisson=0:0.45:10".parse().unwrap();
        assert_eq!(r.key, "body.poisson");
        let v = r.values();
        assert_eq!((v.len(), v[0], v[9]), (10, 0.0, 0.45));
        for bad in [
            "poisson=0:1:3",
            "body.poisson=0:1",
            "body.poisson=0:x:3",
            "a.b=0:1:0",
        ] {
            let e = bad.parse::<FigureRange>().unwrap_err();
            assert!(e.to_string().contains("--range"), "{e}");
        }
    }
}
