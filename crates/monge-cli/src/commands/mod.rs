//! The commands of `monge`, one file each: its arguments with their help text,
//! and `run`. A command uses what `crate::shared` offers, never another command.

pub mod align;
pub mod approximate;
pub mod bench;
pub mod check;
pub mod explore;
pub mod fabricate;
pub mod fit;
pub mod generate;
pub mod info;
pub mod optimise_panels;
pub mod patches;
pub mod render;
pub mod scan;
pub mod smooth;
