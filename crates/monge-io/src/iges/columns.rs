//! A degree-2 NURBS surface as the IGES writer goes through it: a column of
//! control points and weights at a time, held or computed as it is written.

use std::io;

use glam::DVec3;
use monge_core::cyclidic::{CyclidicNet, NurbsSurface};

/// What [`NurbsColumns::columns`] calls with each column: its control points
/// and weights.
pub type NurbsColumn<'a> = dyn FnMut(&[DVec3], &[f64]) -> io::Result<()> + 'a;

/// A degree-2 NURBS surface as [`write_iges`](crate::write_iges) writes it (§5.3): its control
/// points and weights a column (index along `v`) at a time, so that a surface
/// computed as it is written ([`CyclidicNet::nurbs_columns`]) is never held.
pub trait NurbsColumns {
    /// The number of control points along `u` and along `v`.
    fn size(&self) -> (usize, usize);

    /// The knots along `u` and along `v`.
    fn knots(&self) -> (Vec<f64>, Vec<f64>);

    /// Calls `column` with the control points and weights of every column,
    /// in order, each along `u`; stops at its first error.
    fn columns(&self, column: &mut NurbsColumn<'_>) -> io::Result<()>;
}

/// The surface as it is held.
impl NurbsColumns for NurbsSurface {
    fn size(&self) -> (usize, usize) {
        (self.rows, self.cols)
    }

    fn knots(&self) -> (Vec<f64>, Vec<f64>) {
        (self.knots_u.clone(), self.knots_v.clone())
    }

    fn columns(&self, column: &mut NurbsColumn<'_>) -> io::Result<()> {
        let n = self.rows.checked_mul(self.cols);
        if n != Some(self.control_points.len()) || n != Some(self.weights.len()) {
            let n = n.map_or("more than usize::MAX".into(), |n| n.to_string());
            return Err(io::Error::new(
                io::ErrorKind::InvalidInput,
                format!(
                    "{} × {} control points need {n} points and weights, got {} and {}",
                    self.rows,
                    self.cols,
                    self.control_points.len(),
                    self.weights.len()
                ),
            ));
        }
        let (mut points, mut weights) = (Vec::new(), Vec::new());
        for b in 0..self.cols {
            let at = (0..self.rows).map(|a| a * self.cols + b);
            points.clear();
            weights.clear();
            points.extend(at.clone().map(|k| self.control_points[k]));
            weights.extend(at.map(|k| self.weights[k]));
            column(&points, &weights)?;
        }
        Ok(())
    }
}

/// The net's surface ([`CyclidicNet::nurbs`]), computed as it is written.
impl NurbsColumns for CyclidicNet {
    fn size(&self) -> (usize, usize) {
        (2 * self.rows() - 1, 2 * self.cols() - 1)
    }

    fn knots(&self) -> (Vec<f64>, Vec<f64>) {
        self.nurbs_knots()
    }

    fn columns(&self, column: &mut NurbsColumn<'_>) -> io::Result<()> {
        self.nurbs_columns()
            .try_for_each(|(points, weights)| column(&points, &weights))
    }
}
