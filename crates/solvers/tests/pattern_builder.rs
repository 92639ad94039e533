//! Property test of the pattern builder: slots, duplicates and CSC invariants.

use capstan_solvers::SparsityPattern;
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};

fn config() -> Config {
    Config {
        cases: 128,
        rng_seed: RngSeed::Fixed(0x00c0_ffee),
        failure_persistence: None,
        ..Config::default()
    }
}

/// A matrix shape and up to 60 entries inside it (repeats are likely).
fn entries() -> impl Strategy<Value = (usize, usize, Vec<(usize, usize)>)> {
    (1usize..8, 1usize..8).prop_flat_map(|(nrows, ncols)| {
        (
            Just(nrows),
            Just(ncols),
            proptest::collection::vec((0..nrows, 0..ncols), 0..60),
        )
    })
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn builder_slots_round_trip_and_merge_duplicates((nrows, ncols, entries) in entries()) {
        let (pattern, slots) = SparsityPattern::from_entries(nrows, ncols, &entries).unwrap();
        prop_assert_eq!(slots.len(), entries.len());
        // CSC invariants: monotone column pointers, strictly increasing rows per column
        prop_assert_eq!(pattern.col_ptr().len(), ncols + 1);
        prop_assert_eq!(pattern.col_ptr()[ncols], pattern.nnz());
        for j in 0..ncols {
            let rows = pattern.column_rows(j);
            prop_assert!(rows.windows(2).all(|w| w[0] < w[1]));
            prop_assert!(rows.iter().all(|&r| r < nrows));
        }
        // every entry's slot holds that entry; equal entries share a slot
        for (k, &(r, c)) in entries.iter().enumerate() {
            prop_assert_eq!(pattern.slot(r, c), Some(slots[k]));
        }
        let mut distinct = entries.clone();
        distinct.sort_unstable();
        distinct.dedup();
        prop_assert_eq!(pattern.nnz(), distinct.len());
        // assembly by slots equals a dense sum of contributions
        let mut values = vec![0.0; pattern.nnz()];
        let mut dense = vec![0.0; nrows * ncols];
        for (k, &(r, c)) in entries.iter().enumerate() {
            let v = (k + 1) as f64;
            values[slots[k]] += v;
            dense[r * ncols + c] += v;
        }
        let x: Vec<f64> = (0..ncols).map(|j| 1.0 + j as f64).collect();
        let mut y = vec![0.0; nrows];
        pattern.matvec(&values, &x, &mut y);
        for i in 0..nrows {
            let expected: f64 = (0..ncols).map(|j| dense[i * ncols + j] * x[j]).sum();
            prop_assert_eq!(y[i], expected); // small integers: exact in f64
        }
    }
}
