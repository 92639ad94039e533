//! The extended sparsity pattern of the full-system Jacobian: the bulk operator `A` plus the
//! friction entries of the contact rows.

use capstan_solvers::SparsityPattern;

use crate::contact::error::ContactError;
use crate::discretisation::ContactNode;
use crate::error::ElasticityError;

/// The entries of the contact sites: for each site with a free tangential row, its active
/// entries (indices into [`ContactModel::active`]); for each active entry, its site and its
/// place in the site.
#[derive(Debug, Clone)]
pub(crate) struct Sites {
    pub members: Vec<Vec<usize>>,
    /// `(site, position in the site)` per active entry.
    pub of_active: Vec<(usize, usize)>,
}

impl Sites {
    /// Groups the active entries by [`ContactNode::site`] (first appearance order).
    pub(crate) fn new(nodes: &[ContactNode], active: &[usize]) -> Result<Self, ContactError> {
        let mut index = std::collections::HashMap::new();
        let mut members: Vec<Vec<usize>> = Vec::new();
        let mut of_active = Vec::with_capacity(active.len());
        for (k, &a) in active.iter().enumerate() {
            let site = *index.entry(nodes[a].site).or_insert_with(|| {
                members.push(Vec::new());
                members.len() - 1
            });
            if members[site].len() == 2 {
                return Err(ContactError::from(ElasticityError::InvalidParameter {
                    field: "contact entries per site",
                    value: 3.0,
                    allowed: "1 or 2 (one per tangential direction)",
                }));
            }
            of_active.push((site, members[site].len()));
            members[site].push(k);
        }
        Ok(Self { members, of_active })
    }
}

/// The extended sparsity pattern: `A` plus every friction entry of the contact rows.
#[derive(Debug, Clone)]
pub(crate) struct ExtendedPattern {
    pub pattern: SparsityPattern,
    /// Slot in `pattern` of slot `k` of `A`.
    pub a_slot: Vec<usize>,
    /// Slot of `(tangential_row, tangential_dof)` per active node.
    pub tangential_slot: Vec<usize>,
    /// Slots of `(tangential_row, normal_stress.columns[..])` per active node.
    pub normal_slots: Vec<Vec<usize>>,
    /// Slot of `(tangential_row, tangential_dof of the other entry of the site)` per active
    /// entry (`None` on a site with one entry).
    pub partner_slot: Vec<Option<usize>>,
}

pub(crate) fn extended_pattern(
    a: &SparsityPattern,
    nodes: &[ContactNode],
    active: &[usize],
    sites: &Sites,
) -> Result<ExtendedPattern, ContactError> {
    // the friction entries, merged into `A`'s columns (`A`'s entries are not sorted again)
    let mut entries: Vec<(usize, usize)> = Vec::new();
    let mut marks = Vec::with_capacity(active.len());
    for &k in active {
        let node = &nodes[k];
        let row = node.tangential_row.expect("active");
        marks.push(entries.len());
        entries.push((row, node.tangential_dof));
        entries.extend(node.normal_stress.columns.iter().map(|&c| (row, c)));
    }
    let mut partner_marks = Vec::with_capacity(active.len());
    for (k, &(site, e)) in sites.of_active.iter().enumerate() {
        let members = &sites.members[site];
        if members.len() == 2 {
            let row = nodes[active[k]].tangential_row.expect("active");
            partner_marks.push(Some(entries.len()));
            entries.push((row, nodes[active[members[1 - e]]].tangential_dof));
        } else {
            partner_marks.push(None);
        }
    }
    let n = a.nrows();
    let (pattern, a_slot, slots) = a
        .with_entries(n, n, &entries)
        .map_err(crate::ElasticityError::from)?;
    let tangential_slot = marks.iter().map(|&m| slots[m]).collect();
    let normal_slots = active
        .iter()
        .zip(&marks)
        .map(|(&k, &m)| slots[m + 1..m + 1 + nodes[k].normal_stress.columns.len()].to_vec())
        .collect();
    let partner_slot = partner_marks
        .into_iter()
        .map(|m| m.map(|m| slots[m]))
        .collect();
    Ok(ExtendedPattern {
        pattern,
        a_slot,
        tangential_slot,
        normal_slots,
        partner_slot,
    })
}
