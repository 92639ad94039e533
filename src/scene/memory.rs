//! Size limits of a scene and the memory estimate of a thick-body solve.

use capstan_elasticity::finite_element::DiscretisationMethod;

/// Largest `grid.n2` accepted before any memory estimate.
pub const MAX_N2: usize = 10_000_000;
/// Largest `grid.n3` accepted before any memory estimate.
pub const MAX_N3: usize = 1_000_000;
/// Largest `membrane.samples` (as in the membrane models).
pub const MAX_SAMPLES: usize = 10_000_000;
/// Sample points at which obstacle expressions are checked finite on the contact interval.
pub(super) const EXPRESSION_CHECK_SAMPLES: usize = 1025;

/// A conservative estimate of the peak memory of a thick-body contact solve, by the
/// boundary-only solver (`condensed`, `solver.nonlinear = newton`) or the full-system solvers.
///
/// # Math
/// ```text
/// N     = 2 n2 n3                          unknowns (plane strain)
/// bytes = 190 w N log2(N)                 sparse system (w: the method's memory_width,
///                                          2 for fem-q2, 4 for fem-qp), Jacobian and multifrontal LU
///       + 2^27                             factors (nested dissection): fits the measured
///                                          VmHWM of `capstan contact` (fd, default scene)
///                                          from above: full-newton 1.12 GB / 4.70 GB /
///                                          19.9 GB at 1000x161 / 2000x321 / 4000x640,
///                                          condensed 1.65 GB at 1000x161 (8-12% margin)
///   condensed only:
///       + 32 n2^2                          four dense m x m condensed matrices, m ~ n2
///       + 2^29                             the condensation's blocks of right-hand sides,
///                                          residuals and corrections
/// ```
/// Not covered: a matrix whose pivots leave the multifrontal fronts falls back to faer's
/// supernodal LU, which needs up to ~2.3x more (see `capstan_solvers::LuKind`).
pub fn memory_estimate(n2: usize, n3: usize, method: DiscretisationMethod, condensed: bool) -> f64 {
    let (n2, n3) = (n2 as f64, n3 as f64);
    let unknowns = 2.0 * n2 * n3;
    // the method's own factor (fem-q2 2, fem-qp 4: wider element couplings, the fill of the
    // element nested dissection grows ~ p); 1 for a method the registry no longer builds
    let width = method
        .scheme(&Default::default())
        .map_or(1.0, |s| s.memory_width());
    let system =
        MEMORY_BYTES_PER_N_LOG_N * width * unknowns * unknowns.log2().max(1.0) + 134_217_728.0;
    if condensed {
        system + 32.0 * n2 * n2 + 536_870_912.0
    } else {
        system
    }
}

/// The constant of [`memory_estimate`]: bytes per `N log2 N`.
pub const MEMORY_BYTES_PER_N_LOG_N: f64 = 190.0;

/// `MemAvailable` from `/proc/meminfo`, in bytes; `None` where there is no such file.
pub fn available_memory() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024.0)
}

/// Bytes in human units (`1.2 GiB`).
pub fn human_bytes(bytes: f64) -> String {
    const UNITS: [&str; 5] = ["B", "KiB", "MiB", "GiB", "TiB"];
    let mut b = bytes;
    let mut unit = 0;
    while b >= 1024.0 && unit + 1 < UNITS.len() {
        b /= 1024.0;
        unit += 1;
    }
    format!("{b:.1} {}", UNITS[unit])
}

/// Bytes of sparse LU factors per `N^(4/3)` of a 3-D contact solve (`N` unknowns) of trilinear
/// (Q1) elements, fitted above the measured peaks (VmHWM, `capstan contact`, default scene,
/// boundary-only Newton): 17 x 65 x 17, 56,355 unknowns, 1.76 GiB (738 bytes per `N^(4/3)`
/// after the dense and fixed terms); bench_solid_contact, full-system Newton, 11 x 201 x 15,
/// 99,495 unknowns, VmHWM 1.88 GB, and 17 x 129 x 17, 111,843 unknowns, 2.59 GiB. At
/// 33 x 321 x 33 (1.05e6 unknowns) it is 77 GiB without the dense terms: refused on the 24 GiB
/// benchmark machine.
/// Elements of order `p` scale it by [`solid_fill_factor`].
pub const SOLID_BYTES_PER_N_4_3: f64 = 780.0;

/// How much more LU fill per `N^(4/3)` elements of order `p` make than Q1 (their wider
/// coupling: `(p + 1)^3` nodes an element), fitted above the measured peaks of the default
/// scene on 3-D bodies of about 60,000 unknowns (bytes per `N^(4/3)` of the LU term, with
/// `factor * 780` beside it): Q1 17 x 65 x 17 738 (780), Q2 17 x 65 x 17 985 (1,014), Qp3
/// 19 x 64 x 19 1,416 (1,560), Qp4 17 x 65 x 17 2,209 (2,418).
///
/// # Math
/// ```text
/// factor(p) = 1 + 0.1 (p - 1) + 0.2 (p - 1)^2
/// ```
pub fn solid_fill_factor(order: usize) -> f64 {
    let q = order.max(1) as f64 - 1.0;
    1.0 + 0.1 * q + 0.2 * q * q
}

/// The memory a 3-D contact solve on an `n1 x n2 x n3` grid of elements of order `order`
/// (1: Q1, 2: Q2, `p`: Qp) needs, bytes: the sparse LU
/// (`SOLID_BYTES_PER_N_4_3 solid_fill_factor(order) N^(4/3)`, `N = 3 n1 n2 n3`) plus 128 MiB,
/// and for the boundary-only solver (`condensed`) four dense `m x m` matrices (`P Z`, `N Z`,
/// the Newton matrix and its LU), `m = 2 n1 n2` contact unknowns.
pub fn solid_memory_estimate([n1, n2, n3]: [usize; 3], condensed: bool, order: usize) -> f64 {
    let n = (3 * n1 * n2 * n3) as f64;
    let m = (2 * n1 * n2) as f64;
    let dense = if condensed { 4.0 * 8.0 * m * m } else { 0.0 };
    let lu = SOLID_BYTES_PER_N_4_3 * solid_fill_factor(order) * n.powf(4.0 / 3.0);
    lu + dense + 128.0 * 1024.0 * 1024.0
}

/// Bytes per unknown of a 3-D contact solve with the iterative bulk solver
/// (`solver.linear = "multigrid"`), fitted above the measured peaks of `bench_solid_contact`
/// (see [`solid_multigrid_memory_estimate`]): VmHWM 1,107 MiB at 111,843 unknowns
/// (17 x 129 x 17 Q1) and 3,081 MiB at 301,875 (25 x 161 x 25), 10.9 KB per unknown between
/// the two, plus the 60 more GMRES vectors of the default restart (100) since; 11,203 MiB
/// at 1,048,707 (33 x 321 x 33) against 12.3 GiB estimated.
pub const SOLID_MULTIGRID_BYTES_PER_UNKNOWN: f64 = 12_500.0;

/// The memory a 3-D contact solve on an `n1 x n2 x n3` grid needs with the iterative bulk
/// solver, bytes: linear in the unknowns (no factorisation).
///
/// # Math
/// ```text
/// N     = 3 n1 n2 n3
/// bytes = SOLID_MULTIGRID_BYTES_PER_UNKNOWN N + 2^27
/// ```
/// The terms per unknown: about 81 stored entries per row (27 Q1 nodes x 3 components) in the
/// assembled bulk, the Jacobian on the extended pattern and its compressed-row copy
/// (16 + 24 + 16 bytes an entry), the element matrices of the assembly, the Galerkin levels
/// (1/7 of the fine level), 41 GMRES vectors and the multigrid work vectors.
pub fn solid_multigrid_memory_estimate([n1, n2, n3]: [usize; 3]) -> f64 {
    let n = (3 * n1 * n2 * n3) as f64;
    SOLID_MULTIGRID_BYTES_PER_UNKNOWN * n + 128.0 * 1024.0 * 1024.0
}

/// Bytes per fine unknown of a 3-D contact solve by the matrix-free Newton
/// (`solver.linear = "matrix-free-mg"`) with elements of `degree` (1: Q1, 2: Q2, `p`: Qp):
/// the Newton and GMRES(40) vectors, the operator's diagonal and right-hand sides, the
/// prolongation to the coarse level and the face terms; fitted with
/// [`SOLID_MATRIX_FREE_BYTES_PER_COARSE_UNKNOWN`] and [`SOLID_MATRIX_FREE_BYTES_PER_CHART_POINT`]
/// above the measured peaks (see [`solid_matrix_free_memory_estimate`]).
pub fn solid_matrix_free_bytes_per_unknown(degree: usize) -> f64 {
    // the fitted part plus the GMRES(40) basis at full length (41 vectors of 8 bytes), which
    // the 1e6 runs (at most 9 iterations a step) did not fill and the 1e7 run does
    let gmres = 41.0 * 8.0;
    match degree {
        0..=2 => 370.0 + gmres,
        _ => 920.0 + gmres,
    }
}

/// Bytes per unknown of the assembled Q1 coarse level of the matrix-free V-cycle (the
/// rediscretised operator while it is assembled, its compressed rows, the Galerkin levels
/// below it): fitted above the Q1 ellipse at aspect 1 (coarse level 1/8 of the unknowns) and
/// aspect 4 (1/2) together with [`solid_matrix_free_bytes_per_unknown`].
pub const SOLID_MATRIX_FREE_BYTES_PER_COARSE_UNKNOWN: f64 = 4_500.0;

/// Bytes per stored quadrature point of the chart (31 numbers of 8 bytes, held twice while
/// the operator is built): the whole body's points when the chart varies along `x1` (a cone),
/// one slab's on a prism.
pub const SOLID_MATRIX_FREE_BYTES_PER_CHART_POINT: f64 = 2.0 * 31.0 * 8.0;

/// The memory a 3-D contact solve on an `n1 x n2 x n3` grid of elements of `degree` needs
/// with the matrix-free Newton, bytes: linear in the fine unknowns, the coarse level's
/// unknowns and the stored chart points; no matrix of the fine level.
///
/// # Math
/// ```text
/// N      = 3 n1 n2 n3                       fine unknowns
/// N_c    = 3 prod(coarse_level_nodes(nodes, p, cell))   the assembled Q1 level
///          (capstan_elasticity::solid::coarse_level_nodes; cell: the body's cell sizes at its
///          centre, capstan_elasticity::solid::cell_sizes)
/// Q      = (n1 - 1)/p (n2 - 1)/p (n3 - 1)/p (p + 1)^3   chart points, or that / ((n1 - 1)/p)
///          when the chart does not vary along x1 (one slab stored)
/// bytes  = b(p) N + 4,500 N_c + 496 Q + 2^27
///          b = 370 + 328 (Q1, Q2), 920 + 328 (Qp, p >= 3; measured at p = 4)
/// ```
/// The 328 bytes are the GMRES(40) basis at full length (41 vectors): the 1e6 runs took at
/// most 9 Krylov iterations a Newton step and never filled it; the stopped 1e7 run
/// (65 x 801 x 65) had reached 10.24 GiB, above the estimate without them (9.3 GiB).
/// Fitted to the measured peaks (VmHWM of `capstan contact`, release, `full-newton` +
/// `matrix-free-mg`) at 1,048,707 unknowns (33 x 321 x 33), 12-16 % above each: the ellipse
/// `a = 2, b = 1.5` body of width 1 and thickness 1 (before the GMRES term) at Q1 1,011 MiB (N_c = N/7.5), Q2
/// 979 MiB, Qp4 1,020 MiB (its V-cycle then straight to Q1), Q1 of width 0.25 (aspect 4: the
/// coarse level halves x1 only, N_c = N/1.9) 2,509 MiB, and the cone band of
/// examples/scenes/contact_solid_cone.toml (chart stored whole, N_c = N/3.9) 2,497 MiB; at
/// 111,843 unknowns (17 x 129 x 17) the fixed 128 MiB puts the estimate 1.5-2.0x above the
/// peaks (142-308 MiB). Qp4 with the p-levels of its V-cycle
/// (`capstan_elasticity::solid::SolidMultigridParams::p_levels`: the Qp2 level's operator
/// and transfers) peaks higher, and the estimate still lies above (re-measured, GMRES term
/// included): 1,048,707 unknowns 1,203 MiB (`capstan contact`) and 1,274 MiB (every Newton
/// step solved to `1e-6`), the estimate (1,499 MiB) 1.25x and 1.18x above them; 111,843
/// 160 MiB (1.75x); 15,795 (9 x 65 x 9) 32 MiB against 151 MiB. See docs/solid.md.
pub fn solid_matrix_free_memory_estimate(
    nodes: [usize; 3],
    degree: usize,
    cell: [f64; 3],
    chart_varies_in_x1: bool,
) -> f64 {
    let n = (3 * nodes.iter().product::<usize>()) as f64;
    let coarse = 3 * capstan_elasticity::solid::coarse_level_nodes(nodes, degree, cell)
        .iter()
        .product::<usize>();
    let coarse = coarse as f64;
    let p = degree.max(1);
    let elements = nodes.map(|n| ((n - 1) / p).max(1));
    let slabs = if chart_varies_in_x1 { elements[0] } else { 1 };
    let points = (slabs * elements[1] * elements[2] * (p + 1).pow(3)) as f64;
    solid_matrix_free_bytes_per_unknown(degree) * n
        + SOLID_MATRIX_FREE_BYTES_PER_COARSE_UNKNOWN * coarse
        + SOLID_MATRIX_FREE_BYTES_PER_CHART_POINT * points
        + 128.0 * 1024.0 * 1024.0
}

/// The per-rank memory of a full-system solve with `solver.linear = "petsc"`: what every
/// rank holds whole, what is split over the ranks, and a fixed part, fitted above measured
/// per-rank peaks (maximum resident set of each rank).
///
/// # Math
/// ```text
/// bytes per rank (N unknowns, K ranks)      = replicated N + distributed N / K + fixed
/// bytes per node (L of the K ranks on it)   = L (replicated N + distributed N / K + fixed)
/// fewest ranks at one a node, budget B      = ceil(distributed N / (B - replicated N - fixed))
///                                             (none when B <= replicated N + fixed)
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PetscMemory {
    /// Bytes per unknown that every rank holds whatever the number of ranks.
    pub replicated: f64,
    /// Bytes per unknown split over the ranks (`1/K` of them on each).
    pub distributed: f64,
    /// Bytes per rank independent of the unknowns (the binary, PETSc and MPI themselves).
    pub fixed: f64,
}

impl PetscMemory {
    /// The peak memory of one of `ranks` ranks (0 is read as 1) solving `unknowns`, bytes.
    pub fn per_rank(&self, unknowns: usize, ranks: usize) -> f64 {
        let n = unknowns as f64;
        self.replicated * n + self.distributed * n / ranks.max(1) as f64 + self.fixed
    }

    /// The peak memory of the `local` ranks (of `ranks`) on one node together, bytes.
    pub fn per_node(&self, unknowns: usize, ranks: usize, local: usize) -> f64 {
        local.max(1) as f64 * self.per_rank(unknowns, ranks)
    }

    /// The fewest ranks, one a node, that fit `unknowns` in `budget` bytes a node; `None` when
    /// no number does (the replicated part and the fixed part alone exceed the budget).
    pub fn fewest_ranks(&self, unknowns: usize, budget: f64) -> Option<usize> {
        let n = unknowns as f64;
        let room = budget - self.replicated * n - self.fixed;
        if room <= 0.0 {
            return None;
        }
        let k = (self.distributed * n / room).ceil().max(1.0);
        (k < 1e12).then_some(k as usize)
    }
}

/// [`PetscMemory`] of the 3-D body, whose assembly is split over the ranks
/// (`ElementAssembly::for_rows`): each rank holds the element matrices, the pattern and the
/// Jacobian of its rows, PETSc's `MATMPIAIJ` copy of them, its share of the GAMG hierarchy
/// and of the GMRES(100) vectors (`distributed`); every rank holds the whole vectors of the
/// Newton iteration, the line search and the gathered residual (about 40 of them,
/// `replicated`). Fitted above the per-rank peaks (VmHWM) of the 3-D ellipse (Q1): 111,843
/// unknowns (17 x 129 x 17) 1,111 MiB on one rank and 629 MiB on each of two (9.0 KB a unknown
/// distributed; 147 MiB replicated and fixed together), and 1,048,707 unknowns
/// (33 x 321 x 33) 5,116 MiB on each of two after three Newton steps. The estimate lies
/// 11 %, 12 % and 8 % above the three; see docs/scale-out.md.
pub const PETSC_MEMORY_SOLID: PetscMemory = PetscMemory {
    replicated: 400.0,
    distributed: 10_000.0,
    fixed: 134_217_728.0,
};

/// [`PetscMemory`] of the plane-strain body, assembled whole on every rank (small by nature):
/// the model, its Jacobian on the extended pattern and the Newton vectors are `replicated`;
/// PETSc's `MATMPIAIJ` rows, GAMG and GMRES(100) are `distributed`. The first version's fit
/// (every rank holding the whole model, measured on the 3-D body at 111,843 unknowns: 9.0 KB
/// replicated, 0.97 KB distributed), kept as a bound from above: a 2-D run at 1000 x 161
/// (322,000 unknowns) had reached 981 MiB on one rank when stopped, a quarter of this
/// estimate; see docs/scale-out.md.
pub const PETSC_MEMORY_PLANE: PetscMemory = PetscMemory {
    replicated: 10_000.0,
    distributed: 1_500.0,
    fixed: 134_217_728.0,
};

/// The memory model of `solver.linear = "petsc"` on a body of `dimension` (3: the 3-D body,
/// [`PETSC_MEMORY_SOLID`]; otherwise plane strain, [`PETSC_MEMORY_PLANE`]).
pub fn petsc_memory(dimension: usize) -> PetscMemory {
    if dimension == 3 {
        PETSC_MEMORY_SOLID
    } else {
        PETSC_MEMORY_PLANE
    }
}

/// The peak memory of one rank of a full-system solve of `unknowns` unknowns on a body of
/// `dimension` with `solver.linear = "petsc"` on `ranks` MPI ranks, bytes
/// (`petsc_memory(dimension).per_rank(unknowns, ranks)`, see [`PetscMemory`]).
pub fn petsc_memory_estimate_per_rank(unknowns: usize, dimension: usize, ranks: usize) -> f64 {
    petsc_memory(dimension).per_rank(unknowns, ranks)
}

/// Why a `solver.linear = "petsc"` solve does not fit on its node (see [`petsc_memory_check`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PetscMemoryRefusal {
    /// Bytes one rank needs.
    pub per_rank: f64,
    /// Bytes the ranks of this node need together.
    pub per_node: f64,
    /// Bytes available on this node.
    pub available: f64,
    /// The fewest ranks, one a node, on which it would fit; `None` if on none.
    pub fewest_ranks: Option<usize>,
}

/// Whether `unknowns` on a body of `dimension` fit on `ranks` MPI ranks, `local` of them on
/// this node, with `available` bytes on the node (`None`: unknown, accepted): refused only
/// when the local ranks together need more than the node has.
///
/// # Errors
/// [`PetscMemoryRefusal`] with the per-rank and per-node needs and the fewest ranks (one a
/// node) that would fit.
pub fn petsc_memory_check(
    unknowns: usize,
    dimension: usize,
    ranks: usize,
    local: usize,
    available: Option<f64>,
) -> Result<(), PetscMemoryRefusal> {
    let model = petsc_memory(dimension);
    let per_node = model.per_node(unknowns, ranks, local);
    match available {
        Some(have) if per_node > have => Err(PetscMemoryRefusal {
            per_rank: model.per_rank(unknowns, ranks),
            per_node,
            available: have,
            fewest_ranks: model.fewest_ranks(unknowns, have),
        }),
        _ => Ok(()),
    }
}

/// The MPI ranks of this run and those of them on this node, from the launcher's environment
/// (Open MPI's `OMPI_COMM_WORLD_SIZE`, `OMPI_COMM_WORLD_LOCAL_SIZE`; Slurm's `SLURM_NTASKS`,
/// `SLURM_NTASKS_PER_NODE`); `(1, 1)` outside `mpirun`.
pub fn mpi_ranks() -> (usize, usize) {
    let var = |names: &[&str]| {
        names
            .iter()
            .find_map(|n| std::env::var(n).ok()?.trim().parse::<usize>().ok())
            .filter(|&k| k > 0)
    };
    let ranks = var(&["OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "SLURM_NTASKS"]).unwrap_or(1);
    let local = var(&[
        "OMPI_COMM_WORLD_LOCAL_SIZE",
        "MPI_LOCALNRANKS",
        "SLURM_NTASKS_PER_NODE",
    ])
    .unwrap_or(ranks)
    .min(ranks);
    (ranks, local)
}
