//! The owner rule in a form hardware can decide: slots.
//!
//! A pair found in several leaves is reported only by its owner, the first
//! leaf (in schedule order) that holds both triangles
//! ([`OctreeSchedule::owner`]). Deciding that needs each triangle's list of
//! leaves. Here every object gets a *slot table*: one slot per triangle per
//! leaf, a triangle's slots consecutive and in leaf order, each holding
//! the triangle's id, the leaf, and the triangle's first slot. A leaf's
//! arrays carry slot numbers instead of triangle ids, so a hit arrives as
//! two slots `(s_a, s_b)`, both of the leaf `L` that found it, and
//!
//! * if either slot is its triangle's first, that triangle is in no
//!   earlier leaf, so no earlier leaf holds both: `L` owns the pair;
//! * otherwise the two lists up to `L`, `a`'s slots `first_a ..= s_a` and
//!   `b`'s `first_b ..= s_b`, are merged (both ascending): the first leaf
//!   found in both is the first leaf holding both triangles, and `L` owns
//!   the pair exactly when that leaf is `L`. Both lists end with `L`, so
//!   the merge stops there at the latest, after at most
//!   `(s_a - first_a) + (s_b - first_b) + 1` comparisons, and never reads
//!   past `s_a` or `s_b`.
//!
//! That is [`OctreeSchedule::owner`]'s merge, cut at `L`: the same rule,
//! so the hardware that follows this model (`tritri_rtl::octree::
//! owner_filter`) reports each intersecting pair once, the pair the
//! software broad phase assigns to that leaf.

use super::octree::OctreeSchedule;
use super::TaggedTriangle;
use std::collections::HashMap;

/// One triangle in one of its leaves.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Slot {
    /// The triangle's id in its object (what the host gets back).
    pub id: u32,
    /// The leaf's index in schedule order.
    pub leaf: u32,
    /// The triangle's first slot (its first leaf's).
    pub first: u32,
}

/// The slot tables of both objects, and the slot of every entry of the
/// schedule's leaf arrays.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct OwnerSlots {
    pub a: Vec<Slot>,
    pub b: Vec<Slot>,
    /// `a_slot[i]`: the slot of `schedule.a[i]` (the id the leaf sends).
    pub a_slot: Vec<u32>,
    pub b_slot: Vec<u32>,
}

/// How the owner test of one pair ends, and how many comparisons of two
/// list entries it made (0 when a rank is 0).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct OwnerDecision {
    pub owner: bool,
    pub comparisons: u32,
}

impl OwnerSlots {
    /// The slot tables of `schedule`: triangles in order of their first
    /// leaf, each triangle's slots in leaf order.
    pub fn of(schedule: &OctreeSchedule) -> Self {
        let mut entry_leaf_a = vec![0u32; schedule.a.len()];
        let mut entry_leaf_b = vec![0u32; schedule.b.len()];
        for (k, leaf) in schedule.leaves.iter().enumerate() {
            entry_leaf_a[leaf.a.clone()].fill(k as u32);
            entry_leaf_b[leaf.b.clone()].fill(k as u32);
        }
        let (a, a_slot) = tables(schedule.a.iter().map(|t| t.id), &entry_leaf_a);
        let (b, b_slot) = tables(schedule.b.iter().map(|t| t.id), &entry_leaf_b);
        OwnerSlots {
            a,
            b,
            a_slot,
            b_slot,
        }
    }

    /// The schedule's leaf arrays with each triangle's slot as its id:
    /// what the hardware's memories hold, so that its hits come out as
    /// slots ([`super::PreparedScene::leaf_batches`] makes the batches).
    pub fn slotted(&self, schedule: &OctreeSchedule) -> (Vec<TaggedTriangle>, Vec<TaggedTriangle>) {
        let with = |arrays: &[TaggedTriangle], slots: &[u32]| {
            arrays
                .iter()
                .zip(slots)
                .map(|(t, &id)| TaggedTriangle { id, ..*t })
                .collect()
        };
        (
            with(&schedule.a, &self.a_slot),
            with(&schedule.b, &self.b_slot),
        )
    }

    /// The triangle ids of a hit's slots.
    pub fn ids(&self, s_a: u32, s_b: u32) -> (u32, u32) {
        (self.a[s_a as usize].id, self.b[s_b as usize].id)
    }

    /// The owner test of a hit `(s_a, s_b)` (two slots of one leaf), as
    /// the hardware makes it.
    pub fn decide(&self, s_a: u32, s_b: u32) -> OwnerDecision {
        let (x, y) = (self.a[s_a as usize], self.b[s_b as usize]);
        debug_assert_eq!(x.leaf, y.leaf, "a hit's two slots belong to one leaf");
        if x.first == s_a || y.first == s_b {
            return OwnerDecision {
                owner: true,
                comparisons: 0,
            };
        }
        let (mut i, mut j) = (x.first as usize, y.first as usize);
        let mut comparisons = 1;
        loop {
            let (p, q) = (self.a[i].leaf, self.b[j].leaf);
            if p == q {
                return OwnerDecision {
                    owner: p == x.leaf,
                    comparisons,
                };
            }
            if p < q {
                i += 1;
            } else {
                j += 1;
            }
            comparisons += 1;
        }
    }
}

/// One object's slot table from its concatenated leaf arrays (`ids`) and
/// the leaf of each entry (ascending, since leaves are concatenated in
/// order): the table and the slot of each entry.
fn tables(ids: impl Iterator<Item = u32>, entry_leaf: &[u32]) -> (Vec<Slot>, Vec<u32>) {
    let ids: Vec<u32> = ids.collect();
    // Each triangle's entries, triangles in order of first appearance.
    let mut order: Vec<u32> = Vec::new();
    let mut entries: HashMap<u32, Vec<usize>> = HashMap::new();
    for (i, &id) in ids.iter().enumerate() {
        entries.entry(id).or_insert_with(|| {
            order.push(id);
            Vec::new()
        });
        entries.get_mut(&id).expect("inserted above").push(i);
    }
    let mut table = Vec::with_capacity(ids.len());
    let mut slot_of_entry = vec![0u32; ids.len()];
    for id in order {
        let first = table.len() as u32;
        for &i in &entries[&id] {
            slot_of_entry[i] = table.len() as u32;
            table.push(Slot {
                id,
                leaf: entry_leaf[i],
                first,
            });
        }
    }
    (table, slot_of_entry)
}
