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

#[cfg(test)]
mod tests {
    use core::fmt::{Debug, Display};
    use core::str::FromStr;

    use crate::{LinearBackend, NonlinearMethod, SolverError};

    fn assert_round_trip<T>(all: impl IntoIterator<Item = T>, name: fn(T) -> &'static str)
    where
        T: Copy + Debug + Display + FromStr<Err = SolverError> + PartialEq,
        T: serde::Serialize + serde::de::DeserializeOwned,
    {
        for v in all {
            assert_eq!(v.to_string().parse::<T>().unwrap(), v);
            let json = serde_json::to_string(&v).unwrap();
            assert_eq!(json, format!("\"{}\"", name(v)));
            assert_eq!(serde_json::from_str::<T>(&json).unwrap(), v);
        }
        assert!(matches!(
            "broyden".parse::<T>(),
            Err(SolverError::UnknownName { .. })
        ));
    }

    #[test]
    fn names_round_trip_through_display_fromstr_and_serde() {
        assert_round_trip(LinearBackend::ALL, LinearBackend::name);
        assert_round_trip(NonlinearMethod::ALL, NonlinearMethod::name);
    }
}
