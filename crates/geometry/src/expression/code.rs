//! The compiled program: stack-machine operations, functions and binary operators.

use crate::scalar::{Real, Scalar};

/// Largest `|n|` evaluated with `powi`; larger integer exponents use `powf`.
///
/// num-dual's `powi` forms `n (n - 1) (n - 2)` in `i32` for third derivatives, which must not
/// overflow; and `|x|^1024` already overflows `f64` for every `|x| >= 2`.
const MAX_POWI: f64 = 1024.0;

/// One instruction of the stack machine. `c` is a constant operand, `x` the top of the stack
/// and `a` the value below it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Op {
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
pub(super) fn max_stack(code: &[Op]) -> usize {
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
pub(super) enum Function {
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
    Cot,
    Sec,
    Csc,
}

impl Function {
    /// Every function, in the order of [`FUNCTION_NAMES`].
    const ALL: [Self; 14] = [
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
        Self::Cot,
        Self::Sec,
        Self::Csc,
    ];

    /// The name used in expressions.
    pub(super) fn name(self) -> &'static str {
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
            Self::Cot => "cot",
            Self::Sec => "sec",
            Self::Csc => "csc",
        }
    }

    pub(super) fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|f| f.name() == name)
    }

    /// Applies the function; the same code folds constants (`S = F = f64`) and evaluates.
    #[inline(always)]
    pub(super) fn apply<F: Real, S: Scalar<F>>(self, x: S) -> S {
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
            // cot = 1/tan, sec = 1/cos, csc = 1/sin: the reciprocal of a dual number carries
            // the exact derivatives (`(1/f)' = -f'/f^2`, and so on).
            Self::Cot => x.tan().recip(),
            Self::Sec => x.cos().recip(),
            Self::Csc => x.sin().recip(),
        }
    }
}

/// The binary operators.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Binary {
    Add,
    Subtract,
    Multiply,
    Divide,
    Power,
}

/// The instruction for `x^c` with a constant exponent `c`.
pub(super) fn power_by_constant(c: f64) -> Op {
    if c.fract() == 0.0 && c.abs() <= MAX_POWI {
        Op::PowI(c as i32) // exact: an integer of magnitude <= 1024
    } else {
        Op::PowF(c)
    }
}
