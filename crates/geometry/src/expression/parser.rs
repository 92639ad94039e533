//! The recursive-descent parser that compiles the source text into [`Op`]s.

use super::code::{Binary, Function, Op, power_by_constant};
use super::error::ExpressionError;

/// A parsed sub-expression: a folded constant (no code emitted yet), or code just emitted at
/// the end of the program that leaves its value on top of the stack.
#[derive(Clone, Copy, Debug)]
pub(super) enum Operand {
    Constant(f64),
    Code,
}

/// Deepest accepted nesting of parentheses, function calls, unary signs and exponents.
pub const MAX_DEPTH: usize = 64;

/// Recursive-descent parser emitting postfix code as it goes, one function per grammar rule.
pub(super) struct Parser<'a> {
    src: &'a str,
    /// Byte offset of the next unread byte.
    pos: usize,
    /// Current nesting depth, limited by [`MAX_DEPTH`].
    depth: usize,
    /// The names of the variables, `Op::Variable(i)` for `variables[i]`.
    variables: &'a [&'a str],
    pub(super) code: Vec<Op>,
}

type Parsed = Result<Operand, ExpressionError>;

impl<'a> Parser<'a> {
    /// A parser at the start of `src` for an expression in `variables` (at most 256 names).
    pub(super) fn new(src: &'a str, variables: &'a [&'a str]) -> Self {
        Self {
            src,
            pos: 0,
            depth: 0,
            variables,
            code: Vec::new(),
        }
    }
}

impl Parser<'_> {
    /// Skips whitespace and returns the next byte, if any, without consuming it.
    pub(super) fn peek(&mut self) -> Option<u8> {
        let bytes = self.src.as_bytes();
        while self.pos < bytes.len() && bytes[self.pos].is_ascii_whitespace() {
            self.pos += 1;
        }
        bytes.get(self.pos).copied()
    }

    /// The character at `self.pos` (which is always on a character boundary).
    pub(super) fn char_here(&self) -> char {
        self.src[self.pos..].chars().next().unwrap_or('\u{fffd}')
    }

    /// The error for an unexpected `byte` where an operator or the end was expected.
    pub(super) fn leftover(&self, byte: u8) -> ExpressionError {
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
    pub(super) fn enter(&mut self, position: usize) -> Result<(), ExpressionError> {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return Err(ExpressionError::TooDeep {
                position,
                limit: MAX_DEPTH,
            });
        }
        Ok(())
    }

    pub(super) fn leave(&mut self) {
        self.depth -= 1;
    }

    /// Consumes the `)` closing the `(` at `open`.
    pub(super) fn close(&mut self, open: usize) -> Result<(), ExpressionError> {
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
    pub(super) fn expression(&mut self) -> Parsed {
        self.left_associative(Self::term, |byte| match byte {
            b'+' => Some(Binary::Add),
            b'-' => Some(Binary::Subtract),
            _ => None,
        })
    }

    /// `term := unary (('*' | '/') unary)*`
    pub(super) fn term(&mut self) -> Parsed {
        self.left_associative(Self::unary, |byte| match byte {
            b'*' => Some(Binary::Multiply),
            b'/' => Some(Binary::Divide),
            _ => None,
        })
    }

    /// `level := operand (op operand)*`, folded to the left, for the operators `op` names:
    /// the grammar of [`Self::expression`] and [`Self::term`].
    fn left_associative(
        &mut self,
        operand: fn(&mut Self) -> Parsed,
        op: fn(u8) -> Option<Binary>,
    ) -> Parsed {
        self.peek();
        let start = self.pos;
        let mut left = operand(self)?;
        while let Some(op) = self.peek().and_then(op) {
            self.pos += 1;
            let right = operand(self)?;
            left = self.binary(op, left, right, start)?;
        }
        Ok(left)
    }

    /// `unary := ('+' | '-') unary | power`
    pub(super) fn unary(&mut self) -> Parsed {
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
    pub(super) fn power(&mut self) -> Parsed {
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
    pub(super) fn primary(&mut self) -> Parsed {
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
    pub(super) fn number(&mut self) -> Parsed {
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
    pub(super) fn name(&mut self) -> Parsed {
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
        if let Some(i) = self.variables.iter().position(|v| *v == name) {
            self.code.push(Op::Variable(i as u8));
            return Ok(Operand::Code);
        }
        match name {
            "pi" => Ok(Operand::Constant(core::f64::consts::PI)),
            "e" => Ok(Operand::Constant(core::f64::consts::E)),
            _ if self.peek() == Some(b'(') => Err(ExpressionError::UnknownFunction {
                position: start,
                name: name.to_owned(),
            }),
            _ => Err(ExpressionError::UnknownIdentifier {
                position: start,
                name: name.to_owned(),
                variables: self
                    .variables
                    .iter()
                    .map(|v| format!("`{v}`"))
                    .collect::<Vec<_>>()
                    .join(", "),
            }),
        }
    }

    /// The argument list of `function`, whose name starts at `start`.
    pub(super) fn call(&mut self, function: Function, start: usize) -> Parsed {
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
    pub(super) fn binary(
        &mut self,
        op: Binary,
        left: Operand,
        right: Operand,
        start: usize,
    ) -> Parsed {
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
pub(super) fn fold(value: f64, position: usize) -> Parsed {
    if value.is_finite() {
        Ok(Operand::Constant(value))
    } else {
        Err(ExpressionError::NonFiniteConstant { position, value })
    }
}

/// Whether `byte` can start a token of the grammar other than an operator, i.e. whether
/// leftover input starting with it is misplaced rather than foreign.
pub(super) fn starts_token(byte: u8) -> bool {
    byte.is_ascii_alphanumeric() || b"_.(),".contains(&byte)
}
