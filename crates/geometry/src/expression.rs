//! Math expressions in one variable `t`, evaluated exactly on dual numbers.
//!
//! Scene files describe obstacle profiles as text, e.g. `u = "2*sin(t) + 0.2*sin(2*t)"`.
//! [`Expression::parse`] compiles such a string once into a short program for a small stack
//! machine, and [`Expression::eval`] runs it on any [`Scalar`]: on `f64` for values, and on
//! dual numbers for exact derivatives of the profile (to round-off, no finite differences).
//!
//! # Grammar
//! ```text
//! expression := term (('+' | '-') term)*
//! term       := unary (('*' | '/') unary)*
//! unary      := ('+' | '-') unary | power
//! power      := primary ('^' unary)?
//! primary    := number | 't' | 'pi' | 'e' | function '(' expression ')' | '(' expression ')'
//! function   := 'sin' | 'cos' | 'tan' | 'exp' | 'ln' | 'sqrt' | 'abs'
//!             | 'sinh' | 'cosh' | 'tanh' | 'atan'
//! number     := digits ['.' [digits]] [exponent] | '.' digits [exponent]
//! exponent   := ('e' | 'E') ['+' | '-'] digits
//! ```
//! - `+ -` bind weaker than `* /`; all four are left-associative: `t - 1 - 2 = (t - 1) - 2`,
//!   `t / 2 / 3 = (t / 2) / 3`.
//! - `^` is right-associative and binds tighter than unary minus: `2^3^2 = 2^9`,
//!   `-t^2 = -(t^2)`. Its exponent may carry a sign: `t^-2 = t^(-2)`.
//! - Whitespace (ASCII) is ignored. There is no implicit multiplication: write `2*t`, not `2t`.
//! - Names are case-sensitive. `t` is the variable, `pi` and `e` are the constants; `2e3` is
//!   the number 2000, while `2*e` is twice Euler's number.
//!
//! # Evaluation
//! Constant sub-expressions (`2*pi`, `sqrt(2)/2`, `-1`) are folded at parse time, in `f64`
//! (for `F = f32` this is slightly more accurate than evaluating them in `f32`). A folded
//! constant that is not finite, such as `ln(0)` or `1/0`, is a parse error.
//!
//! Powers `a^b` are evaluated as follows:
//! ```text
//! b an integer constant, |b| <= 1024   a.powi(b)      any a; exact derivatives
//! b any other constant                  a.powf(b)      a > 0
//! b depends on t                        exp(b ln a)    a > 0
//! ```
//! Outside the stated domains the result is NaN or infinite. num-dual's `powf` forms
//! `a^(b-3) a^3`, so on dual numbers `0^2.5` is NaN, where `f64` gives 0.
//! A constant base with a variable exponent, `c^t`, is `exp(t ln c)`.
//!
//! # Limits
//! Inputs longer than [`MAX_LENGTH`] bytes and nesting (parentheses, function calls, signs and
//! exponents) deeper than [`MAX_DEPTH`] levels are rejected, so that hostile input cannot
//! overflow the stack. Parsing never panics; neither does evaluating a parsed expression.
//!
//! # Example
//! ```
//! use capstan_geometry::expression::Expression;
//! use num_dual::Dual64;
//!
//! let u = Expression::parse("2*sin(t) + 0.2*sin(2*t)").unwrap();
//! let t = 0.3_f64;
//! let value = u.eval(t);
//! assert!((value - (2.0 * t.sin() + 0.2 * (2.0 * t).sin())).abs() < 1e-15);
//!
//! // The same expression on a dual number gives the exact derivative.
//! let du = u.eval(Dual64::from(t).derivative());
//! assert!((du.eps - (2.0 * t.cos() + 0.4 * (2.0 * t).cos())).abs() < 1e-15);
//! ```

use core::fmt;
use core::str::FromStr;

use crate::scalar::{Real, Scalar, real};

/// Longest accepted source text, in bytes.
pub const MAX_LENGTH: usize = 4096;

/// Deepest accepted nesting of parentheses, function calls, unary signs and exponents.
pub const MAX_DEPTH: usize = 64;

/// Largest `|n|` evaluated with `powi`; larger integer exponents use `powf`.
///
/// num-dual's `powi` forms `n (n - 1) (n - 2)` in `i32` for third derivatives, which must not
/// overflow; and `|x|^1024` already overflows `f64` for every `|x| >= 2`.
const MAX_POWI: f64 = 1024.0;

/// Operand-stack slots kept on the machine stack; longer programs use a heap buffer.
const INLINE_STACK: usize = 8;

/// The functions callable from an expression, in the order listed in error messages.
const FUNCTION_NAMES: &str = "sin, cos, tan, exp, ln, sqrt, abs, sinh, cosh, tanh, atan";

/// An error from parsing an expression or from checking it on an interval.
///
/// Positions are byte offsets into the source text, starting at 0.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ExpressionError {
    /// The source text is longer than [`MAX_LENGTH`].
    #[error("expression is {length} bytes long; the limit is {limit} bytes")]
    TooLong {
        /// Length of the source text in bytes.
        length: usize,
        /// The limit, [`MAX_LENGTH`].
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
    /// Nesting deeper than [`MAX_DEPTH`].
    #[error("expression nests deeper than {limit} levels at byte {position}")]
    TooDeep {
        /// Byte offset of the token that opens the level past the limit.
        position: usize,
        /// The limit, [`MAX_DEPTH`].
        limit: usize,
    },
    /// The value or a derivative is not finite at a sample point
    /// (from [`Expression::check_finite_on`]).
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

/// A parsed math expression in one variable `t`, ready to evaluate on any [`Scalar`].
///
/// Keeps its source text: [`Display`](fmt::Display) prints it back, and two expressions are
/// equal when their source texts are equal. See the [module docs](self) for the grammar.
///
/// # Example
/// ```
/// use capstan_geometry::expression::Expression;
///
/// let u: Expression = "-t^2 + 2^-1".parse().unwrap(); // -(t^2) + 1/2
/// assert_eq!(u.eval(3.0_f64), -8.5);
/// assert_eq!(u.to_string(), "-t^2 + 2^-1");
/// ```
#[derive(Clone, Debug)]
pub struct Expression {
    /// The text as given.
    source: String,
    /// The compiled program, in postfix order.
    code: Vec<Op>,
    /// The largest number of values alive at once while `code` runs.
    stack_len: usize,
}

impl PartialEq for Expression {
    /// Equal source texts (the program is a function of the source text).
    fn eq(&self, other: &Self) -> bool {
        self.source == other.source
    }
}

impl Eq for Expression {}

impl fmt::Display for Expression {
    /// Writes the source text, as given to [`Expression::parse`].
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.source)
    }
}

impl FromStr for Expression {
    type Err = ExpressionError;

    /// Same as [`Expression::parse`].
    fn from_str(src: &str) -> Result<Self, Self::Err> {
        Self::parse(src)
    }
}

impl Expression {
    /// Parses and compiles `src` (see the [module docs](self) for the grammar).
    ///
    /// # Errors
    /// An [`ExpressionError`] with the byte position of the first problem: unexpected character,
    /// missing operand, unknown identifier or function, function without `(...)` or with a wrong
    /// number of arguments, missing `)`, trailing input, a number that does not parse or is not
    /// finite, a constant sub-expression that is not finite, nesting deeper than [`MAX_DEPTH`],
    /// input longer than [`MAX_LENGTH`] bytes, or an empty input.
    ///
    /// # Example
    /// ```
    /// use capstan_geometry::expression::{Expression, ExpressionError};
    ///
    /// assert!(Expression::parse("sqrt(1 + t^2)").is_ok());
    /// let err = Expression::parse("2*sin(x)").unwrap_err();
    /// assert!(matches!(err, ExpressionError::UnknownIdentifier { position: 6, .. }));
    /// ```
    pub fn parse(src: &str) -> Result<Self, ExpressionError> {
        if src.len() > MAX_LENGTH {
            return Err(ExpressionError::TooLong {
                length: src.len(),
                limit: MAX_LENGTH,
            });
        }
        let mut parser = Parser {
            src,
            pos: 0,
            depth: 0,
            code: Vec::new(),
        };
        if parser.peek().is_none() {
            return Err(ExpressionError::Empty);
        }
        let value = parser.expression()?;
        if let Some(byte) = parser.peek() {
            return Err(parser.leftover(byte));
        }
        let mut code = parser.code;
        if let Operand::Constant(c) = value {
            code.push(Op::Constant(c));
        }
        code.shrink_to_fit();
        let stack_len = max_stack(&code);
        Ok(Self {
            source: src.to_owned(),
            code,
            stack_len,
        })
    }

    /// The source text, as given to [`Expression::parse`].
    pub fn source(&self) -> &str {
        &self.source
    }

    /// Evaluates the expression at `t`.
    ///
    /// On a dual number `t` (seeded with derivative 1) the result carries the exact
    /// derivatives of the expression. Never panics; outside the domain of a function
    /// (e.g. `ln` of a negative number) the result is NaN or infinite, as in `F`.
    ///
    /// # Example
    /// ```
    /// use capstan_geometry::expression::Expression;
    /// use num_dual::Dual2_64;
    ///
    /// let g = Expression::parse("exp(-t^2)").unwrap();
    /// let t = 0.7_f64;
    /// assert!((g.eval(t) - (-t * t).exp()).abs() < 1e-15);
    /// let d = g.eval(Dual2_64::from(t).derivative()); // value, g', g''
    /// let exact = (4.0 * t * t - 2.0) * (-t * t).exp();
    /// assert!((d.v2 - exact).abs() < 1e-14);
    /// ```
    #[inline]
    pub fn eval<F: Real, S: Scalar<F>>(&self, t: S) -> S {
        if self.stack_len <= INLINE_STACK {
            let mut stack = [S::zero(); INLINE_STACK];
            self.run(t, &mut stack)
        } else {
            let mut stack = vec![S::zero(); self.stack_len];
            self.run(t, &mut stack)
        }
    }

    /// Runs the program with `stack` (at least `stack_len` slots) for the values below the top.
    ///
    /// The top of the stack lives in `top`, so unary operations and operations with a constant
    /// touch no memory. Indices stay in bounds because `stack_len` was computed from `code`.
    #[inline(always)]
    fn run<F: Real, S: Scalar<F>>(&self, t: S, stack: &mut [S]) -> S {
        let mut top = S::zero();
        let mut sp = 0;
        for op in &self.code {
            top = match *op {
                Op::Variable => {
                    stack[sp] = top;
                    sp += 1;
                    t
                }
                Op::Constant(c) => {
                    stack[sp] = top;
                    sp += 1;
                    S::from(real::<F>(c))
                }
                Op::Add => {
                    sp -= 1;
                    stack[sp] + top
                }
                Op::Subtract => {
                    sp -= 1;
                    stack[sp] - top
                }
                Op::Multiply => {
                    sp -= 1;
                    stack[sp] * top
                }
                Op::Divide => {
                    sp -= 1;
                    stack[sp] / top
                }
                Op::Power => {
                    sp -= 1;
                    (top * stack[sp].ln()).exp()
                }
                Op::Plus(c) => top + real::<F>(c),
                Op::ConstantMinus(c) => S::from(real::<F>(c)) - top,
                Op::Times(c) => top * real::<F>(c),
                Op::Over(c) => top / real::<F>(c),
                Op::ConstantOver(c) => S::from(real::<F>(c)) / top,
                Op::PowI(n) => top.powi(n),
                Op::PowF(c) => top.powf(real::<F>(c)),
                Op::ExpTimes(c) => (top * real::<F>(c)).exp(),
                Op::Negate => -top,
                Op::Call(function) => function.apply(top),
            };
        }
        top
    }

    /// Checks that the value and the first and second derivatives are finite at `samples`
    /// evenly spaced points from `t0` to `t1` (both included), for validating scene files.
    ///
    /// One sample checks `t0` alone; zero samples check nothing. Derivatives are exact
    /// (second-order dual numbers), so e.g. `sqrt(t)` fails at `t = 0`, where its value is
    /// finite but its slope is not.
    ///
    /// # Errors
    /// [`ExpressionError::NotFinite`] at the first sample point, in order from `t0`, where the
    /// value or a derivative is infinite or NaN.
    ///
    /// # Example
    /// ```
    /// use capstan_geometry::expression::{Expression, ExpressionError};
    ///
    /// let u = Expression::parse("sqrt(t)").unwrap();
    /// assert!(u.check_finite_on(0.5, 2.0, 16).is_ok());
    /// let err = u.check_finite_on(0.0, 1.0, 5).unwrap_err();
    /// assert!(matches!(err, ExpressionError::NotFinite { t: 0.0, derivative: 1, .. }));
    /// ```
    pub fn check_finite_on<F: Real>(
        &self,
        t0: F,
        t1: F,
        samples: usize,
    ) -> Result<(), ExpressionError> {
        // num-dual is otherwise named only in `crate::ad`, whose `curve_jet` would also carry a
        // third derivative that is not checked here; `Dual2` is the lightest exact type.
        use num_dual::Dual2;
        let to_f64 = |x: F| x.to_f64().unwrap_or(f64::NAN);
        for i in 0..samples {
            let t = if i == 0 {
                t0
            } else if i + 1 == samples {
                t1
            } else {
                t0 + (t1 - t0) * real::<F>(i as f64 / (samples - 1) as f64)
            };
            let y = self.eval(Dual2::from_re(t).derivative());
            for (derivative, value) in [y.re, y.v1, y.v2].into_iter().enumerate() {
                if !value.is_finite() {
                    return Err(ExpressionError::NotFinite {
                        t: to_f64(t),
                        derivative,
                        value: to_f64(value),
                    });
                }
            }
        }
        Ok(())
    }
}

/// One instruction of the stack machine. `c` is a constant operand, `x` the top of the stack
/// and `a` the value below it.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Op {
    /// Push `t`.
    Variable,
    /// Push `c` (only when the whole expression is constant).
    Constant(f64),
    /// `a + x`.
    Add,
    /// `a - x`.
    Subtract,
    /// `a * x`.
    Multiply,
    /// `a / x`.
    Divide,
    /// `a^x = exp(x ln a)`.
    Power,
    /// `x + c` (also `x - c`, as `x + (-c)`: identical in IEEE arithmetic).
    Plus(f64),
    /// `c - x`.
    ConstantMinus(f64),
    /// `x * c`.
    Times(f64),
    /// `x / c`.
    Over(f64),
    /// `c / x`.
    ConstantOver(f64),
    /// `x^n` for an integer constant `n`.
    PowI(i32),
    /// `x^c` for a non-integer constant `c`.
    PowF(f64),
    /// `exp(x c)`: `b^x` with `c = ln b`.
    ExpTimes(f64),
    /// `-x`.
    Negate,
    /// `f(x)`.
    Call(Function),
}

/// The largest number of values alive at once while `code` runs.
fn max_stack(code: &[Op]) -> usize {
    let (mut depth, mut max) = (0_usize, 0_usize);
    for op in code {
        match op {
            Op::Variable | Op::Constant(_) => depth += 1,
            Op::Add | Op::Subtract | Op::Multiply | Op::Divide | Op::Power => depth -= 1,
            _ => {}
        }
        max = max.max(depth);
    }
    max
}

/// The functions of one argument.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Function {
    Sin,
    Cos,
    Tan,
    Exp,
    Ln,
    Sqrt,
    Abs,
    Sinh,
    Cosh,
    Tanh,
    Atan,
}

impl Function {
    /// Every function, in the order of [`FUNCTION_NAMES`].
    const ALL: [Self; 11] = [
        Self::Sin,
        Self::Cos,
        Self::Tan,
        Self::Exp,
        Self::Ln,
        Self::Sqrt,
        Self::Abs,
        Self::Sinh,
        Self::Cosh,
        Self::Tanh,
        Self::Atan,
    ];

    /// The name used in expressions.
    fn name(self) -> &'static str {
        match self {
            Self::Sin => "sin",
            Self::Cos => "cos",
            Self::Tan => "tan",
            Self::Exp => "exp",
            Self::Ln => "ln",
            Self::Sqrt => "sqrt",
            Self::Abs => "abs",
            Self::Sinh => "sinh",
            Self::Cosh => "cosh",
            Self::Tanh => "tanh",
            Self::Atan => "atan",
        }
    }

    fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|f| f.name() == name)
    }

    /// Applies the function; the same code folds constants (`S = F = f64`) and evaluates.
    #[inline(always)]
    fn apply<F: Real, S: Scalar<F>>(self, x: S) -> S {
        match self {
            Self::Sin => x.sin(),
            Self::Cos => x.cos(),
            Self::Tan => x.tan(),
            Self::Exp => x.exp(),
            Self::Ln => x.ln(),
            Self::Sqrt => x.sqrt(),
            Self::Abs => x.abs(),
            Self::Sinh => x.sinh(),
            Self::Cosh => x.cosh(),
            Self::Tanh => x.tanh(),
            Self::Atan => x.atan(),
        }
    }
}

/// The binary operators.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Binary {
    Add,
    Subtract,
    Multiply,
    Divide,
    Power,
}

/// The instruction for `x^c` with a constant exponent `c`.
fn power_by_constant(c: f64) -> Op {
    if c.fract() == 0.0 && c.abs() <= MAX_POWI {
        Op::PowI(c as i32) // exact: an integer of magnitude <= 1024
    } else {
        Op::PowF(c)
    }
}

/// A parsed sub-expression: a folded constant (no code emitted yet), or code just emitted at
/// the end of the program that leaves its value on top of the stack.
#[derive(Clone, Copy, Debug)]
enum Operand {
    Constant(f64),
    Code,
}

/// Recursive-descent parser emitting postfix code as it goes, one function per grammar rule.
struct Parser<'a> {
    src: &'a str,
    /// Byte offset of the next unread byte.
    pos: usize,
    /// Current nesting depth, limited by [`MAX_DEPTH`].
    depth: usize,
    code: Vec<Op>,
}

type Parsed = Result<Operand, ExpressionError>;

impl Parser<'_> {
    /// Skips whitespace and returns the next byte, if any, without consuming it.
    fn peek(&mut self) -> Option<u8> {
        let bytes = self.src.as_bytes();
        while self.pos < bytes.len() && bytes[self.pos].is_ascii_whitespace() {
            self.pos += 1;
        }
        bytes.get(self.pos).copied()
    }

    /// The character at `self.pos` (which is always on a character boundary).
    fn char_here(&self) -> char {
        self.src[self.pos..].chars().next().unwrap_or('\u{fffd}')
    }

    /// The error for an unexpected `byte` where an operator or the end was expected.
    fn leftover(&self, byte: u8) -> ExpressionError {
        let found = self.char_here();
        if starts_token(byte) {
            ExpressionError::TrailingInput {
                position: self.pos,
                found,
            }
        } else {
            ExpressionError::UnexpectedCharacter {
                position: self.pos,
                found,
            }
        }
    }

    /// Opens a nesting level at `position`.
    fn enter(&mut self, position: usize) -> Result<(), ExpressionError> {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return Err(ExpressionError::TooDeep {
                position,
                limit: MAX_DEPTH,
            });
        }
        Ok(())
    }

    fn leave(&mut self) {
        self.depth -= 1;
    }

    /// Consumes the `)` closing the `(` at `open`.
    fn close(&mut self, open: usize) -> Result<(), ExpressionError> {
        match self.peek() {
            Some(b')') => {
                self.pos += 1;
                Ok(())
            }
            Some(byte) if !starts_token(byte) => Err(self.leftover(byte)),
            _ => Err(ExpressionError::MissingClosingParenthesis {
                position: self.pos,
                open,
            }),
        }
    }

    /// `expression := term (('+' | '-') term)*`
    fn expression(&mut self) -> Parsed {
        self.peek();
        let start = self.pos;
        let mut left = self.term()?;
        loop {
            let op = match self.peek() {
                Some(b'+') => Binary::Add,
                Some(b'-') => Binary::Subtract,
                _ => return Ok(left),
            };
            self.pos += 1;
            let right = self.term()?;
            left = self.binary(op, left, right, start)?;
        }
    }

    /// `term := unary (('*' | '/') unary)*`
    fn term(&mut self) -> Parsed {
        self.peek();
        let start = self.pos;
        let mut left = self.unary()?;
        loop {
            let op = match self.peek() {
                Some(b'*') => Binary::Multiply,
                Some(b'/') => Binary::Divide,
                _ => return Ok(left),
            };
            self.pos += 1;
            let right = self.unary()?;
            left = self.binary(op, left, right, start)?;
        }
    }

    /// `unary := ('+' | '-') unary | power`
    fn unary(&mut self) -> Parsed {
        let negate = match self.peek() {
            Some(b'-') => true,
            Some(b'+') => false,
            _ => return self.power(),
        };
        self.enter(self.pos)?;
        self.pos += 1;
        let operand = self.unary()?;
        self.leave();
        Ok(match operand {
            Operand::Constant(c) if negate => Operand::Constant(-c),
            Operand::Code if negate => {
                self.code.push(Op::Negate);
                Operand::Code
            }
            _ => operand,
        })
    }

    /// `power := primary ('^' unary)?`
    fn power(&mut self) -> Parsed {
        self.peek();
        let start = self.pos;
        let base = self.primary()?;
        if self.peek() != Some(b'^') {
            return Ok(base);
        }
        self.enter(self.pos)?;
        self.pos += 1;
        let exponent = self.unary()?;
        self.leave();
        self.binary(Binary::Power, base, exponent, start)
    }

    /// `primary := number | 't' | 'pi' | 'e' | function '(' expression ')' | '(' expression ')'`
    fn primary(&mut self) -> Parsed {
        match self.peek() {
            None => Err(ExpressionError::ExpectedOperand {
                position: self.pos,
                found: None,
            }),
            Some(b'(') => {
                let open = self.pos;
                self.enter(open)?;
                self.pos += 1;
                let inner = self.expression()?;
                self.close(open)?;
                self.leave();
                Ok(inner)
            }
            Some(byte) if byte.is_ascii_digit() || byte == b'.' => self.number(),
            Some(byte) if byte.is_ascii_alphabetic() || byte == b'_' => self.name(),
            Some(byte) if starts_token(byte) || b"+-*/^".contains(&byte) => {
                Err(ExpressionError::ExpectedOperand {
                    position: self.pos,
                    found: Some(self.char_here()),
                })
            }
            Some(_) => Err(ExpressionError::UnexpectedCharacter {
                position: self.pos,
                found: self.char_here(),
            }),
        }
    }

    /// A number literal.
    fn number(&mut self) -> Parsed {
        let bytes = self.src.as_bytes();
        let start = self.pos;
        let mut end = start;
        while end < bytes.len() && (bytes[end].is_ascii_digit() || bytes[end] == b'.') {
            end += 1;
        }
        // An exponent only if digits follow: in `2e` or `2*e+t`, `e` is Euler's number.
        if end < bytes.len() && bytes[end].eq_ignore_ascii_case(&b'e') {
            let mut k = end + 1;
            if k < bytes.len() && (bytes[k] == b'+' || bytes[k] == b'-') {
                k += 1;
            }
            if k < bytes.len() && bytes[k].is_ascii_digit() {
                while k < bytes.len() && bytes[k].is_ascii_digit() {
                    k += 1;
                }
                end = k;
            }
        }
        self.pos = end;
        let text = &self.src[start..end];
        match text.parse::<f64>() {
            Ok(value) if value.is_finite() => Ok(Operand::Constant(value)),
            Ok(_) => Err(ExpressionError::NonFiniteNumber {
                position: start,
                text: text.to_owned(),
            }),
            Err(_) => Err(ExpressionError::InvalidNumber {
                position: start,
                text: text.to_owned(),
            }),
        }
    }

    /// The variable, a constant or a function call.
    fn name(&mut self) -> Parsed {
        let bytes = self.src.as_bytes();
        let start = self.pos;
        while self.pos < bytes.len()
            && (bytes[self.pos].is_ascii_alphanumeric() || bytes[self.pos] == b'_')
        {
            self.pos += 1;
        }
        let name = &self.src[start..self.pos];
        if let Some(function) = Function::from_name(name) {
            return self.call(function, start);
        }
        match name {
            "t" => {
                self.code.push(Op::Variable);
                Ok(Operand::Code)
            }
            "pi" => Ok(Operand::Constant(core::f64::consts::PI)),
            "e" => Ok(Operand::Constant(core::f64::consts::E)),
            _ if self.peek() == Some(b'(') => Err(ExpressionError::UnknownFunction {
                position: start,
                name: name.to_owned(),
            }),
            _ => Err(ExpressionError::UnknownIdentifier {
                position: start,
                name: name.to_owned(),
            }),
        }
    }

    /// The argument list of `function`, whose name starts at `start`.
    fn call(&mut self, function: Function, start: usize) -> Parsed {
        if self.peek() != Some(b'(') {
            return Err(ExpressionError::MissingArgumentList {
                position: start,
                name: function.name(),
            });
        }
        let open = self.pos;
        self.enter(open)?;
        self.pos += 1;
        let (mut argument, mut count) = (Operand::Code, 0);
        if self.peek() != Some(b')') {
            loop {
                argument = self.expression()?;
                count += 1;
                if self.peek() != Some(b',') {
                    break;
                }
                self.pos += 1;
            }
        }
        self.close(open)?;
        self.leave();
        match argument {
            _ if count != 1 => Err(ExpressionError::WrongArgumentCount {
                position: start,
                name: function.name(),
                expected: 1,
                found: count,
            }),
            Operand::Constant(c) => fold(function.apply::<f64, f64>(c), start),
            Operand::Code => {
                self.code.push(Op::Call(function));
                Ok(Operand::Code)
            }
        }
    }

    /// Combines two operands; `start` is where the left one begins (for error messages).
    fn binary(&mut self, op: Binary, left: Operand, right: Operand, start: usize) -> Parsed {
        let instruction = match (left, right) {
            (Operand::Constant(a), Operand::Constant(b)) => {
                let value = match op {
                    Binary::Add => a + b,
                    Binary::Subtract => a - b,
                    Binary::Multiply => a * b,
                    Binary::Divide => a / b,
                    Binary::Power => match power_by_constant(b) {
                        Op::PowI(n) => a.powi(n),
                        _ => a.powf(b),
                    },
                };
                return fold(value, start);
            }
            (Operand::Code, Operand::Constant(b)) => match op {
                Binary::Add => Op::Plus(b),
                Binary::Subtract => Op::Plus(-b),
                Binary::Multiply => Op::Times(b),
                Binary::Divide => Op::Over(b),
                Binary::Power => power_by_constant(b),
            },
            // Only the right operand emitted code; `a op x` in terms of `x`.
            (Operand::Constant(a), Operand::Code) => match op {
                Binary::Add => Op::Plus(a),
                Binary::Subtract => Op::ConstantMinus(a),
                Binary::Multiply => Op::Times(a),
                Binary::Divide => Op::ConstantOver(a),
                Binary::Power => Op::ExpTimes(a.ln()),
            },
            (Operand::Code, Operand::Code) => match op {
                Binary::Add => Op::Add,
                Binary::Subtract => Op::Subtract,
                Binary::Multiply => Op::Multiply,
                Binary::Divide => Op::Divide,
                Binary::Power => Op::Power,
            },
        };
        self.code.push(instruction);
        Ok(Operand::Code)
    }
}

/// A folded constant, if finite.
fn fold(value: f64, position: usize) -> Parsed {
    if value.is_finite() {
        Ok(Operand::Constant(value))
    } else {
        Err(ExpressionError::NonFiniteConstant { position, value })
    }
}

/// Whether `byte` can start a token of the grammar other than an operator, i.e. whether
/// leftover input starting with it is misplaced rather than foreign.
fn starts_token(byte: u8) -> bool {
    byte.is_ascii_alphanumeric() || b"_.(),".contains(&byte)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn code(src: &str) -> Vec<Op> {
        Expression::parse(src).unwrap().code
    }

    #[test]
    fn constants_are_folded_into_single_instructions() {
        assert_eq!(
            code("2*sin(t) + 0.2*sin(2*t)"),
            [
                Op::Variable,
                Op::Call(Function::Sin),
                Op::Times(2.0),
                Op::Variable,
                Op::Times(2.0),
                Op::Call(Function::Sin),
                Op::Times(0.2),
                Op::Add,
            ]
        );
        assert_eq!(
            code("2*pi/4 - sqrt(4)"),
            [Op::Constant(0.5 * core::f64::consts::PI - 2.0)]
        );
        assert_eq!(code("t - 1"), [Op::Variable, Op::Plus(-1.0)]);
        assert_eq!(code("1 - t"), [Op::Variable, Op::ConstantMinus(1.0)]);
        assert_eq!(code("1 / t"), [Op::Variable, Op::ConstantOver(1.0)]);
        assert_eq!(code("t / 4"), [Op::Variable, Op::Over(4.0)]);
    }

    #[test]
    fn powers_choose_powi_powf_or_exp_ln() {
        assert_eq!(code("t^3"), [Op::Variable, Op::PowI(3)]);
        assert_eq!(code("t^-2"), [Op::Variable, Op::PowI(-2)]);
        assert_eq!(code("t^1024"), [Op::Variable, Op::PowI(1024)]);
        assert_eq!(code("t^1025"), [Op::Variable, Op::PowF(1025.0)]);
        assert_eq!(code("t^2.5"), [Op::Variable, Op::PowF(2.5)]);
        assert_eq!(code("t^t"), [Op::Variable, Op::Variable, Op::Power]);
        assert_eq!(code("e^t"), [Op::Variable, Op::ExpTimes(1.0)]);
        assert_eq!(code("-t^2"), [Op::Variable, Op::PowI(2), Op::Negate]);
    }

    #[test]
    fn stack_len_counts_values_alive_at_once() {
        let stack_len = |src: &str| Expression::parse(src).unwrap().stack_len;
        assert_eq!(stack_len("1"), 1);
        assert_eq!(stack_len("t + t + t + t"), 2); // left-associative: never more than two
        assert_eq!(stack_len("t + (t + (t + t))"), 4);
        assert_eq!(stack_len("2*sin(t) + 0.2*sin(2*t)"), 2);
    }

    #[test]
    fn long_programs_use_a_heap_stack() {
        let src = format!("{}t{}", "(t + ".repeat(20), ")".repeat(20));
        let e = Expression::parse(&src).unwrap();
        assert_eq!(e.stack_len, 21);
        assert_eq!(e.eval(1.5_f64), 21.0 * 1.5);
    }

    #[test]
    fn sub_of_constant_equals_add_of_negated_constant() {
        // `Op::Plus(-c)` stands for `x - c`; IEEE subtraction is addition of the negation.
        for x in [0.0, -0.0, 1.0, -1.0, 1e-300, 3.7, f64::MAX] {
            for c in [0.0, -0.0, 1.0, 0.1, 1e300] {
                assert_eq!((x - c).to_bits(), (x + -c).to_bits());
            }
        }
    }
}
