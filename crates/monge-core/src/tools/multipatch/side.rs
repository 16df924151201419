//! The side of a patch whose line the next patch takes as a guide, and where a
//! patch is attached (§4.7).

use serde::{Deserialize, Serialize};

/// A side of a patch's grid whose line another patch takes as a guide (§4.7).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Side {
    /// Row 0, the patch's `guide_v`; the new patch continues `guide_u` backwards.
    FirstRow,
    /// Row `rows − 1`; the new patch continues `guide_u` forwards.
    LastRow,
    /// Column 0, the patch's `guide_u`; the new patch continues `guide_v` backwards.
    FirstColumn,
    /// Column `cols − 1`; the new patch continues `guide_v` forwards.
    LastColumn,
}

impl Side {
    /// Whether the side is a row (the patches then follow each other along `i`) (§4.7).
    pub fn is_row(self) -> bool {
        matches!(self, Side::FirstRow | Side::LastRow)
    }

    /// Whether the side is a last row or column (§4.7).
    pub fn is_last(self) -> bool {
        matches!(self, Side::LastRow | Side::LastColumn)
    }

    /// The side facing this one across the seam: the other patch's side there (§4.7).
    pub fn opposite(self) -> Side {
        match self {
            Side::FirstRow => Side::LastRow,
            Side::LastRow => Side::FirstRow,
            Side::FirstColumn => Side::LastColumn,
            Side::LastColumn => Side::FirstColumn,
        }
    }

    /// The name used in design files (§4.7).
    pub fn name(self) -> &'static str {
        match self {
            Side::FirstRow => "first_row",
            Side::LastRow => "last_row",
            Side::FirstColumn => "first_column",
            Side::LastColumn => "last_column",
        }
    }
}

/// Where a patch is attached: a side of an earlier patch (§4.7).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Attach {
    /// Index of the earlier patch in
    /// [`MultiPatchDesign::patches`](super::MultiPatchDesign::patches).
    pub patch: usize,
    /// Which of its sides.
    pub side: Side,
}
