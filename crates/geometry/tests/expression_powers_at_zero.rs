//! Fuzz finding (issue 18): at a zero base, powers evaluated on dual numbers had a NaN value
//! where `f64` gives 0 or inf (`2^t^-2` at `t = 0`: num-dual forms `x^n` as `x^(n-3) x x x`).

use capstan_geometry::ad::curve_jet;
use capstan_geometry::expression::Expression;

#[test]
fn powers_at_zero_have_the_f64_value_on_dual_numbers() {
    for src in [
        "t^-2", "t^-1", "t^-3", "2^t^-2", "t^1.5", "t^-0.5", "t^1025", "t^-2000", "t^2", "t^3",
    ] {
        let e = Expression::parse(src).unwrap();
        for t in [0.0, -0.0] {
            let value: f64 = e.eval(t);
            let [jet] = curve_jet(|s| [e.eval(s)], t);
            assert!(
                value == jet[0] || value.is_nan() && jet[0].is_nan(),
                "{src} at {t}: {value} vs {}",
                jet[0]
            );
            assert!(!value.is_nan(), "{src} at {t}");
        }
        // away from zero the dual value is the f64 value to round-off
        let [jet] = curve_jet(|s| [e.eval(s)], 0.7);
        let value: f64 = e.eval(0.7);
        assert!(
            !value.is_finite() || (value - jet[0]).abs() <= 4.0 * f64::EPSILON * value.abs(),
            "{src}"
        );
    }
}
