//! Names for the enums chosen by name in scene files: `ALL`, `NAMES`, `name`, `from_name`
//! and `Display` from one table ([`named_variants!`](crate::named_variants)), and `FromStr`
//! with a typed error for the solver enums.

/// Defines, for a fieldless enum chosen by name in scene files, from one table of
/// `Variant => "name"`: `ALL` (every variant, in the table's order), `NAMES` (the accepted
/// spellings for messages, `` `a`, `b` ``), `name(self)` (the spelling in files),
/// `from_name(&str) -> Option<Self>` and `Display` (the name).
///
/// # Example
/// ```
/// #[derive(Clone, Copy, Debug, PartialEq)]
/// enum Smoother { Jacobi, GaussSeidel }
/// capstan_solvers::named_variants!(Smoother { Jacobi => "jacobi", GaussSeidel => "gauss-seidel" });
/// assert_eq!(Smoother::NAMES, "`jacobi`, `gauss-seidel`");
/// assert_eq!(Smoother::from_name("gauss-seidel"), Some(Smoother::GaussSeidel));
/// assert_eq!(Smoother::ALL.map(|s| s.to_string()), ["jacobi", "gauss-seidel"]);
/// ```
#[macro_export]
macro_rules! named_variants {
    ($ty:ident { $first:ident => $first_name:literal $(, $variant:ident => $name:literal)* $(,)? }) => {
        impl $ty {
            /// Every variant, in declaration order.
            pub const ALL: [Self; 1 $(+ $crate::named_variants!(@one $variant))*] =
                [Self::$first $(, Self::$variant)*];

            /// The accepted spellings, for messages.
            pub const NAMES: &'static str =
                concat!("`", $first_name, "`" $(, ", `", $name, "`")*);

            /// The name as used in files.
            pub fn name(self) -> &'static str {
                match self {
                    Self::$first => $first_name,
                    $(Self::$variant => $name,)*
                }
            }

            /// The variant of a name, `None` if unknown.
            pub fn from_name(name: &str) -> Option<Self> {
                Self::ALL.into_iter().find(|v| v.name() == name)
            }
        }

        impl core::fmt::Display for $ty {
            fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
                f.write_str(self.name())
            }
        }
    };
    (@one $variant:ident) => {
        1
    };
}

/// Implements `FromStr` ([`named_variants!`](crate::named_variants)' `from_name`, else
/// [`SolverError::UnknownName`](crate::SolverError::UnknownName) listing `NAMES`).
macro_rules! named_enum {
    ($ty:ty, $kind:literal) => {
        impl core::str::FromStr for $ty {
            type Err = $crate::error::SolverError;

            fn from_str(s: &str) -> Result<Self, Self::Err> {
                Self::from_name(s).ok_or_else(|| $crate::error::SolverError::UnknownName {
                    kind: $kind,
                    name: s.to_owned(),
                    allowed: Self::NAMES.to_owned(),
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

    use crate::{NonlinearMethod, SolverError};

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
        assert_round_trip(NonlinearMethod::ALL, NonlinearMethod::name);
    }
}
