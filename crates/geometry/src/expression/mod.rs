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
//!             | 'sinh' | 'cosh' | 'tanh' | 'atan' | 'cot' | 'sec' | 'csc'
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

/// Operand-stack slots kept on the machine stack; longer programs use a heap buffer.
const INLINE_STACK: usize = 8;

mod code;
mod error;
mod parser;
#[cfg(test)]
mod tests;

use code::{Op, max_stack};
pub use error::ExpressionError;
pub use parser::MAX_DEPTH;
use parser::{Operand, Parser};

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
        let mut parser = Parser::new(src);
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
                // num-dual divides as `a (1/b)`, two roundings: the value is moved to `f64`'s
                // `a / b` (fuzz finding `1 - t/t + ...` at `t = 4e-80`, where cancellation
                // exposed the last bit).
                Op::Divide => {
                    sp -= 1;
                    with_value(stack[sp] / top, stack[sp].re() / top.re())
                }
                Op::Power => {
                    sp -= 1;
                    (top * stack[sp].ln()).exp()
                }
                Op::Plus(c) => top + real::<F>(c),
                Op::ConstantMinus(c) => S::from(real::<F>(c)) - top,
                Op::Times(c) => top * real::<F>(c),
                Op::Over(c) => with_value(top / real::<F>(c), top.re() / real::<F>(c)),
                Op::ConstantOver(c) => {
                    with_value(S::from(real::<F>(c)) / top, real::<F>(c) / top.re())
                }
                // num-dual forms `x^n` as `x^(n-3) x x x`, whose first factor over- or
                // underflows (or is `0^negative`) where `x^n` does not: `1 / x^|n|`, as `f64`
                // computes it (fuzz findings `2^t^-2` at `t = 0`, `t^-1` at `t = 5.7e148`).
                Op::PowI(n) => {
                    let y = top.powi(n);
                    if n < 0 && !same_value(y.re(), top.re().powi(n)) {
                        with_value(top.powi(-n).recip(), top.re().powi(n))
                    } else {
                        with_value(y, top.re().powi(n))
                    }
                }
                Op::PowF(c) => power_by_real(top, real::<F>(c)),
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

/// `x^c` for a non-integer (or large) constant `c` on any scalar: num-dual's `powf`, unless
/// its value differs from `f64`'s `x^c` (its intermediate `x^(c-3)` over- or underflows, or is
/// `0^negative`); then `exp(c ln|x|)` (with the sign of an integer power of a negative `x`)
/// if that has `f64`'s value to `1e-12`. On `f64` itself this is `powf`.
fn power_by_real<F: Real, S: Scalar<F>>(x: S, c: F) -> S {
    let target = x.re().powf(c);
    let y = with_value(x.powf(c), target);
    if same_value(y.re(), target) {
        return y;
    }
    let z = if x.re() < F::zero() && c.fract() == F::zero() {
        let z = ((-x).ln() * c).exp();
        if (c * real::<F>(0.5)).fract() == F::zero() {
            z
        } else {
            -z
        }
    } else {
        (x.ln() * c).exp()
    };
    // `exp(c ln x)` rounds `c ln x`, whose size is hundreds here: agree to 1e-12.
    let close = (z.re() - target).abs() <= real::<F>(1e-12) * target.abs();
    if same_value(z.re(), target) || close {
        z
    } else if target.is_infinite() {
        // e.g. `(-inf)^0.1 = inf` (IEEE `pow`), NaN through `ln`: the value is infinite,
        // derivatives have no meaning there (fuzz finding `(t/0)^.1`).
        S::from(target)
    } else {
        y
    }
}

/// `y` with its value moved to `f64`'s `target` when both are finite (derivatives unchanged):
/// num-dual's `x^(c-3) x x x` rounds four times, and an ill-conditioned caller (`sin(t^0.2)` at
/// `t = 3.7e76`, a fuzz finding) would amplify that into a different value than on `f64`.
fn with_value<F: Real, S: Scalar<F>>(y: S, target: F) -> S {
    let re = y.re();
    if re != target && re.is_finite() && target.is_finite() {
        y + S::from(target - re)
    } else {
        y
    }
}

/// Equal, or both NaN.
fn same_value<F: Real>(a: F, b: F) -> bool {
    a == b || (a.is_nan() && b.is_nan())
}
