//! Paragraphs shared by the help texts of several commands.

/// The θ convention, in one line, shared by the help texts.
pub const THETA: &str = "θ (`theta_deg`, degrees, taken modulo 360 into (−180°, 180°]) places the \
pencil axis {tan(θ/2)·N_p + s·t_v} of the Gauss map (t_u, t_v the unit start tangents, \
N_p = t_u × t_v normalised): θ = 0 gives a moulding surface with guide_u as its rail, \
θ = ±180° one with guide_v as its rail, θ = +90° is singular.";

/// Exit statuses, shared by the help texts.
pub const EXIT: &str = "Exit status: 0 success; 1 `monge check` found a metric above --tol; \
2 any error (unreadable, malformed or invalid design or mesh, unwritable output, bad \
arguments), reported on stderr as `error: <message>`.";
