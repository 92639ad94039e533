//! Public behaviour of `capstan_geometry::expression`: the parse errors, each located and
//! naming what is allowed (split from `expression.rs`, which keeps values, derivatives, the
//! finite-on-an-interval check and the properties).

use capstan_geometry::expression::{Expression, ExpressionError, MAX_DEPTH, MAX_LENGTH};

fn parse(src: &str) -> Expression {
    Expression::parse(src).unwrap_or_else(|e| panic!("`{src}` should parse: {e}"))
}

fn error(src: &str) -> ExpressionError {
    match Expression::parse(src) {
        Ok(_) => panic!("`{src}` should not parse"),
        Err(e) => e,
    }
}

// ---------------------------------------------------------------- errors

#[test]
fn too_long_input_is_rejected_before_parsing() {
    let src = "t".repeat(MAX_LENGTH + 1);
    assert_eq!(
        error(&src),
        ExpressionError::TooLong {
            length: MAX_LENGTH + 1,
            limit: MAX_LENGTH
        }
    );
    assert_eq!(error(&src).position(), Some(MAX_LENGTH));
}

/// Each `(source, a, b)` of `cases` fails to parse with `expected(a, b)`.
#[track_caller]
fn assert_errors<A: Copy, B: Copy>(
    cases: &[(&str, A, B)],
    expected: impl Fn(A, B) -> ExpressionError,
) {
    for &(src, a, b) in cases {
        assert_eq!(error(src), expected(a, b), "`{src}`");
    }
}

#[test]
fn empty_input_is_rejected() {
    assert_eq!(error(""), ExpressionError::Empty);
    assert_eq!(error(" \t\n "), ExpressionError::Empty);
    assert_eq!(error("").position(), Some(0));
}

#[test]
fn unexpected_characters_are_located() {
    let cases: &[(&str, usize, char)] = &[
        ("t # 2", 2, '#'),
        ("t + é", 4, 'é'),
        ("2*[t]", 2, '['),
        ("sin(t]", 5, ']'),
        ("t $", 2, '$'),
        ("t = 1", 2, '='),
        ("t\u{a0}+ 1", 1, '\u{a0}'), // only ASCII whitespace is skipped
    ];
    assert_errors(cases, |position, found| {
        ExpressionError::UnexpectedCharacter { position, found }
    });
}

#[test]
fn missing_operands_are_located() {
    let cases: &[(&str, usize, Option<char>)] = &[
        ("t + ", 4, None),
        ("t * * 2", 4, Some('*')),
        ("()", 1, Some(')')),
        ("sin(t,)", 6, Some(')')),
        ("2^", 2, None),
        ("-", 1, None),
        ("(, t)", 1, Some(',')),
    ];
    assert_errors(cases, |position, found| ExpressionError::ExpectedOperand {
        position,
        found,
    });
    assert!(
        error("t +")
            .to_string()
            .contains("the end of the expression")
    );
}

#[test]
fn unknown_identifiers_list_the_allowed_names() {
    let err = error("2*sin(x)");
    assert_eq!(
        err,
        ExpressionError::UnknownIdentifier {
            position: 6,
            name: "x".into()
        }
    );
    let message = err.to_string();
    assert!(
        message.contains("`t`") && message.contains("`pi`") && message.contains("`e`"),
        "{message}"
    );
    assert!(matches!(
        error("T"),
        ExpressionError::UnknownIdentifier { position: 0, .. }
    ));
    assert!(matches!(
        error("t2 + 1"),
        ExpressionError::UnknownIdentifier { position: 0, .. }
    ));
    assert!(matches!(
        error("1 + PI"),
        ExpressionError::UnknownIdentifier { position: 4, .. }
    ));
}

#[test]
fn unknown_functions_list_the_allowed_functions() {
    let err = error("1 + log(t)");
    assert_eq!(
        err,
        ExpressionError::UnknownFunction {
            position: 4,
            name: "log".into()
        }
    );
    let message = err.to_string();
    for name in [
        "sin", "cos", "tan", "exp", "ln", "sqrt", "abs", "sinh", "cosh", "tanh", "atan", "cot",
        "sec", "csc",
    ] {
        assert!(message.contains(name), "{message}");
    }
    assert!(matches!(
        error("Sin(t)"),
        ExpressionError::UnknownFunction { position: 0, .. }
    ));
}

#[test]
fn functions_need_parenthesised_arguments() {
    assert_eq!(
        error("sin t"),
        ExpressionError::MissingArgumentList {
            position: 0,
            name: "sin"
        }
    );
    assert_eq!(
        error("2*cos"),
        ExpressionError::MissingArgumentList {
            position: 2,
            name: "cos"
        }
    );
}

#[test]
fn wrong_argument_counts_are_reported() {
    let count = |found| ExpressionError::WrongArgumentCount {
        position: 2,
        name: "atan",
        expected: 1,
        found,
    };
    assert_eq!(error("1+atan()"), count(0));
    assert_eq!(error("1+atan(t, 1)"), count(2));
    assert_eq!(error("1+atan(1, 2, t)"), count(3));
}

#[test]
fn missing_closing_parentheses_point_at_both_ends() {
    let cases: &[(&str, usize, usize)] = &[
        ("(t + 1", 6, 0),
        ("2*(t", 4, 2),
        ("sin(t", 5, 3),
        ("(t t)", 3, 0),
        ("((t)", 4, 0),
        ("sin(t 1)", 6, 3),
    ];
    assert_errors(cases, |position, open| {
        ExpressionError::MissingClosingParenthesis { position, open }
    });
}

#[test]
fn trailing_input_is_located() {
    let cases: &[(&str, usize, char)] = &[
        ("2t", 1, 't'),
        ("t)", 1, ')'),
        ("t, 1", 1, ','),
        ("2 e", 2, 'e'),
        ("2e", 1, 'e'),
        ("pi(2)", 2, '('),
        ("t (1)", 2, '('),
        ("sin(t) cos(t)", 7, 'c'),
    ];
    assert_errors(cases, |position, found| ExpressionError::TrailingInput {
        position,
        found,
    });
}

#[test]
fn malformed_numbers_are_reported() {
    let invalid = |position, text: &str| ExpressionError::InvalidNumber {
        position,
        text: text.into(),
    };
    assert_eq!(error("1.2.3"), invalid(0, "1.2.3"));
    assert_eq!(error("t + ."), invalid(4, "."));
    assert_eq!(error("t*..5"), invalid(2, "..5"));
}

#[test]
fn non_finite_numbers_are_reported() {
    let non_finite = |position, text: &str| ExpressionError::NonFiniteNumber {
        position,
        text: text.into(),
    };
    assert_eq!(error("1e400"), non_finite(0, "1e400"));
    assert_eq!(error("t*1e999"), non_finite(2, "1e999"));
    let big = "9".repeat(400);
    assert_eq!(error(&format!("2*{big}")), non_finite(2, &big));
    assert_eq!(parse("1e-400").eval(1.0_f64), 0.0); // underflow to zero is finite
}

#[test]
fn non_finite_constant_sub_expressions_are_reported() {
    let cases: &[(&str, usize)] = &[
        ("ln(0)", 0),
        ("t + 1/0", 4),
        ("t*sqrt(-1)", 2),
        ("exp(1000) - t", 0),
        ("t + (0/0)", 5),
        ("2^2000 * t", 0),
    ];
    for &(src, position) in cases {
        let err = error(src);
        assert!(
            matches!(err, ExpressionError::NonFiniteConstant { position: p, value } if p == position && !value.is_finite()),
            "`{src}`: {err}"
        );
    }
}

#[test]
fn nesting_past_the_limit_is_rejected() {
    let n = MAX_DEPTH + 1;
    let deep = |src: String, position| {
        assert_eq!(
            error(&src),
            ExpressionError::TooDeep {
                position,
                limit: MAX_DEPTH
            },
            "`{src}`"
        );
    };
    deep(format!("{}t{}", "(".repeat(n), ")".repeat(n)), MAX_DEPTH);
    deep(format!("{}t", "-".repeat(n)), MAX_DEPTH);
    deep(
        format!("{}t{}", "sin(".repeat(n), ")".repeat(n)),
        4 * MAX_DEPTH + 3,
    );
    deep(format!("{}t", "t^".repeat(n)), 2 * MAX_DEPTH + 1);
    // Hostile input at the length limit fails cleanly instead of overflowing the stack.
    deep("(".repeat(MAX_LENGTH), MAX_DEPTH);
    deep("-".repeat(MAX_LENGTH), MAX_DEPTH);
}

#[test]
fn every_parse_error_has_a_position() {
    for src in [
        "", "t #", "t +", "x", "f(t)", "sin", "sin()", "(t", "t)", "1..", "1e999", "ln(0)",
    ] {
        let err = error(src);
        let position = err
            .position()
            .unwrap_or_else(|| panic!("`{src}`: {err} has no position"));
        assert!(position <= src.len(), "`{src}`: {err}");
    }
}
