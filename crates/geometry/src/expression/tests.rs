//! Unit tests of the expression compiler.

use super::*;
use code::Function;

fn code(src: &str) -> Vec<Op> {
    Expression::parse(src).unwrap().code
}

#[test]
fn constants_are_folded_into_single_instructions() {
    assert_eq!(
        code("2*sin(t) + 0.2*sin(2*t)"),
        [
            Op::Variable(0),
            Op::Call(Function::Sin),
            Op::Times(2.0),
            Op::Variable(0),
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
    assert_eq!(code("t - 1"), [Op::Variable(0), Op::Plus(-1.0)]);
    assert_eq!(code("1 - t"), [Op::Variable(0), Op::ConstantMinus(1.0)]);
    assert_eq!(code("1 / t"), [Op::Variable(0), Op::ConstantOver(1.0)]);
    assert_eq!(code("t / 4"), [Op::Variable(0), Op::Over(4.0)]);
}

#[test]
fn powers_choose_powi_powf_or_exp_ln() {
    assert_eq!(code("t^3"), [Op::Variable(0), Op::PowI(3)]);
    assert_eq!(code("t^-2"), [Op::Variable(0), Op::PowI(-2)]);
    assert_eq!(code("t^1024"), [Op::Variable(0), Op::PowI(1024)]);
    assert_eq!(code("t^1025"), [Op::Variable(0), Op::PowF(1025.0)]);
    assert_eq!(code("t^2.5"), [Op::Variable(0), Op::PowF(2.5)]);
    assert_eq!(code("t^t"), [Op::Variable(0), Op::Variable(0), Op::Power]);
    assert_eq!(code("e^t"), [Op::Variable(0), Op::ExpTimes(1.0)]);
    assert_eq!(code("-t^2"), [Op::Variable(0), Op::PowI(2), Op::Negate]);
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
