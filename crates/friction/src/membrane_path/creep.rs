//! Belt creep on a circular capstan: the closed form of the membrane with exact Coulomb
//! friction along a load path (loading, unloading, reloading).
//!
//! # Math
//! A membrane of axial stiffness `k` on `[theta0, theta1]` of a circle of radius `R`
//! (`kappa = 1/R`, `ds = R dtheta`), wrapped at the uniform tension `T0` (no friction), the end
//! `theta0` held at `T0`, the end `theta1` loaded. Slip zones obey the capstan balance
//! `dT/dtheta = +-mu T`; stick zones keep their tension (no slip increment means no strain
//! increment).
//!
//! *Loading* `T0 -> T1 > T0`: a forward slip zone `[theta_c, theta1]` grows from the loaded end,
//! ```text
//! theta_c = theta1 - ln(T1/T0)/mu,     T = T0 exp(mu (theta - theta_c)) in it, T0 before it
//! W_load  = int (T - T0)/k ds = R (T1 - T0 - T0 ln(T1/T0)) / (k mu)   (end displacement)
//! ```
//! *Unloading* `T1 -> T2 < T1`: a reverse slip zone from the end, where
//! `T = T2 exp(mu (theta1 - theta))` meets the loaded profile `T1 exp(-mu (theta1 - theta))`:
//! ```text
//! theta_r  = theta1 - ln(T1/T2)/(2 mu)                 (valid for T2 >= T0^2/T1)
//! W_unload = R/k int_{theta_r}^{theta1} (T2 e^{mu(theta1-theta)} - T1 e^{-mu(theta1-theta)}) dtheta
//!          = -R (sqrt(T1) - sqrt(T2))^2 / (k mu)
//! ```
//! *Reloading* `T2 -> T1`: a forward zone from the end meets the unloaded profile at the same
//! `theta_r` and restores the loaded state exactly: `W_reload = -W_unload`, the loop closes.
//! The energy the end load puts in over a cycle, `oint T dW` with `dW/dT` from the two
//! branches, is what friction dissipates:
//! ```text
//! D = R/(k mu) (T1^2 - T2^2 - (2/3) (T1^(3/2) - T2^(3/2)) (sqrt(T1) + sqrt(T2)))  > 0
//! ```
//! Everything needs the slip zone inside the interval: `ln(T1/T0)/mu <= theta1 - theta0`.
//!
//! # References
//! Johnson, *Contact Mechanics* (1985), 8.5 (creep of a belt on a pulley); the unloading and the
//! cycle follow from the same balance (derived here; `docs/verification.md`).

use crate::error::{FrictionError, check};

/// The closed form of belt creep on a circle (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BeltCreep {
    /// Radius `R` of the circle.
    pub radius: f64,
    /// Coefficient of friction `mu`.
    pub mu: f64,
    /// Axial stiffness `k`.
    pub stiffness: f64,
    /// The wrapping tension `T0`, held at `theta0`.
    pub t0: f64,
    /// Start of the contact interval.
    pub theta0: f64,
    /// The loaded end.
    pub theta1: f64,
}

impl BeltCreep {
    fn checked(&self, t1: f64) -> Result<(), FrictionError> {
        check("radius", self.radius, "(0, inf)", |v| v > 0.0)?;
        check("mu", self.mu, "(0, inf)", |v| v > 0.0)?;
        check("stiffness", self.stiffness, "(0, inf)", |v| v > 0.0)?;
        check("t0", self.t0, "(0, inf)", |v| v > 0.0)?;
        let span = self.theta1 - self.theta0;
        check("theta1", self.theta1, "(theta0, inf)", |_| span > 0.0)?;
        let limit = self.t0 * (self.mu * span).exp();
        check(
            "t1",
            t1,
            "[t0, t0 exp(mu (theta1 - theta0))]: the slip zone inside the interval",
            |v| v >= self.t0 && v <= limit,
        )?;
        Ok(())
    }

    /// Where the forward slip zone of loading to `t1` starts: `theta1 - ln(t1/t0)/mu`.
    ///
    /// # Errors
    /// [`FrictionError::InvalidParameter`] naming the first bad field, or `t1` outside
    /// `[t0, t0 exp(mu (theta1 - theta0))]`.
    pub fn loading_slip_start(&self, t1: f64) -> Result<f64, FrictionError> {
        self.checked(t1)?;
        Ok(self.theta1 - (t1 / self.t0).ln() / self.mu)
    }

    /// The tension at `theta` after loading to `t1`.
    ///
    /// # Errors
    /// As [`BeltCreep::loading_slip_start`].
    pub fn loading_tension(&self, t1: f64, theta: f64) -> Result<f64, FrictionError> {
        let start = self.loading_slip_start(t1)?;
        Ok(self.t0 * (self.mu * (theta - start).max(0.0)).exp())
    }

    /// The end displacement of loading to `t1`: `R (t1 - t0 - t0 ln(t1/t0)) / (k mu)`.
    ///
    /// # Errors
    /// As [`BeltCreep::loading_slip_start`].
    pub fn loading_displacement(&self, t1: f64) -> Result<f64, FrictionError> {
        self.checked(t1)?;
        let (t0, r) = (self.t0, self.radius);
        Ok(r * (t1 - t0 - t0 * (t1 / t0).ln()) / (self.stiffness * self.mu))
    }

    fn checked_unloading(&self, t1: f64, t2: f64) -> Result<(), FrictionError> {
        self.checked(t1)?;
        let low = self.t0 * self.t0 / t1;
        check(
            "t2",
            t2,
            "[t0^2/t1, t1]: the reverse zone inside the loaded slip zone",
            |v| v >= low && v <= t1,
        )?;
        Ok(())
    }

    /// Where the reverse slip zone of unloading from `t1` to `t2` starts:
    /// `theta1 - ln(t1/t2)/(2 mu)`.
    ///
    /// # Errors
    /// As [`BeltCreep::loading_slip_start`]; `t2` outside `[t0^2/t1, t1]`.
    pub fn unloading_slip_start(&self, t1: f64, t2: f64) -> Result<f64, FrictionError> {
        self.checked_unloading(t1, t2)?;
        Ok(self.theta1 - (t1 / t2).ln() / (2.0 * self.mu))
    }

    /// The end displacement of unloading from `t1` to `t2` (negative):
    /// `-R (sqrt(t1) - sqrt(t2))^2 / (k mu)`.
    ///
    /// # Errors
    /// As [`BeltCreep::unloading_slip_start`].
    pub fn unloading_displacement(&self, t1: f64, t2: f64) -> Result<f64, FrictionError> {
        self.checked_unloading(t1, t2)?;
        let d = t1.sqrt() - t2.sqrt();
        Ok(-self.radius * d * d / (self.stiffness * self.mu))
    }

    /// The energy friction dissipates in one cycle `t1 -> t2 -> t1` (after loading to `t1`).
    ///
    /// # Errors
    /// As [`BeltCreep::unloading_slip_start`].
    pub fn cycle_dissipation(&self, t1: f64, t2: f64) -> Result<f64, FrictionError> {
        self.checked_unloading(t1, t2)?;
        let (a, b) = (t1.sqrt(), t2.sqrt());
        let bracket = t1 * t1 - t2 * t2 - 2.0 / 3.0 * (a * t1 - b * t2) * (a + b);
        Ok(self.radius * bracket / (self.stiffness * self.mu))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn creep() -> BeltCreep {
        BeltCreep {
            radius: 2.0,
            mu: 0.5,
            stiffness: 1e3,
            t0: 1.0,
            theta0: -1.5,
            theta1: 1.5,
        }
    }

    #[test]
    fn the_cycle_is_the_area_between_the_branches() {
        // oint T dW by Simpson on the two branches W(T) against the closed form
        let c = creep();
        let (t1, t2) = (2.0, 1.2);
        let n = 2000;
        let mut area = 0.0;
        for k in 0..=n {
            let tk = t2 + (t1 - t2) * k as f64 / n as f64;
            let weight = if k == 0 || k == n {
                1.0
            } else if k % 2 == 1 {
                4.0
            } else {
                2.0
            };
            // dW/dT on the reloading and the unloading branch
            let reload = (tk.sqrt() - t2.sqrt()) / tk.sqrt();
            let unload = (t1.sqrt() - tk.sqrt()) / tk.sqrt();
            area += weight * tk * (reload - unload);
        }
        area *= (t1 - t2) / (3.0 * n as f64) * c.radius / (c.stiffness * c.mu);
        let d = c.cycle_dissipation(t1, t2).unwrap();
        assert!(d > 0.0);
        assert!((area / d - 1.0).abs() < 1e-10, "{area} vs {d}"); // Simpson: smooth integrand
    }

    #[test]
    fn ranges_are_checked() {
        let c = creep();
        assert!(matches!(
            c.loading_slip_start(0.5),
            Err(FrictionError::InvalidParameter { field: "t1", .. })
        ));
        assert!(c.loading_slip_start((0.5f64 * 3.0).exp() * 1.0001).is_err());
        assert!(matches!(
            c.unloading_slip_start(2.0, 0.4),
            Err(FrictionError::InvalidParameter { field: "t2", .. })
        ));
        // unloading to t0^2/t1 reaches back exactly to the loaded zone's start
        let s = c.unloading_slip_start(2.0, 0.5).unwrap();
        assert!((s - c.loading_slip_start(2.0).unwrap()).abs() < 1e-15);
    }
}
