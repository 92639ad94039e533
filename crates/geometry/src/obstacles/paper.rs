//! The paper's obstacles as scenes name them: `cylinder`, `ellipse`, `prism`,
//! `circular-cone`, `cone`. Each builds its own [`Obstacle`] variant (closed forms stay the
//! fast paths); the constructors validate and name the scene key.

use crate::cone::GeneralCone;
use crate::elliptical_prism::{CircularCylinder, EllipticalPrism};
use crate::expression_profile::ExpressionProfile;
use crate::obstacle::Obstacle;
use crate::prism::GeneralPrism;
use crate::registration::{ObstacleParameter, ParameterDefault, RegisteredObstacle};
use crate::simple_surfaces::RightCircularCone;

const fn number(key: &'static str, default: f64, allowed: &'static str) -> ObstacleParameter {
    ObstacleParameter {
        key,
        default: ParameterDefault::Number(default),
        allowed,
    }
}

const fn expression(key: &'static str, default: &'static str) -> ObstacleParameter {
    ObstacleParameter {
        key,
        default: ParameterDefault::Expression(default),
        allowed: "an expression in t, C^2 on the wrap interval",
    }
}

/// `cylinder`: `(x1, r sin x2, r cos x2)`, `obstacle.radius`.
pub(super) const CYLINDER: RegisteredObstacle = RegisteredObstacle {
    name: "cylinder",
    summary: "circular cylinder (x1, r sin x2, r cos x2) of obstacle.radius",
    parameters: &[number("radius", 2.0, "(0, inf)")],
    build: |s| {
        Ok(Obstacle::Cylinder(CircularCylinder::new(
            s.number("radius")?,
        )?))
    },
};

/// `ellipse`: `(x1, a sin x2, b cos x2)`, `obstacle.a`, `obstacle.b`.
pub(super) const ELLIPSE: RegisteredObstacle = RegisteredObstacle {
    name: "ellipse",
    summary: "elliptical prism (x1, a sin x2, b cos x2), obstacle.a and obstacle.b",
    parameters: &[number("a", 2.0, "(0, inf)"), number("b", 2.0, "(0, inf)")],
    build: |s| {
        Ok(Obstacle::Ellipse(EllipticalPrism::new(
            s.number("a")?,
            s.number("b")?,
        )?))
    },
};

/// `prism`: `(x1, u(x2), v(x2))`, expressions `obstacle.u`, `obstacle.v`.
pub(super) const PRISM: RegisteredObstacle = RegisteredObstacle {
    name: "prism",
    summary: "general prism (x1, u(x2), v(x2)) from expressions obstacle.u, obstacle.v",
    parameters: &[expression("u", "2*sin(t)"), expression("v", "2*cos(t)")],
    build: |s| {
        let profile = ExpressionProfile::parse_named(
            s.expression("u")?,
            s.expression("v")?,
            ["obstacle.u", "obstacle.v"],
        )?;
        Ok(Obstacle::Prism(GeneralPrism::new(profile)))
    },
};

/// `circular-cone`: half-aperture `obstacle.half_angle`.
pub(super) const CIRCULAR_CONE: RegisteredObstacle = RegisteredObstacle {
    name: "circular-cone",
    summary: "right circular cone of half-aperture obstacle.half_angle (radians)",
    parameters: &[number(
        "half_angle",
        std::f64::consts::FRAC_PI_6,
        "(0, pi/2)",
    )],
    build: |s| {
        Ok(Obstacle::CircularCone(RightCircularCone::new(
            s.number("half_angle")?,
        )?))
    },
};

/// `cone`: `x1 (1, ubar(x2), vbar(x2))`, expressions `obstacle.ubar`, `obstacle.vbar`.
pub(super) const CONE: RegisteredObstacle = RegisteredObstacle {
    name: "cone",
    summary: "general cone x1 (1, ubar(x2), vbar(x2)) from expressions obstacle.ubar, obstacle.vbar",
    parameters: &[
        expression("ubar", "0.5*sin(t)"),
        expression("vbar", "0.5*cos(t)"),
    ],
    build: |s| {
        let profile = ExpressionProfile::parse_named(
            s.expression("ubar")?,
            s.expression("vbar")?,
            ["obstacle.ubar", "obstacle.vbar"],
        )?;
        Ok(Obstacle::Cone(GeneralCone::new(profile)))
    },
};
