//! Boundary conditions on the four sides of the parameter rectangle.

use std::fmt;
use std::sync::Arc;

use crate::error::ElasticityError;
use crate::grid::Grid;

/// A side of the rectangle `[theta0, theta1] x [0, h]`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Side {
    /// `x2 = theta0`.
    X2Min,
    /// `x2 = theta1`.
    X2Max,
    /// `x3 = 0`, the contact surface.
    X3Min,
    /// `x3 = h`, the outer surface.
    X3Max,
}

impl Side {
    /// All sides.
    pub const ALL: [Self; 4] = [Self::X2Min, Self::X2Max, Self::X3Min, Self::X3Max];

    /// The point `(x2, x3)` of `grid`'s rectangle at parameter `s` along the side (`s` is
    /// `x3` on an `x2` side, `x2` on an `x3` side).
    pub fn point(self, grid: &Grid, s: f64) -> [f64; 2] {
        match self {
            Self::X2Min => [grid.theta()[0], s],
            Self::X2Max => [grid.theta()[1], s],
            Self::X3Min => [s, 0.0],
            Self::X3Max => [s, grid.thickness()],
        }
    }

    /// The coordinate normal to the side as an array index (1 for `x2`, 2 for `x3`).
    pub fn normal_index(self) -> usize {
        match self {
            Self::X2Min | Self::X2Max => 1,
            Self::X3Min | Self::X3Max => 2,
        }
    }

    /// `+1` on the maximum side, `-1` on the minimum side (sign of the outward normal).
    pub fn sign(self) -> f64 {
        match self {
            Self::X2Min | Self::X3Min => -1.0,
            Self::X2Max | Self::X3Max => 1.0,
        }
    }

    /// Name as in scene files and reports.
    pub fn name(self) -> &'static str {
        match self {
            Self::X2Min => "x2-min",
            Self::X2Max => "x2-max",
            Self::X3Min => "x3-min",
            Self::X3Max => "x3-max",
        }
    }
}

/// A displacement component (`v^2` or `v^3`) or the matching equation / traction component
/// (`j = 2` or `j = 3`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Component {
    /// `v^2` (tangential, radians on an angular chart) / the `j = 2` equation.
    X2,
    /// `v^3` (normal, length) / the `j = 3` equation.
    X3,
}

impl Component {
    /// Both components.
    pub const ALL: [Self; 2] = [Self::X2, Self::X3];

    /// 0 for `X2`, 1 for `X3` (index into `[v^2, v^3]`).
    pub fn index(self) -> usize {
        match self {
            Self::X2 => 0,
            Self::X3 => 1,
        }
    }
}

/// A scalar function of a boundary point `X`: of the boundary coordinate (`X = f64`,
/// [`BoundaryFunction`]) in plane strain, of the point `(x1, x2, x3)` on a face of a 3-D body
/// (`X = [f64; 3]`, [`crate::solid::FaceFunction`]).
#[derive(Clone)]
pub struct PointFunction<X>(Arc<dyn Fn(X) -> f64 + Send + Sync>);

/// A scalar function of the boundary coordinate (`x3` on the `x2` sides, `x2` on the `x3`
/// sides).
pub type BoundaryFunction = PointFunction<f64>;

impl<X: 'static> PointFunction<X> {
    /// Wraps a closure.
    pub fn new(f: impl Fn(X) -> f64 + Send + Sync + 'static) -> Self {
        Self(Arc::new(f))
    }
    /// The constant `c`.
    pub fn constant(c: f64) -> Self {
        Self::new(move |_| c)
    }
    /// Zero.
    pub fn zero() -> Self {
        Self::constant(0.0)
    }
    /// Evaluates at the boundary point `x`.
    pub fn eval(&self, x: X) -> f64 {
        (self.0)(x)
    }
}

impl<X> fmt::Debug for PointFunction<X> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("PointFunction(..)")
    }
}

/// The condition on one component of one side.
///
/// # Math
/// With `a` the coordinate normal to the side and `s = +-1` the sign of the outward normal,
/// the unit outward normal has covariant components `n_i = s delta_i^a / sqrt(g^aa)`, so
/// ```text
/// Displacement(f):  v^c = f                         (Dirichlet)
/// Traction(f):      n_i T^i_c = s T^a_c / sqrt(g^aa) = f     (force per area, covariant)
/// Stress(f):        T^a_c = f                       (the paper's end condition T^2_2 = tau)
/// ```
/// `Traction` and `Stress` are the same natural condition with different scalings: on
/// `x3 = 0` (where `g^33 = 1`, `s = -1`) `Traction(f)` means `T^3_c = -f`.
#[derive(Debug, Clone)]
pub enum ComponentCondition {
    /// Prescribed contravariant displacement `v^c`.
    Displacement(BoundaryFunction),
    /// Prescribed traction `t_c = n_i T^i_c` (unit outward normal).
    Traction(BoundaryFunction),
    /// Prescribed stress component `T^a_c` (`a` normal to the side).
    Stress(BoundaryFunction),
}

impl ComponentCondition {
    /// Zero traction.
    pub fn free() -> Self {
        Self::Traction(BoundaryFunction::zero())
    }
    /// Zero displacement.
    pub fn fixed() -> Self {
        Self::Displacement(BoundaryFunction::zero())
    }
    /// Whether this is a Dirichlet condition.
    pub fn is_displacement(&self) -> bool {
        matches!(self, Self::Displacement(_))
    }
}

/// The conditions on both components of one side, `[j = 2, j = 3]`.
#[derive(Debug, Clone)]
pub struct SideCondition(pub [ComponentCondition; 2]);

impl SideCondition {
    /// Traction-free (`n_i T^i_j = 0`).
    pub fn free() -> Self {
        Self([ComponentCondition::free(), ComponentCondition::free()])
    }
    /// Clamped (`v^2 = v^3 = 0`).
    pub fn clamped() -> Self {
        Self([ComponentCondition::fixed(), ComponentCondition::fixed()])
    }
    /// The paper's end condition: `T^a_2 = tension` and zero shear `T^a_3 = 0`.
    pub fn end_tension(tension: f64) -> Self {
        Self([
            ComponentCondition::Stress(BoundaryFunction::constant(tension)),
            ComponentCondition::Stress(BoundaryFunction::zero()),
        ])
    }
    /// Bilateral contact with a prescribed tangential traction: `v^3 = 0`, `t_2 = f`.
    pub fn bilateral(tangential_traction: BoundaryFunction) -> Self {
        Self([
            ComponentCondition::Traction(tangential_traction),
            ComponentCondition::fixed(),
        ])
    }
    /// The condition of one component.
    pub fn component(&self, c: Component) -> &ComponentCondition {
        &self.0[c.index()]
    }
}

/// The `x2` ends: two sides, or periodic (a full wrap).
#[derive(Debug, Clone)]
pub enum X2Ends {
    /// Conditions at `x2 = theta0` and `x2 = theta1`.
    Sides {
        /// At `x2 = theta0`.
        min: SideCondition,
        /// At `x2 = theta1`.
        max: SideCondition,
    },
    /// Periodic in `x2` (the grid must be periodic too).
    Periodic,
}

impl X2Ends {
    /// Whether the ends are periodic.
    pub fn is_periodic(&self) -> bool {
        matches!(self, Self::Periodic)
    }
}

/// A Dirichlet condition on one node and component, e.g. to pin the rigid rotation of a
/// full wrap (`v^2 = 0` at one node).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct PinnedDof {
    /// `(i2, i3)`.
    pub node: [usize; 2],
    /// The component.
    pub component: Component,
    /// The prescribed value.
    pub value: f64,
}

/// Boundary conditions on the rectangle.
///
/// At a corner a `Displacement` condition on either side wins; if both sides are
/// `Displacement`, the `x3` side's function is used. Two natural conditions at a corner both
/// act (each on its half of the corner cell).
#[derive(Debug, Clone)]
pub struct BoundaryConditions {
    /// The `x2` ends.
    pub x2: X2Ends,
    /// `x3 = 0`, the contact surface.
    pub x3_min: SideCondition,
    /// `x3 = h`, the outer surface.
    pub x3_max: SideCondition,
    /// Extra Dirichlet nodes (gauge conditions).
    pub pinned: Vec<PinnedDof>,
}

impl BoundaryConditions {
    /// The paper's section 3 stand-in: end tensions `tau0`, `tau_max` (zero shear), free outer
    /// surface, and `v^2 = v^3 = 0` on `x3 = 0` (a linear stand-in for the contact).
    pub fn paper_clamped(tau0: f64, tau_max: f64) -> Self {
        Self {
            x2: X2Ends::Sides {
                min: SideCondition::end_tension(tau0),
                max: SideCondition::end_tension(tau_max),
            },
            x3_min: SideCondition::clamped(),
            x3_max: SideCondition::free(),
            pinned: vec![],
        }
    }

    /// Checks the conditions fit `grid`: both periodic in `x2` or both not, every pinned
    /// node inside.
    ///
    /// # Errors
    /// [`ElasticityError::InconsistentBoundary`] saying which.
    pub fn check_grid(&self, grid: &Grid) -> Result<(), ElasticityError> {
        if grid.is_periodic() != self.is_periodic() {
            return Err(ElasticityError::InconsistentBoundary {
                what: "the grid and the x2 conditions must both be periodic or both not",
            });
        }
        if self
            .pinned
            .iter()
            .any(|p| p.node[0] >= grid.n2() || p.node[1] >= grid.n3())
        {
            return Err(ElasticityError::InconsistentBoundary {
                what: "a pinned node is outside the grid",
            });
        }
        Ok(())
    }

    /// The condition on a side, `None` for the `x2` sides of a periodic problem.
    pub fn side(&self, side: Side) -> Option<&SideCondition> {
        match (side, &self.x2) {
            (Side::X3Min, _) => Some(&self.x3_min),
            (Side::X3Max, _) => Some(&self.x3_max),
            (Side::X2Min, X2Ends::Sides { min, .. }) => Some(min),
            (Side::X2Max, X2Ends::Sides { max, .. }) => Some(max),
            (_, X2Ends::Periodic) => None,
        }
    }

    /// Whether `x2` is periodic.
    pub fn is_periodic(&self) -> bool {
        self.x2.is_periodic()
    }

    /// The displacement prescribed at a grid node and component, if any: pinned dofs first,
    /// then the `x3` sides, then the `x2` sides (the corner rule of every discretisation).
    ///
    /// # Errors
    /// [`crate::ElasticityError::NonFinite`] if the prescribed function is not finite there.
    pub fn dirichlet_value(
        &self,
        grid: &Grid,
        node: [usize; 2],
        c: Component,
    ) -> Result<Option<f64>, crate::error::ElasticityError> {
        self.dirichlet_value_at(grid, node, grid.coordinates(node), c)
    }

    /// [`BoundaryConditions::dirichlet_value`] for a node of `grid`'s numbering that sits at
    /// `[x2, x3]` (the nodes of the high-order elements are not uniformly spaced): the side
    /// functions are evaluated there.
    ///
    /// # Errors
    /// [`crate::ElasticityError::NonFinite`] if the prescribed function is not finite there.
    pub fn dirichlet_value_at(
        &self,
        grid: &Grid,
        node: [usize; 2],
        [x2, x3]: [f64; 2],
        c: Component,
    ) -> Result<Option<f64>, crate::error::ElasticityError> {
        if let Some(p) = self
            .pinned
            .iter()
            .find(|p| p.node == node && p.component == c)
        {
            return Ok(Some(p.value));
        }
        let (n2, n3) = (grid.n2(), grid.n3());
        let mut sides = Vec::with_capacity(2);
        if node[1] == 0 {
            sides.push((Side::X3Min, x2));
        }
        if node[1] == n3 - 1 {
            sides.push((Side::X3Max, x2));
        }
        if !grid.is_periodic() {
            if node[0] == 0 {
                sides.push((Side::X2Min, x3));
            }
            if node[0] == n2 - 1 {
                sides.push((Side::X2Max, x3));
            }
        }
        for (side, s) in sides {
            if let Some(ComponentCondition::Displacement(f)) =
                self.side(side).map(|sc| sc.component(c))
            {
                let value = f.eval(s);
                if !value.is_finite() {
                    return Err(crate::error::ElasticityError::NonFinite {
                        what: "boundary displacement",
                        at: [x2, x3],
                    });
                }
                return Ok(Some(value));
            }
        }
        Ok(None)
    }
}
