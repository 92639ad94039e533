//! `Display` and `FromStr` for the enums chosen by name in scene files.

/// Implements `Display` (the variant's `name()`) and `FromStr` (the variant of `ALL` with that
/// name, else [`SolverError::UnknownName`](crate::SolverError::UnknownName) listing `NAMES`)
/// for an enum with `const ALL`, `const NAMES` and `fn name(self) -> &'static str`.
macro_rules! named_enum {
    ($ty:ty, $kind:literal) => {
        impl core::fmt::Display for $ty {
            fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
                f.write_str(self.name())
            }
        }

        impl core::str::FromStr for $ty {
            type Err = $crate::error::SolverError;

            fn from_str(s: &str) -> Result<Self, Self::Err> {
                Self::ALL
                    .into_iter()
                    .find(|v| v.name() == s)
                    .ok_or_else(|| $crate::error::SolverError::UnknownName {
                        kind: $kind,
                        name: s.to_owned(),
                        allowed: Self::NAMES,
                    })
            }
        }
    };
}

pub(crate) use named_enum;
