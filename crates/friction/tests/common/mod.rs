//! Helpers shared by the friction-law tests.

use capstan_friction::{ContactState, FrictionLaw};

/// Central differences of `traction` with slip step `h` and pressure step `hp`.
pub fn central_differences<L: FrictionLaw<f64>>(
    law: &L,
    c: &ContactState<f64>,
    p: &L::Params,
    h: f64,
    hp: f64,
) -> ([[f64; 2]; 2], [f64; 2]) {
    let mut d_slip = [[0.0; 2]; 2];
    for j in 0..2 {
        let (mut up, mut down) = (c.slip, c.slip);
        up[j] += h;
        down[j] -= h;
        let tu = law.traction(&ContactState::new(up, c.normal_pressure), p);
        let td = law.traction(&ContactState::new(down, c.normal_pressure), p);
        for i in 0..2 {
            d_slip[i][j] = (tu[i] - td[i]) / (2.0 * h);
        }
    }
    let tu = law.traction(&ContactState::new(c.slip, c.normal_pressure + hp), p);
    let td = law.traction(&ContactState::new(c.slip, c.normal_pressure - hp), p);
    (d_slip, [0, 1].map(|i| (tu[i] - td[i]) / (2.0 * hp)))
}
