//! The multi-patch design file (§4.7): its patches, each a first patch with two
//! guides or a later one attached to an earlier one, its fit and its symmetries.

use serde::{Deserialize, Serialize};

use crate::design::{GuideSpec, Tolerances};
use crate::symmetry::SymmetrySpec;

use super::fit_spec::FitSpec;
use super::side::Attach;

/// One patch of a multi-patch design (§4.7).
///
/// The first patch gives `guide_u` and `guide_v` (a [`Design`](crate::design::Design)'s guides); every
/// other patch gives `attach` and either `guide`, the continuation, or `guide_from`,
/// the line of another earlier patch through the same corner (see the module docs).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PatchSpec {
    /// The patch's θ in degrees, in its own frame (README convention).
    pub theta_deg: f64,
    /// First patch only: its `guide_u`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub guide_u: Option<GuideSpec>,
    /// First patch only: its `guide_v`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub guide_v: Option<GuideSpec>,
    /// Later patches: the side of an earlier patch whose line is one guide.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub attach: Option<Attach>,
    /// Later patches: the continuation guide, starting at the boundary's first vertex.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub guide: Option<GuideSpec>,
    /// Later patches of a layout of several rows and columns of patches, instead of
    /// `guide`: the side of another earlier patch whose line is the other guide (a
    /// column side when `attach` is a row side, and the other way round); both lines
    /// start at the same vertex.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub guide_from: Option<Attach>,
}

/// A multi-patch design file (§4.7): patches, and optionally a fit (§4.7,
/// [`crate::optimise`]) and symmetries (§4.5, [`crate::symmetry`]).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MultiPatchDesign {
    /// The patches, first one first; each later one attaches to an earlier one.
    pub patches: Vec<PatchSpec>,
    /// Input tolerances of every patch (`None`: [`Tolerances::default`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tolerance: Option<Tolerances>,
    /// The fit run by `monge fit` ([`crate::optimise::fit`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fit: Option<FitSpec>,
    /// Mirrors and rotations applied, in order, to assemble the whole structure
    /// ([`crate::symmetry::assemble`]); empty: the multi-patch mesh alone.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub symmetry: Vec<SymmetrySpec>,
}
