//! Boundary conditions on the faces of the parametric box of a 3-D body.

use crate::boundary::{BoundaryConditions, ComponentCondition, PointFunction, Side, X2Ends};

/// A face of the box: `x_a = min` or `x_a = max` for `a = 1, 2, 3`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize)]
pub enum Face {
    /// `x1 = x1a`.
    X1Min,
    /// `x1 = x1b`.
    X1Max,
    /// `x2 = x2a`.
    X2Min,
    /// `x2 = x2b`.
    X2Max,
    /// `x3 = 0`, the contact surface.
    X3Min,
    /// `x3 = h`, the outer surface.
    X3Max,
}

impl Face {
    /// All faces, in the order of [`SolidBoundary::faces`].
    pub const ALL: [Self; 6] = [
        Self::X1Min,
        Self::X1Max,
        Self::X2Min,
        Self::X2Max,
        Self::X3Min,
        Self::X3Max,
    ];

    /// The coordinate normal to the face as an array index (0, 1, 2).
    pub fn normal_index(self) -> usize {
        match self {
            Self::X1Min | Self::X1Max => 0,
            Self::X2Min | Self::X2Max => 1,
            Self::X3Min | Self::X3Max => 2,
        }
    }

    /// `+1` on a max face, `-1` on a min face: the sign of the outward normal.
    pub fn sign(self) -> f64 {
        match self {
            Self::X1Min | Self::X2Min | Self::X3Min => -1.0,
            Self::X1Max | Self::X2Max | Self::X3Max => 1.0,
        }
    }

    /// Whether the face is a max face.
    pub fn is_max(self) -> bool {
        self.sign() > 0.0
    }

    fn index(self) -> usize {
        Self::ALL.iter().position(|f| *f == self).expect("a face")
    }
}

/// A scalar function on the boundary, of the point `(x1, x2, x3)`.
pub type FaceFunction = PointFunction<[f64; 3]>;

/// The condition on one displacement component on one face.
///
/// # Math
/// With `a` the coordinate normal to the face, `s = +-1` the sign of the outward normal and
/// `n_i = s delta_ia / sqrt(g^aa)` the unit outward normal (covariant):
/// ```text
/// Displacement(f):  v^c = f
/// Traction(f):      t_c = n_i T^i_c = f          (boundary flux sqrt(g) sqrt(g^aa) f)
/// Stress(f):        T^a_c = f                    (boundary flux s sqrt(g) f)
/// ```
#[derive(Debug, Clone)]
pub enum FaceComponent {
    /// Prescribed contravariant displacement `v^c`.
    Displacement(FaceFunction),
    /// Prescribed covariant traction `t_c` (zero: free).
    Traction(FaceFunction),
    /// Prescribed mixed stress `T^a_c`.
    Stress(FaceFunction),
}

impl FaceComponent {
    /// Traction-free.
    pub fn free() -> Self {
        Self::Traction(FaceFunction::constant(0.0))
    }
    /// `v^c = 0`.
    pub fn fixed() -> Self {
        Self::Displacement(FaceFunction::constant(0.0))
    }
}

/// The conditions on the three components `[v^1, v^2, v^3]` of one face.
#[derive(Debug, Clone)]
pub struct FaceCondition(pub [FaceComponent; 3]);

impl FaceCondition {
    /// Traction-free.
    pub fn free() -> Self {
        Self([
            FaceComponent::free(),
            FaceComponent::free(),
            FaceComponent::free(),
        ])
    }
    /// Clamped: `v = 0`.
    pub fn clamped() -> Self {
        Self([
            FaceComponent::fixed(),
            FaceComponent::fixed(),
            FaceComponent::fixed(),
        ])
    }
    /// The plane-strain side condition of a prism: `v^1 = 0`, the other components free
    /// (on an `x1`-invariant chart `T^1_2 = T^1_3 = 0` for a plane-strain field).
    pub fn plane_strain() -> Self {
        Self([
            FaceComponent::fixed(),
            FaceComponent::free(),
            FaceComponent::free(),
        ])
    }
}

/// Boundary conditions of a 3-D body on the box.
///
/// A dof on several faces takes the first `Displacement` condition in the order `x3` faces,
/// `x1` faces, `x2` faces (the 2-D corner rule with the `x1` faces inserted); natural
/// conditions act on every face they are given on.
#[derive(Debug, Clone)]
pub struct SolidBoundary {
    /// Conditions in the order of [`Face::ALL`]; the `x2` faces are ignored when periodic.
    pub faces: [FaceCondition; 6],
    /// Periodic in `x2` (a full wrap; the grid must be periodic too).
    pub periodic_x2: bool,
    /// Extra Dirichlet dofs: `(node (i1, i2, i3), component 0..3, value)`.
    pub pinned: Vec<([usize; 3], usize, f64)>,
}

impl SolidBoundary {
    /// The condition on `face`, `None` for the `x2` faces of a periodic body.
    pub fn face(&self, face: Face) -> Option<&FaceCondition> {
        if self.periodic_x2 && face.normal_index() == 1 {
            None
        } else {
            Some(&self.faces[face.index()])
        }
    }

    /// The 2-D conditions of a plane-strain problem extruded along `x1`: each side of the
    /// rectangle becomes the face over it (the 2-D functions of the side coordinate `s`
    /// evaluated at `x3` on the `x2` faces, at `x2` on the `x3` faces), `v^1` free there, and
    /// `x1_faces` on the two `x1` faces. Pinned 2-D dofs are pinned along the whole `x1` line
    /// (`n1` nodes).
    pub fn extruded(plane: &BoundaryConditions, x1_faces: FaceCondition, n1: usize) -> Self {
        let lift = |side: Side| -> FaceCondition {
            let Some(cond) = plane.side(side) else {
                return FaceCondition::free();
            };
            let along = if side.normal_index() == 1 { 2 } else { 1 }; // s = x3 or x2
            let map = |c: &ComponentCondition| -> FaceComponent {
                let f = match c {
                    ComponentCondition::Displacement(f)
                    | ComponentCondition::Traction(f)
                    | ComponentCondition::Stress(f) => f.clone(),
                };
                let g = FaceFunction::new(move |x: [f64; 3]| f.eval(x[along]));
                match c {
                    ComponentCondition::Displacement(_) => FaceComponent::Displacement(g),
                    ComponentCondition::Traction(_) => FaceComponent::Traction(g),
                    ComponentCondition::Stress(_) => FaceComponent::Stress(g),
                }
            };
            FaceCondition([FaceComponent::free(), map(&cond.0[0]), map(&cond.0[1])])
        };
        let pinned = plane
            .pinned
            .iter()
            .flat_map(|p| {
                (0..n1)
                    .map(move |i1| ([i1, p.node[0], p.node[1]], p.component.index() + 1, p.value))
            })
            .collect();
        Self {
            faces: [
                x1_faces.clone(),
                x1_faces,
                lift(Side::X2Min),
                lift(Side::X2Max),
                lift(Side::X3Min),
                lift(Side::X3Max),
            ],
            periodic_x2: matches!(plane.x2, X2Ends::Periodic),
            pinned,
        }
    }
}
