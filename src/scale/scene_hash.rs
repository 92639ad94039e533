//! A small stable hash (64-bit FNV-1a) of the canonical serialised scene and sweep grid.

use serde::Serialize;

use crate::scene::Scene;

/// 64-bit FNV-1a: stable across platforms, versions and runs (unlike `std`'s `DefaultHasher`).
///
/// # Math
/// ```text
/// h_0 = 0xcbf29ce484222325;  h_{i+1} = (h_i xor byte_i) * 0x100000001b3  (mod 2^64)
/// ```
///
/// # Example
/// ```
/// use capstan::scale::Fnv1a64;
/// assert_eq!(Fnv1a64::hash(b""), 0xcbf2_9ce4_8422_2325);
/// assert_eq!(Fnv1a64::hash(b"a"), 0xaf63_dc4c_8601_ec8c); // published test vector
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Fnv1a64(u64);

impl Default for Fnv1a64 {
    fn default() -> Self {
        Self(0xcbf2_9ce4_8422_2325)
    }
}

impl Fnv1a64 {
    /// Feeds bytes.
    pub fn update(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = (self.0 ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3);
        }
    }

    /// The hash so far.
    pub fn finish(self) -> u64 {
        self.0
    }

    /// The hash of `bytes`.
    pub fn hash(bytes: &[u8]) -> u64 {
        let mut h = Self::default();
        h.update(bytes);
        h.finish()
    }
}

/// What the hash covers, serialised as compact JSON in this field order.
#[derive(Serialize)]
struct Canonical<'a> {
    format: &'static str,
    scene: &'a Scene,
    param: &'a str,
    values: &'a [f64],
}

/// The hash of a sweep: the resolved scene (file plus `--set`s, every key with its value),
/// the swept key and the whole grid, as `fnv1a64:` and 16 hex digits.
///
/// Floats are written by serde_json's shortest round-trip form, so equal inputs give equal
/// bytes on every platform.
///
/// # Errors
/// Only if the scene cannot be serialised (a non-finite number: serde_json refuses none,
/// writes `null`, so in practice never).
pub fn sweep_hash(scene: &Scene, param: &str, values: &[f64]) -> Result<String, serde_json::Error> {
    let bytes = serde_json::to_vec(&Canonical {
        format: "capstan-sweep/1",
        scene,
        param,
        values,
    })?;
    Ok(format!("fnv1a64:{:016x}", Fnv1a64::hash(&bytes)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fnv1a64_matches_published_vectors() {
        assert_eq!(Fnv1a64::hash(b"foobar"), 0x8594_4171_f739_67e8);
    }

    #[test]
    fn sweep_hash_depends_on_scene_param_and_grid() {
        let s = Scene::default();
        let h = sweep_hash(&s, "body.poisson", &[0.1, 0.2]).unwrap();
        assert_eq!(h, sweep_hash(&s, "body.poisson", &[0.1, 0.2]).unwrap());
        assert_ne!(h, sweep_hash(&s, "body.poisson", &[0.1, 0.3]).unwrap());
        assert_ne!(h, sweep_hash(&s, "body.young", &[0.1, 0.2]).unwrap());
        let mut t = s.clone();
        t.grid.n2 += 1;
        assert_ne!(h, sweep_hash(&t, "body.poisson", &[0.1, 0.2]).unwrap());
    }
}
