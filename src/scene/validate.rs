//! Validation of every scene value against its allowed range, naming the key.

use super::*;

impl Scene {
    /// Checks every field against its allowed range (see [`Scene::load`], which calls it).
    ///
    /// Ranges: `obstacle.shape` is a registered obstacle ([`capstan_geometry::registry`]),
    /// whose builder checks its own keys (`obstacle.radius, a, b > 0`; `obstacle.half_angle`
    /// in `(0, pi/2)`; a registered obstacle's ranges); the four expressions parse, and the
    /// shape's expressions are finite with finite first and second derivatives on
    /// `[membrane.theta0, membrane.theta_max]`; `friction.law` is one of
    /// [`FrictionLawKind::names`],
    /// `friction.mu >= 0`, `friction.eps > 0`; `membrane.t0 > 0`, `theta0 < theta_max`,
    /// `samples` in `[2, 10^7]`, `t_max > 0` when given; `loads.gravity, density >= 0`,
    /// `loads.width, thickness > 0`; `loads.body_force` one expression per component, finite on
    /// the body; `body.thickness > 0`, `body.young > 0`, `body.poisson`
    /// in `(-1, 1/2)`; `discretisation.volumetric = "reduced"` only with `fem-q1`, `fem-q2`;
    /// `grid.n2, n3 >= 3` (odd for `fem-q2`), at most [`MAX_N2`], [`MAX_N3`],
    /// and a thick-body solve that fits in the available memory ([`memory_estimate`]); known
    /// solver names. Every number must be finite (TOML allows `nan` and `inf`).
    ///
    /// Whether the interval is convex is checked by the models that need it (the membrane
    /// models report [`capstan_friction::FrictionError::NonPositiveCurvature`], exit code 3).
    ///
    /// # Errors
    /// [`CliError::Scene`] naming the key, the value and the allowed range.
    pub fn validate(&self) -> Result<(), CliError> {
        self.validate_with(&Origins::default())
    }

    /// `loads.body_force`: one expression per component of the body's dimension, each finite
    /// at a 9 x 5 (x 5 across a 3-D body's width) lattice of points of the body.
    fn validate_body_force(&self) -> Result<(), CliError> {
        let Some(force) = self.loads.body_force_field(self.body.dimension)? else {
            return Ok(());
        };
        let (m, b) = (&self.membrane, &self.body);
        let lattice =
            |a: f64, z: f64, n: usize| (0..n).map(move |i| a + (z - a) * i as f64 / (n - 1) as f64);
        let x1s: Vec<f64> = if b.dimension == 3 {
            lattice(b.x1 - 0.5 * b.width, b.x1 + 0.5 * b.width, 5).collect()
        } else {
            vec![0.0]
        };
        for x1 in x1s {
            for x2 in lattice(m.theta0, m.theta_max, 9) {
                for x3 in lattice(0.0, b.thickness, 5) {
                    let f = force.components([x1, x2, x3]);
                    if f.iter().any(|v| !v.is_finite()) {
                        return Err(CliError::Scene {
                            origin: "loads.body_force".into(),
                            message: format!(
                                "`loads.body_force` = {:?} is not finite at (x1, x2, x3) = ({x1}, {x2}, {x3}): {f:?}; it must be finite on the body",
                                self.loads.body_force.as_deref().unwrap_or_default()
                            ),
                        });
                    }
                }
            }
        }
        Ok(())
    }

    /// `discretisation.grading` in `[0.05, 1]` and `discretisation.layers` in `1..=12` (only
    /// with a grading), both only with `fem-qp` on the plane-strain body, and at least two
    /// layers' worth of elements (`e >= 2 n`) along `grid.n2` and `grid.n3`.
    fn validate_grading(
        &self,
        bad: &dyn Fn(&str, String, &str) -> CliError,
    ) -> Result<(), CliError> {
        let d = &self.discretisation;
        let set = [
            ("discretisation.grading", d.grading.map(|r| r.to_string())),
            ("discretisation.layers", d.layers.map(|n| n.to_string())),
        ];
        for (key, value) in set.iter().filter_map(|(k, v)| Some((*k, v.clone()?))) {
            if d.method != DiscretisationMethod::FemQp || self.body.dimension != 2 {
                return Err(bad(
                    key,
                    value,
                    "what this scene allows: only discretisation.method = \"fem-qp\" with body.dimension = 2 grades its elements (leave the key unset otherwise)",
                ));
            }
            if key == "discretisation.layers" && d.grading.is_none() {
                return Err(bad(
                    key,
                    value,
                    "what this scene allows: no layers without discretisation.grading (they are the layers of a geometric grading)",
                ));
            }
        }
        let grading = d.grading().map_err(|e| match e {
            ElasticityError::InvalidParameter {
                field,
                value,
                allowed,
            } => bad(field, value.to_string(), allowed),
            other => CliError::from(other),
        })?;
        if grading.is_uniform() {
            return Ok(());
        }
        let layers = grading.layers();
        for (key, n) in [("grid.n2", self.grid.n2), ("grid.n3", self.grid.n3)] {
            if (n - 1) / d.order < 2 * layers {
                return Err(bad(
                    key,
                    n.to_string(),
                    &format!(
                        "p e + 1 nodes with e >= 2 discretisation.layers = {} elements of order p = {} (the graded layers at both ends)",
                        2 * layers,
                        d.order
                    ),
                ));
            }
        }
        Ok(())
    }

    /// `discretisation.corner_layers` in `0..=16` and `discretisation.corner_ratio` in
    /// `[0.05, 0.95]`, only with `fem-qp-corner`, which needs `e >= 2` element cells along
    /// `grid.n2` and `grid.n3` (each corner its own cell); with `body.dimension = 3` an
    /// assembled linear backend (`lu`, `cholesky`, `jacobi`, `gauss-seidel`).
    fn validate_corner(
        &self,
        bad: &dyn Fn(&str, String, &str) -> CliError,
    ) -> Result<(), CliError> {
        let d = &self.discretisation;
        let corner = d.method == DiscretisationMethod::FemQpCorner;
        let set = [
            (
                "discretisation.corner_layers",
                d.corner_layers.map(|n| n.to_string()),
            ),
            (
                "discretisation.corner_ratio",
                d.corner_ratio.map(|r| r.to_string()),
            ),
        ];
        for (key, value) in set.iter().filter_map(|(k, v)| Some((*k, v.clone()?))) {
            if !corner {
                return Err(bad(
                    key,
                    value,
                    "what this scene allows: only discretisation.method = \"fem-qp-corner\" has corner layers (leave the key unset otherwise)",
                ));
            }
        }
        if !corner {
            return Ok(());
        }
        if self.body.dimension == 3
            && matches!(
                self.solver.linear.as_str(),
                "multigrid" | "matrix-free-mg" | "petsc"
            )
        {
            return Err(bad(
                "solver.linear",
                format!("{:?}", self.solver.linear),
                "`lu`, `cholesky`, `jacobi` or `gauss-seidel` with discretisation.method = \"fem-qp-corner\" and body.dimension = 3 (the corner-refined body is assembled on its mesh: no box-grid multigrid, matrix-free operator or PETSc distribution yet)",
            ));
        }
        let named = |e: ElasticityError| match e {
            ElasticityError::InvalidParameter {
                field,
                value,
                allowed,
            } => bad(field, value.to_string(), allowed),
            other => CliError::from(other),
        };
        let scheme = d
            .settings()
            .and_then(|s| d.method.scheme(&s))
            .map_err(named)?;
        for (key, n) in [("grid.n2", self.grid.n2), ("grid.n3", self.grid.n3)] {
            scheme.check_nodes(key, n).map_err(named)?;
        }
        Ok(())
    }

    pub(super) fn validate_with(&self, at: &Origins) -> Result<(), CliError> {
        let bad = |key: &str, value: String, allowed: &str| CliError::Scene {
            origin: at.locate(key),
            message: format!("`{key}` = {value} is outside {allowed}"),
        };
        let real = |key: &str, v: f64, allowed: &str, ok: bool| {
            if v.is_finite() && ok {
                Ok(())
            } else {
                Err(bad(key, format!("{v}"), allowed))
            }
        };
        if let Some(tol) = self.accuracy.tol {
            real(
                "accuracy.tol",
                tol,
                crate::problem::AccuracyTarget::ALLOWED,
                (1e-9..=0.1).contains(&tol),
            )?;
        }
        if self.accuracy.max_unknowns < 1000 {
            return Err(bad(
                "accuracy.max_unknowns",
                self.accuracy.max_unknowns.to_string(),
                "at least 1000",
            ));
        }
        let o = &self.obstacle;
        let m = &self.membrane;
        real("membrane.theta0", m.theta0, "finite values", true)?;
        real(
            "membrane.theta_max",
            m.theta_max,
            "(membrane.theta0, inf)",
            m.theta_max > m.theta0,
        )?;
        let registered = capstan_geometry::registry::find(&o.shape).ok_or_else(|| {
            bad(
                "obstacle.shape",
                format!("{:?}", o.shape),
                &capstan_geometry::registry::names(),
            )
        })?;
        let settings = o.settings()?;
        let is_expression = |key: &str| {
            registered.parameter(key).is_some_and(|p| {
                matches!(
                    p.default,
                    capstan_geometry::registry::ParameterDefault::Expression(_)
                )
            })
        };
        // The paper's four expressions always parse; the shape's own are C^2 on the wrap.
        let fixed = [
            ("u", &o.u),
            ("v", &o.v),
            ("ubar", &o.ubar),
            ("vbar", &o.vbar),
        ];
        let extra = registered
            .parameters
            .iter()
            .filter(|p| !fixed.iter().any(|(k, _)| *k == p.key) && is_expression(p.key))
            .filter_map(|p| match settings.get(p.key) {
                Some(capstan_geometry::registry::ParameterValue::Expression(e)) => Some((p.key, e)),
                _ => None,
            });
        for (name, src) in fixed.into_iter().chain(extra) {
            let key = format!("obstacle.{name}");
            let expression = Expression::parse(src).map_err(|e| CliError::Scene {
                origin: at.locate(&key),
                message: format!("`{key}` = {src:?}: {e}"),
            })?;
            if is_expression(name) {
                expression
                    .check_finite_on(m.theta0, m.theta_max, EXPRESSION_CHECK_SAMPLES)
                    .map_err(|e| CliError::Scene {
                        origin: at.locate(&key),
                        message: format!(
                            "`{key}` = {src:?} must be finite with finite first and second derivatives on [membrane.theta0, membrane.theta_max] = [{}, {}]: {e}",
                            m.theta0, m.theta_max
                        ),
                    })?;
            }
        }
        // The obstacle's own ranges: validated by building it.
        registered.build_from(&settings).map_err(|e| match e {
            GeometryError::InvalidParameter {
                field,
                value,
                allowed,
            } => bad(field, value.to_string(), allowed),
            GeometryError::Expression { field, .. } => CliError::Scene {
                origin: at.locate(field),
                message: e.to_string(),
            },
            other => CliError::Scene {
                origin: at.locate("obstacle.shape"),
                message: other.to_string(),
            },
        })?;
        let f = &self.friction;
        if !capstan_friction::registry::is_registered(&f.law) {
            return Err(bad(
                "friction.law",
                format!("{:?}", f.law),
                &capstan_friction::registry::all_names(),
            ));
        }
        real("friction.mu", f.mu, "[0, inf)", f.mu >= 0.0)?;
        real("friction.eps", f.eps, "(0, inf)", f.eps > 0.0)?;
        real("friction.bound", f.bound, "[0, inf)", f.bound >= 0.0)?;
        real(
            "friction.exponent",
            f.exponent,
            "(0, 2]",
            f.exponent > 0.0 && f.exponent <= 2.0,
        )?;
        real("friction.mu2", f.mu2, "[0, inf)", f.mu2 >= 0.0)?;
        real("friction.axis_angle", f.axis_angle, "finite values", true)?;
        if let Some(kind) = FrictionLawKind::parse(&f.law) {
            // The law's own checks (e.g. orthotropic: not both coefficients zero).
            AnyFrictionParams::of_kind(kind, &f.settings()).map_err(|e| CliError::Scene {
                origin: at.locate("friction.law"),
                message: e.to_string(),
            })?;
        } else {
            // a nonsmooth law (exact Coulomb): its own checks
            capstan_friction::AnyNonsmoothParams::new(&f.law, &f.settings()).map_err(|e| {
                CliError::Scene {
                    origin: at.locate("friction.law"),
                    message: e.to_string(),
                }
            })?;
        }
        if let Some(path) = &self.loads.path {
            if path.is_empty() {
                return Err(bad(
                    "loads.path",
                    "[]".into(),
                    "a non-empty list of end loads",
                ));
            }
            for &v in path {
                real("loads.path", v, "(0, inf) for every value", v > 0.0)?;
            }
        }
        if !(3..=MAX_SAMPLES).contains(&m.nodes) {
            return Err(bad("membrane.nodes", m.nodes.to_string(), "[3, 10^7]"));
        }
        real("membrane.t0", m.t0, "(0, inf)", m.t0 > 0.0)?;
        if !(2..=MAX_SAMPLES).contains(&m.samples) {
            return Err(bad("membrane.samples", m.samples.to_string(), "[2, 10^7]"));
        }
        if let Some(t_max) = m.t_max {
            real("membrane.t_max", t_max, "(0, inf)", t_max > 0.0)?;
        }
        let s = &self.solver;
        for (key, n) in [
            ("membrane.max_subdivisions", m.max_subdivisions),
            ("membrane.max_steps", m.max_steps),
            ("membrane.max_root_iterations", m.max_root_iterations),
            ("membrane.max_newton_iterations", m.max_newton_iterations),
            ("solver.max_iterations", s.max_iterations),
            ("solver.max_continuation_steps", s.max_continuation_steps),
            ("solver.max_sweeps", s.max_sweeps.unwrap_or(1)),
        ] {
            if n == 0 {
                return Err(bad(key, "0".into(), "[1, inf)"));
            }
        }
        real(
            "membrane.min_step",
            m.min_step,
            "[0, inf)",
            m.min_step >= 0.0,
        )?;
        let initial = capstan_elasticity::contact::ContactSettings::default().initial_load_step;
        real(
            "solver.min_load_step",
            s.min_load_step,
            "(0, 0.25] (the first load step is 0.25)",
            s.min_load_step > 0.0 && s.min_load_step <= initial,
        )?;
        let l = &self.loads;
        real("loads.gravity", l.gravity, "[0, inf)", l.gravity >= 0.0)?;
        real("loads.density", l.density, "[0, inf)", l.density >= 0.0)?;
        real("loads.width", l.width, "(0, inf)", l.width > 0.0)?;
        real(
            "loads.thickness",
            l.thickness,
            "(0, inf)",
            l.thickness > 0.0,
        )?;
        real("loads.speed", l.speed, "finite values", true)?;
        real("loads.tau0", l.tau0, "finite values", true)?;
        real("loads.tau_max", l.tau_max, "finite values", true)?;
        if let Some(w) = self.solver.relaxation {
            real("solver.relaxation", w, "(0, 2)", w > 0.0 && w < 2.0)?;
        }
        for (key, src) in [("loads.f_t", &l.f_t), ("loads.f_n", &l.f_n)] {
            let Some(src) = src else { continue };
            let expression = Expression::parse(src).map_err(|e| CliError::Scene {
                origin: at.locate(key),
                message: format!("`{key}` = {src:?}: {e}"),
            })?;
            expression
                .check_finite_on(m.theta0, m.theta_max, EXPRESSION_CHECK_SAMPLES)
                .map_err(|e| CliError::Scene {
                    origin: at.locate(key),
                    message: format!(
                        "`{key}` = {src:?} must be finite with finite first and second derivatives on [membrane.theta0, membrane.theta_max] = [{}, {}]: {e}",
                        m.theta0, m.theta_max
                    ),
                })?;
        }
        let b = &self.body;
        real("body.thickness", b.thickness, "(0, inf)", b.thickness > 0.0)?;
        real("body.young", b.young, "(0, inf)", b.young > 0.0)?;
        real(
            "body.poisson",
            b.poisson,
            "(-1, 1/2)",
            b.poisson > -1.0 && b.poisson < 0.5,
        )?;
        if !matches!(b.dimension, 2 | 3) {
            return Err(bad(
                "body.dimension",
                b.dimension.to_string(),
                "{2, 3} (2: plane strain on a prism, 3: the 3-D body on any obstacle)",
            ));
        }
        real("body.width", b.width, "(0, inf)", b.width > 0.0)?;
        real("body.x1", b.x1, "finite values", true)?;
        self.validate_body_force()?;
        let corner = self.discretisation.method == DiscretisationMethod::FemQpCorner;
        let qp = self.discretisation.method == DiscretisationMethod::FemQp || corner;
        let order = self.discretisation.order;
        if qp && !capstan_elasticity::finite_element::high_order::ORDERS.contains(&order) {
            return Err(bad(
                "discretisation.order",
                order.to_string(),
                "1..=10 (the order p of fem-qp)",
            ));
        }
        if !qp && order != DiscretisationMethod::DEFAULT_ORDER {
            return Err(bad(
                "discretisation.order",
                order.to_string(),
                "4 (the default) unless discretisation.method = \"fem-qp\" or \"fem-qp-corner\": only they have an order",
            ));
        }
        if qp {
            for (key, n) in [("grid.n2", self.grid.n2), ("grid.n3", self.grid.n3)] {
                if n < 2 || !(n - 1).is_multiple_of(order) {
                    return Err(bad(
                        key,
                        n.to_string(),
                        "p e + 1 nodes (e elements of order p = discretisation.order) with fem-qp",
                    ));
                }
            }
        }
        self.validate_grading(&bad)?;
        self.validate_corner(&bad)?;
        if b.dimension == 3 && self.discretisation.method == DiscretisationMethod::Fd {
            return Err(bad(
                "discretisation.method",
                "\"fd\"".into(),
                "{\"fem-q1\", \"fem-q2\", \"fem-qp\"} with body.dimension = 3 (finite differences are plane strain only)",
            ));
        }
        self.validate_grid(at)?;
        if self.discretisation.method == DiscretisationMethod::Fd
            && self.discretisation.volumetric != VolumetricIntegration::Full
        {
            return Err(bad(
                "discretisation.volumetric",
                format!("{:?}", self.discretisation.volumetric.name()),
                "{\"full\"} for discretisation.method = \"fd\" (finite differences have no quadrature rule to reduce; \"reduced\" needs \"fem-q1\" or \"fem-q2\")",
            ));
        }
        if self.solver.linear == "multigrid" {
            if self.body.dimension != 3 || self.solver.nonlinear != "full-newton" {
                return Err(bad(
                    "solver.linear",
                    format!("{:?}", self.solver.linear),
                    "`multigrid` only with body.dimension = 3 and solver.nonlinear = \"full-newton\" (the geometric multigrid of the 3-D box); otherwise `lu`, `cholesky`, `jacobi`, `gauss-seidel`",
                ));
            }
        } else if self.solver.linear == "petsc" {
            if self.solver.nonlinear != "full-newton" {
                return Err(bad(
                    "solver.linear",
                    format!("{:?}", self.solver.linear),
                    "`petsc` only with solver.nonlinear = \"full-newton\" (PETSc solves the full-system Newton steps)",
                ));
            }
            if !crate::features::PETSC_ENABLED {
                return Err(bad(
                    "solver.linear",
                    format!("{:?}", self.solver.linear),
                    "`petsc` only in a build with the cargo feature `petsc` (cargo build --release --features petsc; needs petsc-dev; the Python package is built without it (its wheel links no system PETSc or Open MPI, and the PETSc session lives for one CLI command: MPI cannot start again in a process once it has ended, so a Python process could solve once at most); from Python, run the CLI under mpirun: subprocess.run([\"mpirun\", \"-n\", \"2\", \"capstan\", \"contact\", ...]) (docs/scale-out.md, Python)); otherwise `lu`, `cholesky`, `jacobi`, `gauss-seidel`, `multigrid`",
                ));
            }
        } else if self.solver.linear.parse::<LinearBackend>().is_err() {
            let registered: Vec<String> = LinearBackend::all()
                .iter()
                .map(|b| format!("`{b}`"))
                .collect();
            return Err(bad(
                "solver.linear",
                format!("{:?}", self.solver.linear),
                &format!(
                    "{} (`multigrid`: 3-D body, full-newton; `petsc`: full-newton, feature `petsc`)",
                    registered.join(", ")
                ),
            ));
        }
        if crate::problem::nonlinear_registry::find(&self.solver.nonlinear).is_none() {
            return Err(bad(
                "solver.nonlinear",
                format!("{:?}", self.solver.nonlinear),
                &format!(
                    "{{{}}} (the registered nonlinear methods)",
                    crate::problem::nonlinear_registry::names()
                ),
            ));
        }
        Ok(())
    }

    /// `solver.linear = "petsc"`: the ranks of this node together
    /// ([`petsc_memory_check`]: the per-rank estimate of the body's dimension times the local
    /// ranks of [`mpi_ranks`]) against the memory available, so a scene is refused only when
    /// it does not fit on its ranks.
    fn check_petsc_memory(&self, at: &Origins, key: &str, unknowns: usize) -> Result<(), CliError> {
        let (ranks, local) = mpi_ranks();
        let dimension = usize::from(self.body.dimension);
        petsc_memory_check(unknowns, dimension, ranks, local, available_memory()).map_err(|r| {
            let advice = match r.fewest_ranks {
                Some(k) if k > ranks => format!(
                    "it fits on {k} or more ranks with one a node (mpirun -n {k} --map-by ppr:1:node), or use a coarser grid"
                ),
                Some(_) => "put fewer ranks on each node, or use a coarser grid".to_string(),
                None => "the part every rank holds alone exceeds a node: use a coarser grid".to_string(),
            };
            CliError::Scene {
                origin: at.locate(key),
                message: format!(
                    "{unknowns} unknowns on {ranks} MPI rank(s), {local} of them on this node, need about {} per rank ({} on this node: {}), more than the {} available (MemAvailable in /proc/meminfo); {advice}",
                    human_bytes(r.per_rank),
                    human_bytes(r.per_node),
                    if dimension == 3 {
                        "the whole Newton vectors, and this rank's share of the assembly, PETSc's matrix, GAMG and GMRES"
                    } else {
                        "the plane body assembled whole on every rank, and this rank's share of PETSc's matrix, GAMG and GMRES"
                    },
                    human_bytes(r.available)
                ),
            }
        })
    }

    fn validate_grid(&self, at: &Origins) -> Result<(), CliError> {
        let g = &self.grid;
        let method = self.discretisation.method;
        let q2 = method == DiscretisationMethod::FemQ2;
        for (key, n, max, allowed, allowed_q2) in [
            (
                "grid.n2",
                g.n2,
                MAX_N2,
                "[3, 10^7]",
                "odd values in [3, 10^7] (fem-q2)",
            ),
            (
                "grid.n3",
                g.n3,
                MAX_N3,
                "[3, 10^6]",
                "odd values in [3, 10^6] (fem-q2)",
            ),
        ] {
            if !(3..=max).contains(&n) || (q2 && n % 2 == 0) {
                return Err(CliError::Scene {
                    origin: at.locate(key),
                    message: format!(
                        "`{key}` = {n} is outside {}",
                        if q2 { allowed_q2 } else { allowed }
                    ),
                });
            }
        }
        if self.body.dimension == 3 {
            return self.validate_solid_grid(at);
        }
        if self.solver.linear == "petsc" {
            return self.check_petsc_memory(at, "grid.n2", 2 * g.n2 * g.n3);
        }
        let need = memory_estimate(g.n2, g.n3, method, self.solver.condenses());
        check_memory(at, "grid.n2", need, |have| {
            format!(
                "grid {} x {} ({method}) needs about {} for the sparse system and its LU factors (estimate: {MEMORY_BYTES_PER_N_LOG_N} bytes x N log2 N, N = {} unknowns: contact solves measured up to 4000 x 640), more than the {} available (MemAvailable in /proc/meminfo); use a coarser grid",
                g.n2,
                g.n3,
                human_bytes(need),
                2 * g.n2 * g.n3,
                human_bytes(have)
            )
        })
    }

    /// `grid.n1` of a 3-D body (`[2, 10^5]`, odd for `fem-q2`, `p e + 1` for `fem-qp`) and its
    /// memory estimate
    /// ([`solid_memory_estimate`]) against the memory available.
    fn validate_solid_grid(&self, at: &Origins) -> Result<(), CliError> {
        let g = &self.grid;
        let q2 = self.discretisation.method == DiscretisationMethod::FemQ2;
        if !(2..=100_000).contains(&g.n1) || (q2 && (g.n1.is_multiple_of(2) || g.n1 < 3)) {
            return Err(CliError::Scene {
                origin: at.locate("grid.n1"),
                message: format!(
                    "`grid.n1` = {} is outside {}",
                    g.n1,
                    if q2 {
                        "odd values in [3, 10^5] (fem-q2)"
                    } else {
                        "[2, 10^5]"
                    }
                ),
            });
        }
        let order = self.discretisation.order;
        let method = self.discretisation.method;
        if (method == DiscretisationMethod::FemQp || method == DiscretisationMethod::FemQpCorner)
            && !(g.n1 - 1).is_multiple_of(order)
        {
            return Err(CliError::Scene {
                origin: at.locate("grid.n1"),
                message: format!(
                    "`grid.n1` = {} is outside p e + 1 nodes (e elements of order p = discretisation.order = {order}) with {method}",
                    g.n1
                ),
            });
        }
        if self.solver.linear == "petsc" {
            return self.check_petsc_memory(at, "grid.n1", 3 * g.n1 * g.n2 * g.n3);
        }
        // a mesh method's layout (fem-qp-corner): K face nodes and N nodes in every x1 line,
        // sized as the box grid n1 x K x N/K
        let layout = self
            .discretisation
            .settings()
            .and_then(|s| method.scheme(&s))
            .and_then(|s| s.solid_layout(g.n2, g.n3))
            .ok()
            .flatten();
        let nodes = layout.map_or([g.n1, g.n2, g.n3], |l| {
            let k = l.face_node_count();
            [g.n1, k, l.node_count().div_ceil(k)]
        });
        // what `auto` picks (crate::problem::Solver::resolved): the full-system Newton with
        // LU on a mesh
        let auto_mf = self.solver.nonlinear == "auto"
            && layout.is_none()
            && crate::problem::auto_matrix_free(
                true,
                2 * g.n1 * g.n2,
                self.contact.kind == "unilateral",
                self.loads.body_force.is_some(),
                self.discretisation.volumetric == VolumetricIntegration::Full,
            );
        let matrix_free = self.solver.matrix_free() || auto_mf;
        let condensed = if layout.is_some() {
            self.solver.nonlinear == "newton"
        } else {
            self.solver.condenses() && !auto_mf
        };
        let multigrid = self.solver.linear == "multigrid";
        let settings = capstan_elasticity::registration::DiscretisationSettings {
            order,
            ..Default::default()
        };
        let degree = self
            .discretisation
            .method
            .scheme(&settings)
            .and_then(|s| s.solid_element())
            .map_or(1, |e| e.degree());
        let need = if matrix_free {
            let (cell, varies) = self.solid_cells(at)?;
            solid_matrix_free_memory_estimate(nodes, degree, cell, varies)
        } else if multigrid {
            solid_multigrid_memory_estimate(nodes)
        } else {
            solid_memory_estimate(nodes, condensed, degree)
        };
        check_memory(at, "grid.n1", need, |have| {
            format!(
                "3-D grid {} x {} x {} (grid.n1 x grid.n2 x grid.n3) needs about {} ({}), more than the {} available (MemAvailable in /proc/meminfo); use a coarser grid{}",
                g.n1,
                g.n2,
                g.n3,
                human_bytes(need),
                if matrix_free {
                    "the matrix-free operator's quadrature data, its assembled coarse level and the GMRES vectors"
                } else if multigrid {
                    "the sparse Jacobian, its multigrid hierarchy and the GMRES vectors"
                } else if condensed {
                    "dense condensed contact matrices of 2 n1 n2 rows and the sparse LU"
                } else {
                    "the sparse LU factors"
                },
                human_bytes(have),
                if matrix_free {
                    ""
                } else if condensed || multigrid {
                    " or solver.nonlinear = \"full-newton\" with solver.linear = \"matrix-free-mg\""
                } else {
                    " or solver.linear = \"matrix-free-mg\" (no matrix, no factorisation)"
                }
            )
        })
    }
}

/// Refuses, at `key`, a grid whose estimated need (bytes) exceeds the memory available
/// ([`available_memory`]; nothing is refused where it cannot be read), with `message(have)`.
impl Scene {
    /// The physical cell sizes of the 3-D body's grid at its centre (as the matrix-free
    /// V-cycle measures them, [`capstan_elasticity::solid::cell_sizes`]) and whether the
    /// obstacle's chart varies along `x1` (not a prism), for the matrix-free memory estimate.
    pub(crate) fn solid_cells(&self, at: &Origins) -> Result<([f64; 3], bool), CliError> {
        let g = &self.grid;
        let obstacle = self.obstacle.build()?;
        let b = &self.body;
        let grid = capstan_elasticity::solid::BoxGrid::new(
            [b.x1 - 0.5 * b.width, b.x1 + 0.5 * b.width],
            [self.membrane.theta0, self.membrane.theta_max],
            b.thickness,
            [g.n1, g.n2, g.n3],
            false,
        );
        let chart = capstan_geometry::ShellChart::new(obstacle.clone());
        let cell = grid
            .and_then(|grid| capstan_elasticity::solid::cell_sizes(&chart, &grid))
            .map_err(|e| CliError::Scene {
                origin: at.locate("grid.n1"),
                message: format!("the 3-D body's grid at its centre: {e}"),
            })?;
        Ok((cell, !obstacle.is_prism()))
    }
}

fn check_memory(
    at: &Origins,
    key: &str,
    need: f64,
    message: impl FnOnce(f64) -> String,
) -> Result<(), CliError> {
    match available_memory() {
        Some(have) if need > have => Err(CliError::Scene {
            origin: at.locate(key),
            message: message(have),
        }),
        _ => Ok(()),
    }
}
