//! `capstan sweep --shard I/N` parts and `capstan merge`.

use std::path::{Path, PathBuf};
use std::str::FromStr;

use serde::{Deserialize, Serialize};

use super::scene_hash::sweep_hash;
use crate::commands::sweep::{SweepPoint, SweepReport};
use crate::error::CliError;
use crate::scene::Scene;
use crate::shard_error::ShardError;

/// `--shard I/N`: the `I`-th (1-based) of `N` interleaved parts of a sweep.
///
/// # Example
/// ```
/// use capstan::scale::ShardSpec;
/// let s: ShardSpec = "2/3".parse().unwrap();
/// assert_eq!(s.indices(8), vec![1, 4, 7]); // 0-based points k with k % 3 == 2 - 1
/// assert!("0/3".parse::<ShardSpec>().is_err());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct ShardSpec {
    /// `I`, 1-based.
    pub index: usize,
    /// `N`.
    pub count: usize,
}

impl FromStr for ShardSpec {
    type Err = ShardError;
    fn from_str(s: &str) -> Result<Self, ShardError> {
        let bad = || ShardError::InvalidSpec { spec: s.to_owned() };
        let (i, n) = s.split_once('/').ok_or_else(bad)?;
        let index: usize = i.trim().parse().map_err(|_| bad())?;
        let count: usize = n.trim().parse().map_err(|_| bad())?;
        if index == 0 || index > count {
            return Err(bad());
        }
        Ok(Self { index, count })
    }
}

impl ShardSpec {
    /// Whether 0-based point `k` belongs to this shard: `k % N == I - 1`.
    pub fn owns(&self, k: usize) -> bool {
        k % self.count == self.index - 1
    }

    /// The 0-based points of a sweep of `steps` points that belong to this shard.
    pub fn indices(&self, steps: usize) -> Vec<usize> {
        (self.index - 1..steps).step_by(self.count).collect()
    }
}

/// The file name of a part: `shard-I-of-N.json`.
pub fn shard_file_name(spec: ShardSpec) -> String {
    format!("shard-{}-of-{}.json", spec.index, spec.count)
}

/// The `format` of a part file.
const FORMAT: &str = "capstan-sweep-part";
/// Its version.
const VERSION: u32 = 1;

/// One part of a sharded sweep (`shard-I-of-N.json`): self-describing, so parts can be
/// checked and merged anywhere.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ShardFile {
    /// `capstan-sweep-part`.
    pub format: String,
    /// `1`.
    pub version: u32,
    /// [`sweep_hash`] of the scene, key and grid.
    pub scene_hash: String,
    /// The swept key.
    pub param: String,
    /// The whole grid (every shard's points).
    pub values: Vec<f64>,
    /// Which part this is.
    pub shard: ShardSpec,
    /// The 0-based grid points held here, ascending.
    pub indices: Vec<usize>,
    /// The results at `indices`, in the same order.
    pub points: Vec<SweepPoint>,
    /// As in [`SweepReport`].
    pub shared_factorisation: bool,
    /// Wall time of this part, seconds.
    pub seconds: f64,
    /// The resolved scene (for the record; the hash is what is checked).
    pub scene: serde_json::Value,
}

/// Runs the part `spec` of the sweep of `key` over `values` (the whole grid).
///
/// A part may hold no points (`N` larger than the grid); it is still written, so the merge
/// sees that shard. With `fields`, the body fields of each converged point go there as
/// `points/point_NNNN.vtu`, numbered in the whole grid (the merge collects them).
///
/// # Errors
/// As [`crate::commands::sweep::report`]; [`CliError::Output`] if the scene cannot be
/// serialised for the hash.
pub fn run_shard(
    path: Option<&Path>,
    sets: &[String],
    key: &str,
    values: &[f64],
    spec: ShardSpec,
    fields: Option<&crate::output::OutputDir>,
) -> Result<ShardFile, CliError> {
    let scene = Scene::load(path, sets)?;
    let hash = sweep_hash(&scene, key, values).map_err(crate::output::OutputError::Json)?;
    let indices = spec.indices(values.len());
    let subset: Vec<f64> = indices.iter().map(|&k| values[k]).collect();
    let (points, shared, seconds) = if subset.is_empty() {
        // Still check the key, as a non-empty part would.
        let mut s = sets.to_vec();
        s.push(format!("{key}={}", values.first().copied().unwrap_or(0.0)));
        Scene::load(path, &s)?;
        (
            Vec::new(),
            key == "loads.tau_max" || key == "loads.tau0",
            0.0,
        )
    } else {
        let at = crate::commands::sweep::SweepPoints {
            key,
            values: &subset,
            fields,
            index: &|i| indices[i],
        };
        let r = crate::commands::sweep::report_indexed(path, sets, at)?;
        (r.points, r.shared_factorisation, r.seconds)
    };
    Ok(ShardFile {
        format: FORMAT.into(),
        version: VERSION,
        scene_hash: hash,
        param: key.to_owned(),
        values: values.to_vec(),
        shard: spec,
        indices,
        points,
        shared_factorisation: shared,
        seconds,
        scene: serde_json::to_value(&scene).map_err(crate::output::OutputError::Json)?,
    })
}

/// Reads the parts: every `shard-*-of-*.json` in each directory (sorted by name), or each
/// file given directly.
///
/// # Errors
/// [`CliError::Io`] for unreadable paths; [`ShardError::Malformed`] for a file that is not a
/// part; [`ShardError::NoParts`] when nothing is found.
pub fn read_parts(inputs: &[PathBuf]) -> Result<Vec<(String, ShardFile)>, CliError> {
    let io = |p: &Path| {
        let p = p.display().to_string();
        move |source| CliError::Io { path: p, source }
    };
    let mut files = Vec::new();
    for input in inputs {
        if input.is_dir() {
            let mut found: Vec<PathBuf> = std::fs::read_dir(input)
                .map_err(io(input))?
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| {
                    p.file_name()
                        .and_then(|n| n.to_str())
                        .is_some_and(|n| n.starts_with("shard-") && n.ends_with(".json"))
                })
                .collect();
            found.sort();
            files.extend(found);
        } else {
            files.push(input.clone());
        }
    }
    if files.is_empty() {
        return Err(ShardError::NoParts {
            dirs: inputs
                .iter()
                .map(|p| p.display().to_string())
                .collect::<Vec<_>>()
                .join(", "),
        }
        .into());
    }
    files
        .into_iter()
        .map(|f| {
            let text = std::fs::read_to_string(&f).map_err(io(&f))?;
            let name = f.display().to_string();
            let malformed = |reason: String| ShardError::Malformed {
                path: name.clone(),
                reason,
            };
            let part: ShardFile =
                serde_json::from_str(&text).map_err(|e| malformed(e.to_string()))?;
            if part.format != FORMAT || part.version != VERSION {
                return Err(malformed(format!(
                    "format {} version {}, expected {FORMAT} version {VERSION}",
                    part.format, part.version
                ))
                .into());
            }
            Ok((name, part))
        })
        .collect()
}

/// Checks that `parts` belong together and cover the grid exactly once, and rebuilds the
/// report of the unsharded sweep (points in grid order; `seconds` is the longest part's).
///
/// # Errors
/// [`ShardError::GridMismatch`], [`ShardError::HashMismatch`], [`ShardError::CountMismatch`]
/// for parts that do not belong together; [`ShardError::Malformed`] for a part whose points
/// are not those of its shard; [`ShardError::DuplicatePoints`] and
/// [`ShardError::MissingPoints`] naming the 0-based points; [`ShardError::NoParts`].
pub fn merge(parts: &[(String, ShardFile)]) -> Result<SweepReport, ShardError> {
    let Some((first_name, first)) = parts.first() else {
        return Err(ShardError::NoParts {
            dirs: String::new(),
        });
    };
    let describe =
        |p: &ShardFile| format!("{} over {} points {:?}", p.param, p.values.len(), p.values);
    let steps = first.values.len();
    let mut owner: Vec<Option<&str>> = vec![None; steps];
    let mut duplicates = Vec::new();
    let mut duplicate_paths: Option<[String; 2]> = None;
    let mut seconds = 0.0f64;
    for (name, part) in parts {
        let same_grid = part.param == first.param
            && part.values.len() == steps
            && part
                .values
                .iter()
                .zip(&first.values)
                .all(|(a, b)| a.to_bits() == b.to_bits());
        if !same_grid {
            return Err(ShardError::GridMismatch {
                path: name.clone(),
                found: describe(part),
                first: first_name.clone(),
                expected: describe(first),
            });
        }
        if part.scene_hash != first.scene_hash {
            return Err(ShardError::HashMismatch {
                path: name.clone(),
                found: part.scene_hash.clone(),
                first: first_name.clone(),
                expected: first.scene_hash.clone(),
            });
        }
        if part.shard.count != first.shard.count {
            return Err(ShardError::CountMismatch {
                path: name.clone(),
                found: part.shard.count,
                first: first_name.clone(),
                expected: first.shard.count,
            });
        }
        let malformed = |reason: String| ShardError::Malformed {
            path: name.clone(),
            reason,
        };
        if part.shard.index == 0 || part.shard.index > part.shard.count {
            return Err(malformed(format!(
                "shard {}/{} out of range",
                part.shard.index, part.shard.count
            )));
        }
        if part.indices != part.shard.indices(steps) || part.points.len() != part.indices.len() {
            return Err(malformed(format!(
                "holds points {:?} ({} results), but shard {}/{} of {steps} points is {:?}",
                part.indices,
                part.points.len(),
                part.shard.index,
                part.shard.count,
                part.shard.indices(steps)
            )));
        }
        for (&k, p) in part.indices.iter().zip(&part.points) {
            if p.value.to_bits() != part.values[k].to_bits() {
                return Err(malformed(format!(
                    "point {k} has value {}, the grid says {}",
                    p.value, part.values[k]
                )));
            }
            match owner[k] {
                Some(other) => {
                    duplicates.push(k);
                    duplicate_paths.get_or_insert_with(|| [other.to_owned(), name.clone()]);
                }
                None => owner[k] = Some(name),
            }
        }
        seconds = seconds.max(part.seconds);
    }
    if let Some(paths) = duplicate_paths {
        duplicates.sort_unstable();
        duplicates.dedup();
        return Err(ShardError::DuplicatePoints {
            indices: duplicates,
            paths,
        });
    }
    let missing: Vec<usize> = (0..steps).filter(|&k| owner[k].is_none()).collect();
    if !missing.is_empty() {
        let mut shards: Vec<usize> = missing.iter().map(|k| k % first.shard.count + 1).collect();
        shards.sort_unstable();
        shards.dedup();
        return Err(ShardError::MissingPoints {
            values: missing.iter().map(|&k| first.values[k]).collect(),
            indices: missing,
            shards,
            count: first.shard.count,
        });
    }
    let mut points: Vec<Option<SweepPoint>> = vec![None; steps];
    for (_, part) in parts {
        for (&k, p) in part.indices.iter().zip(&part.points) {
            points[k] = Some(p.clone());
        }
    }
    Ok(SweepReport {
        param: first.param.clone(),
        points: points
            .into_iter()
            .map(|p| p.expect("covered once"))
            .collect(),
        shared_factorisation: first.shared_factorisation,
        seconds,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(value: f64) -> SweepPoint {
        SweepPoint {
            value,
            status: crate::commands::sweep::PointStatus::Converged,
            converged: true,
            slip_fraction: Some(0.25),
            newton_iterations: Some(4),
            stick_interval: Some([-0.5, 0.5]),
            max_azimuthal_displacement: Some(capstan_elasticity::contact::Extremum {
                value: 1e-3,
                x1: None,
                x2: 0.1,
                x3: 0.0,
            }),
            max_radial_displacement: None,
            tension_ratio: 2.0,
            error: None,
            accuracy: None,
        }
    }

    #[test]
    fn a_sweep_point_round_trips_through_json_and_an_unknown_status_is_refused() {
        let p = point(0.3);
        let json = serde_json::to_string(&p).unwrap();
        let back: SweepPoint = serde_json::from_str(&json).unwrap();
        assert_eq!(back, p);
        assert_eq!(serde_json::to_string(&back).unwrap(), json);
        let bad = json.replace("\"converged\",", "\"diverged\",");
        assert_ne!(bad, json);
        let e = serde_json::from_str::<SweepPoint>(&bad).unwrap_err();
        assert!(e.to_string().contains("diverged"), "{e}");
    }

    #[test]
    fn shard_spec_rejects_bad_forms_and_partitions_the_grid() {
        for bad in ["", "1", "0/2", "3/2", "a/2", "1/0", "-1/2"] {
            assert!(bad.parse::<ShardSpec>().is_err(), "{bad}");
        }
        let steps = 10;
        let mut seen = vec![0; steps];
        for i in 1..=3 {
            let s = ShardSpec { index: i, count: 3 };
            for k in s.indices(steps) {
                assert!(s.owns(k));
                seen[k] += 1;
            }
        }
        assert!(seen.iter().all(|&c| c == 1));
        assert!(ShardSpec { index: 5, count: 5 }.indices(3).is_empty());
    }

    fn part(index: usize, count: usize, values: &[f64]) -> (String, ShardFile) {
        let spec = ShardSpec { index, count };
        let indices = spec.indices(values.len());
        (
            format!("p{index}"),
            ShardFile {
                format: FORMAT.into(),
                version: VERSION,
                scene_hash: "fnv1a64:0".into(),
                param: "body.poisson".into(),
                values: values.to_vec(),
                shard: spec,
                points: indices.iter().map(|&k| point(values[k])).collect(),
                indices,
                shared_factorisation: false,
                seconds: index as f64,
                scene: serde_json::Value::Null,
            },
        )
    }

    #[test]
    fn merge_names_missing_and_duplicate_points() {
        let v = [0.1, 0.2, 0.3, 0.4, 0.5];
        let all = [part(1, 2, &v), part(2, 2, &v)];
        let r = merge(&all).unwrap();
        assert_eq!(r.points.iter().map(|p| p.value).collect::<Vec<_>>(), v);
        assert_eq!(r.seconds, 2.0);
        match merge(&all[..1]) {
            Err(ShardError::MissingPoints {
                indices, shards, ..
            }) => {
                assert_eq!((indices, shards), (vec![1, 3], vec![2]));
            }
            other => panic!("{other:?}"),
        }
        match merge(&[all[0].clone(), all[1].clone(), all[0].clone()]) {
            Err(ShardError::DuplicatePoints { indices, .. }) => assert_eq!(indices, vec![0, 2, 4]),
            other => panic!("{other:?}"),
        }
        let mut other_scene = all[1].clone();
        other_scene.1.scene_hash = "fnv1a64:1".into();
        assert!(matches!(
            merge(&[all[0].clone(), other_scene]),
            Err(ShardError::HashMismatch { .. })
        ));
        assert!(matches!(
            merge(&[all[0].clone(), part(2, 3, &v)]),
            Err(ShardError::CountMismatch { .. })
        ));
        assert!(matches!(
            merge(&[all[0].clone(), part(2, 2, &v[..4])]),
            Err(ShardError::GridMismatch { .. })
        ));
    }
}
