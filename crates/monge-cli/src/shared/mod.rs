//! What the commands share: how a run ends ([`Outcome`]), printing and number
//! formats, argument parsers and kinds, the help texts' common paragraphs, the
//! warnings of a generated mesh, and pictures. Nothing here knows a command.

pub mod args;
pub mod help;
pub mod output;
pub mod picture;
pub mod warnings;

/// What a command that ran to completion found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// Everything as expected: exit status 0.
    Success,
    /// `check` found a metric above its tolerance, or `approximate` no design within its
    /// --tolerance: exit status 1.
    Failed,
}

/// The error of a command that works on a whole grid given a trimmed design (a design
/// and the outline its mesh is cut by, as `monge approximate` writes a trimmed result).
pub fn trimmed_design_refused(path: &std::path::Path, command: &str) -> anyhow::Error {
    anyhow::anyhow!(
        "`{}` is a trimmed design (a design and the outline its mesh is cut by): `monge {command}` \
         works on a whole grid. `monge generate` writes its mesh trimmed; for `{command}`, give \
         the design before trimming (the file's `design`) as a file of its own",
        path.display()
    )
}
