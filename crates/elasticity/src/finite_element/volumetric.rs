//! How the volumetric (`lambda`) part of the element stiffness is integrated: with the
//! element's full Gauss rule, or selectively with a rule one order lower (the remedy for
//! volumetric locking as Poisson's ratio approaches 1/2).

/// The quadrature of the volumetric part of the stiffness (scene key
/// `discretisation.volumetric`): `full` (default) or `reduced` (selective reduced
/// integration, SRI).
///
/// # Math
/// The point energy of [`crate::finite_element::HighOrderNavier`] splits into a
/// volumetric and a shear part (the Lamé split of Hughes' selective integration):
/// ```text
/// a(v, w) = a_vol(v, w) + a_dev(v, w)
/// a_vol(v, w) = int lambda (div v) (div w) sqrt(g) dx2 dx3        div v = nabla_i v^i = tr M(v)
/// a_dev(v, w) = int 2 mu tr(M(v) M(w)) sqrt(g) dx2 dx3            M(v) = g^-1 E(v) (mixed strain)
/// ```
/// `full` integrates both with the element's `(k + 1) x (k + 1)` Gauss rule; `reduced`
/// integrates `a_dev` with it and `a_vol` with the `k x k` rule (Q1: 1 point, the element
/// centre; Q2: 2 x 2). The divergence `nabla_i v^i = d_i v^i + Gamma^i_im v^m` is the
/// curvilinear one, evaluated with the chart's Christoffel symbols at the reduced points, so
/// the split needs no Cartesian frame. SRI rather than B-bar: B-bar replaces the dilatational
/// part of `E_ij` by its projection (in curvilinear coordinates `g_ij` times the projected
/// divergence, inside the strain at every full point) and, for linear problems, is equivalent
/// to SRI of the bulk/deviatoric split (Hughes 1980); SRI of the Lamé split only changes which
/// points see the `lambda` term, with the traces `tr M_k` the point matrix already forms.
///
/// Why it works: as `nu -> 1/2`, `lambda = nu E / ((1 + nu)(1 - 2 nu))` grows without bound
/// and the discrete displacement is pushed toward fields with `div v = 0` at every volumetric
/// quadrature point. With the full rule that is `(k + 1)^2` constraints per element against
/// about `2 k^2` new degrees of freedom (`4 : 2` for Q1, `9 : 8` for Q2): too many, the
/// element locks (errors growing like `lambda / mu ~ 1 / (1 - 2 nu)`). The reduced rule
/// imposes `k^2` constraints (`1 : 2`, `4 : 8`), the constraint count of the mixed Q1-P0 and
/// Q2-Q1(disc.) elements it is equivalent to (Malkus–Hughes), and the displacement stays
/// accurate uniformly in `nu`.
///
/// Orders: the `k x k` Gauss rule is exact for degree `2k - 1` per direction, which is what
/// Ciarlet's criterion asks of a quadrature to keep the H1 order `k` and (Aubin–Nitsche) the L2
/// order `k + 1`; tested on the manufactured solutions and the Lamé cylinder.
///
/// Stresses: with the nodal-difference recovery of `fem-q1`, `fem-q2` the contact rows and the
/// nodal output take `lambda div v` from the reduced points (extrapolated to the nodes), not
/// from the pointwise divergence, which SRI leaves unpenalised; see
/// [`crate::finite_element::NodalRecovery::Differences`].
///
/// # References
/// T. J. R. Hughes, *The Finite Element Method*, §4.4 (selective reduced integration,
/// equivalence theorem of Malkus and Hughes, 1978).
#[derive(
    Debug, Clone, Copy, Default, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize,
)]
#[serde(rename_all = "kebab-case")]
pub enum VolumetricIntegration {
    /// The element's full `(k + 1) x (k + 1)` rule for the whole stiffness.
    #[default]
    Full,
    /// Selective reduced integration: the `lambda (div v)(div w)` term with the `k x k` rule.
    Reduced,
}

capstan_solvers::named_variants!(VolumetricIntegration {
    Full => "full",
    Reduced => "reduced",
});

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_default_is_full() {
        assert_eq!(
            VolumetricIntegration::default(),
            VolumetricIntegration::Full
        );
        for v in VolumetricIntegration::ALL {
            assert_eq!(VolumetricIntegration::from_name(v.name()), Some(v));
            assert_eq!(v.to_string(), v.name());
        }
        assert_eq!(VolumetricIntegration::from_name("selective"), None);
    }
}
