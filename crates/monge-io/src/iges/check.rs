//! What a surface must be for IGES to hold it: its size (the sequence numbers
//! of the lines), degrees and knots, and finite control points and weights,
//! checked a column at a time as the writer goes through them.

use std::cell::{Cell, RefCell};
use std::io;

use glam::DVec3;
use monge_core::cyclidic::NURBS_DEGREE;

use super::columns::{NurbsColumn, NurbsColumns};
use super::fields::MAX_SEQUENCE;

/// Why `lines` Parameter Data lines of a surface of `rows × cols` control
/// points cannot be written, if they cannot.
pub(super) fn check_lines(lines: usize, (rows, cols): (usize, usize)) -> Result<(), String> {
    if lines > MAX_SEQUENCE {
        return Err(format!(
            "the surface of {rows} × {cols} control points takes {lines} lines of parameter \
             data, more than the {MAX_SEQUENCE} that an IGES section can number: write fewer \
             patches (fewer guide samples), or another format"
        ));
    }
    Ok(())
}

/// Why `s` cannot be written, if its size or knots say so.
pub(super) fn check_shape(s: &(impl NurbsColumns + ?Sized)) -> Result<(), String> {
    let p = NURBS_DEGREE;
    let (rows, cols) = s.size();
    if rows <= p || cols <= p {
        return Err(format!(
            "a degree-{p} surface needs at least {} control points in each direction, got {rows} × {cols}",
            p + 1,
        ));
    }
    let (knots_u, knots_v) = s.knots();
    for (name, knots, count) in [("u", &knots_u, rows), ("v", &knots_v, cols)] {
        if knots.len() != count + p + 1 {
            return Err(format!(
                "{count} control points of degree {p} need {} knots along {name}, got {}",
                count + p + 1,
                knots.len()
            ));
        }
        if !knots.iter().all(|k| k.is_finite()) || knots.windows(2).any(|k| k[0] > k[1]) {
            return Err(format!(
                "the knots along {name} are not finite and non-decreasing"
            ));
        }
        if knots[p] >= knots[count] {
            return Err(format!("the knot domain along {name} is empty"));
        }
    }
    Ok(())
}

/// A surface whose columns are checked ([`ColumnCheck`]) the first time
/// they are gone through, each before it is passed on.
pub(super) struct Checking<'s, S: ?Sized> {
    pub(super) surface: &'s S,
    pub(super) check: RefCell<ColumnCheck>,
    /// Times the columns have been gone through.
    pub(super) sweeps: Cell<usize>,
}

impl<S: NurbsColumns + ?Sized> NurbsColumns for Checking<'_, S> {
    fn size(&self) -> (usize, usize) {
        self.surface.size()
    }

    fn knots(&self) -> (Vec<f64>, Vec<f64>) {
        self.surface.knots()
    }

    fn columns(&self, column: &mut NurbsColumn<'_>) -> io::Result<()> {
        let first = self.sweeps.replace(self.sweeps.get() + 1) == 0;
        self.surface.columns(&mut |points, weights| {
            if first {
                let mut check = self.check.borrow_mut();
                check
                    .column(points, weights)
                    .map_err(|m| io::Error::new(io::ErrorKind::InvalidInput, m))?;
            }
            column(points, weights)
        })
    }
}

/// What the writer needs of the control points, found a column at a time.
pub(super) struct ColumnCheck {
    rows: usize,
    cols: usize,
    /// Columns seen.
    columns: usize,
    /// The first column, to compare with the last.
    first: Vec<DVec3>,
    /// The first weight, to compare with every other.
    first_weight: Option<f64>,
    checked: Checked,
}

/// What [`ColumnCheck`] finds of a surface that can be written.
pub(super) struct Checked {
    /// The largest absolute control point coordinate.
    pub(super) max_coordinate: f64,
    /// The largest coordinate difference between the first and the last row
    /// of control points (closed along `u` within the resolution).
    pub(super) closing_u: f64,
    /// The same between the first and the last column.
    pub(super) closing_v: f64,
    /// All weights equal.
    pub(super) polynomial: bool,
}

impl ColumnCheck {
    pub(super) fn new((rows, cols): (usize, usize)) -> Self {
        ColumnCheck {
            rows,
            cols,
            columns: 0,
            first: Vec::new(),
            first_weight: None,
            checked: Checked {
                max_coordinate: 0.0,
                closing_u: 0.0,
                closing_v: 0.0,
                polynomial: true,
            },
        }
    }

    /// Takes the next column in, or says why the surface cannot be written.
    pub(super) fn column(&mut self, points: &[DVec3], weights: &[f64]) -> Result<(), String> {
        let (rows, cols, k) = (self.rows, self.cols, self.columns);
        if points.len() != rows || weights.len() != rows {
            return Err(format!(
                "{rows} × {cols} control points need {rows} points and weights a column, \
                 got {} and {} in column {k}",
                points.len(),
                weights.len()
            ));
        }
        if !points.iter().all(|q| q.is_finite()) {
            return Err("a control point is not finite".into());
        }
        if !weights.iter().all(|&w| w.is_finite() && w > 0.0) {
            return Err("a weight is not a positive finite number".into());
        }
        let difference = |x: DVec3, y: DVec3| (x - y).abs().max_element();
        let c = &mut self.checked;
        for q in points {
            c.max_coordinate = c.max_coordinate.max(q.abs().max_element());
        }
        c.closing_u = c.closing_u.max(difference(points[0], points[rows - 1]));
        let w0 = *self.first_weight.get_or_insert(weights[0]);
        c.polynomial &= weights.iter().all(|&w| w == w0);
        if k == 0 {
            self.first = points.to_vec();
        }
        if k + 1 == cols {
            c.closing_v = (self.first.iter().zip(points))
                .map(|(x, y)| difference(*x, *y))
                .fold(0.0, f64::max);
        }
        self.columns += 1;
        Ok(())
    }

    /// What was found, once every column is in.
    pub(super) fn finish(self) -> Result<Checked, String> {
        if self.columns != self.cols {
            return Err(format!(
                "{} × {} control points need {} columns, got {}",
                self.rows, self.cols, self.cols, self.columns
            ));
        }
        Ok(self.checked)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn more_lines_than_a_section_can_number_are_refused() {
        // 1415 × 1415 faces of cyclidic patches: 2831 × 2831 control points,
        // about 10.7 million lines (what the first pass counts).
        assert!(check_lines(MAX_SEQUENCE, (2831, 2831)).is_ok());
        let e = check_lines(10_700_000, (2831, 2831)).unwrap_err();
        assert!(
            e.contains("2831 × 2831 control points takes 10700000 lines")
                && e.contains("more than the 9999999")
                && e.contains("fewer guide samples"),
            "{e}"
        );
    }
}
