//! Errors of parsing and checking an expression.

/// The functions callable from an expression, in the order listed in error messages.
const FUNCTION_NAMES: &str =
    "sin, cos, tan, exp, ln, sqrt, abs, sinh, cosh, tanh, atan, cot, sec, csc";

/// An error from parsing an expression or from checking it on an interval.
///
/// Positions are byte offsets into the source text, starting at 0.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ExpressionError {
    /// The source text is longer than [`MAX_LENGTH`](super::MAX_LENGTH).
    #[error("expression is {length} bytes long; the limit is {limit} bytes")]
    TooLong {
        /// Length of the source text in bytes.
        length: usize,
        /// The limit, [`MAX_LENGTH`](super::MAX_LENGTH).
        limit: usize,
    },
    /// The source text is empty or only whitespace.
    #[error("expression is empty")]
    Empty,
    /// A character that is not part of the grammar.
    #[error("unexpected character `{found}` at byte {position}")]
    UnexpectedCharacter {
        /// Byte offset of the character.
        position: usize,
        /// The character.
        found: char,
    },
    /// An operand (number, `t`, constant, function call or `(`) was expected.
    #[error(
        "expected a number, `t`, `pi`, `e`, a function call or `(` at byte {position}, found {}",
        describe(*found)
    )]
    ExpectedOperand {
        /// Byte offset where the operand should start.
        position: usize,
        /// What was found instead (`None` at the end of the input).
        found: Option<char>,
    },
    /// A name that is neither the variable nor a constant.
    #[error(
        "unknown identifier `{name}` at byte {position}; the variable is `t` and the constants \
         are `pi` and `e`"
    )]
    UnknownIdentifier {
        /// Byte offset of the name.
        position: usize,
        /// The name.
        name: String,
    },
    /// A call of a function that does not exist.
    #[error("unknown function `{name}` at byte {position}; the functions are {FUNCTION_NAMES}")]
    UnknownFunction {
        /// Byte offset of the function name.
        position: usize,
        /// The name.
        name: String,
    },
    /// A function name not followed by `(`.
    #[error(
        "function `{name}` at byte {position} needs its argument in parentheses: `{name}(...)`"
    )]
    MissingArgumentList {
        /// Byte offset of the function name.
        position: usize,
        /// The function.
        name: &'static str,
    },
    /// A function called with the wrong number of arguments.
    #[error("function `{name}` at byte {position} takes {expected} argument(s), found {found}")]
    WrongArgumentCount {
        /// Byte offset of the function name.
        position: usize,
        /// The function.
        name: &'static str,
        /// How many arguments it takes.
        expected: usize,
        /// How many it was given.
        found: usize,
    },
    /// A `(` without its `)`.
    #[error("missing `)` at byte {position} to close the `(` at byte {open}")]
    MissingClosingParenthesis {
        /// Byte offset where `)` was expected.
        position: usize,
        /// Byte offset of the unmatched `(`.
        open: usize,
    },
    /// Input left over after a complete expression, e.g. `2t`, `t)` or `t, 1`.
    #[error(
        "unexpected `{found}` at byte {position}: expected an operator or the end of the \
         expression (there is no implicit multiplication: write `2*t`)"
    )]
    TrailingInput {
        /// Byte offset of the leftover input.
        position: usize,
        /// Its first character.
        found: char,
    },
    /// A number literal that does not parse, e.g. `1.2.3` or `.`.
    #[error("`{text}` at byte {position} is not a number")]
    InvalidNumber {
        /// Byte offset of the literal.
        position: usize,
        /// The literal.
        text: String,
    },
    /// A number literal too large for `f64`, e.g. `1e400`.
    #[error("number `{text}` at byte {position} is not finite in f64")]
    NonFiniteNumber {
        /// Byte offset of the literal.
        position: usize,
        /// The literal.
        text: String,
    },
    /// A constant sub-expression whose value is not finite, e.g. `ln(0)` or `1/0`.
    #[error("the constant sub-expression at byte {position} is {value}, not a finite number")]
    NonFiniteConstant {
        /// Byte offset where the sub-expression starts.
        position: usize,
        /// Its value.
        value: f64,
    },
    /// Nesting deeper than [`MAX_DEPTH`](super::MAX_DEPTH).
    #[error("expression nests deeper than {limit} levels at byte {position}")]
    TooDeep {
        /// Byte offset of the token that opens the level past the limit.
        position: usize,
        /// The limit, [`MAX_DEPTH`](super::MAX_DEPTH).
        limit: usize,
    },
    /// The value or a derivative is not finite at a sample point
    /// (from [`Expression::check_finite_on`](super::Expression::check_finite_on)).
    #[error("{} of the expression is not finite at t = {t}: {value}", derivative_name(*derivative))]
    NotFinite {
        /// The sample point.
        t: f64,
        /// Which derivative: 0 for the value, 1 for the first derivative, 2 for the second.
        derivative: usize,
        /// Its value there.
        value: f64,
    },
}

impl ExpressionError {
    /// Byte offset in the source text where the error was found, if it belongs to one.
    ///
    /// `None` for [`ExpressionError::NotFinite`], which is about a value of `t`;
    /// `Some(0)` for [`ExpressionError::Empty`] and `Some(MAX_LENGTH)` for
    /// [`ExpressionError::TooLong`] (the first byte past the limit).
    pub fn position(&self) -> Option<usize> {
        match self {
            Self::TooLong { limit, .. } => Some(*limit),
            Self::Empty => Some(0),
            Self::UnexpectedCharacter { position, .. }
            | Self::ExpectedOperand { position, .. }
            | Self::UnknownIdentifier { position, .. }
            | Self::UnknownFunction { position, .. }
            | Self::MissingArgumentList { position, .. }
            | Self::WrongArgumentCount { position, .. }
            | Self::MissingClosingParenthesis { position, .. }
            | Self::TrailingInput { position, .. }
            | Self::InvalidNumber { position, .. }
            | Self::NonFiniteNumber { position, .. }
            | Self::NonFiniteConstant { position, .. }
            | Self::TooDeep { position, .. } => Some(*position),
            Self::NotFinite { .. } => None,
        }
    }
}

/// `found` for an error message.
fn describe(found: Option<char>) -> String {
    match found {
        Some(c) => format!("`{c}`"),
        None => "the end of the expression".to_owned(),
    }
}

/// Name of the `order`-th derivative for an error message.
fn derivative_name(order: usize) -> &'static str {
    match order {
        0 => "the value",
        1 => "the first derivative",
        2 => "the second derivative",
        _ => "a derivative",
    }
}
