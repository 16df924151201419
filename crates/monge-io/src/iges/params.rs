//! An IGES entity's parameters, read one after another as integers, reals
//! and counts, with errors that name the line.

use glam::DVec3;

use crate::error::IoError;

/// File name in error messages of [`read_iges_surfaces`].
pub(super) const NO_FILE: &str = "<input>";

/// A parameter of an entity: its text (trimmed) and its line.
pub(super) struct Parameter {
    pub(super) text: String,
    pub(super) line: usize,
}

pub(super) fn syntax(line: usize, message: impl Into<String>) -> IoError {
    IoError::Syntax {
        file: NO_FILE.into(),
        line,
        message: message.into(),
    }
}

/// Reads an entity's parameters in order.
pub(super) struct Reader<'p> {
    pub(super) params: &'p [Parameter],
    pub(super) next: usize,
    pub(super) de: usize,
}

impl Reader<'_> {
    /// The line of the next parameter (of the last one if none is left).
    pub(super) fn line(&self) -> usize {
        self.params[self.next.min(self.params.len() - 1)].line
    }

    /// The next parameter, or a [`IoError::CountMismatch`].
    fn take(&mut self, what: &str) -> Result<&Parameter, IoError> {
        let found = self.params.len() - 1;
        let p = self
            .params
            .get(self.next)
            .ok_or_else(|| IoError::CountMismatch {
                file: NO_FILE.into(),
                what: format!(
                    "parameters of the entity at DE {} (line {}), up to its {what}",
                    self.de, self.params[0].line
                ),
                expected: self.next,
                found,
            })?;
        self.next += 1;
        Ok(p)
    }

    pub(super) fn entity_type(&mut self, expected: i64) -> Result<(), IoError> {
        let de = self.de;
        let p = self.take("entity type")?;
        if p.text.parse::<i64>().ok() != Some(expected) {
            return Err(syntax(
                p.line,
                format!(
                    "parameter data of DE {de} starts with `{}`; expected its entity type {expected}",
                    p.text
                ),
            ));
        }
        Ok(())
    }

    pub(super) fn integer(&mut self, name: &str) -> Result<usize, IoError> {
        let de = self.de;
        let p = self.take(name)?;
        p.text.parse().map_err(|_| {
            syntax(
                p.line,
                format!(
                    "{name} of the entity at DE {de} is `{}`, not a non-negative integer",
                    p.text
                ),
            )
        })
    }

    pub(super) fn real(&mut self, name: &str) -> Result<f64, IoError> {
        let de = self.de;
        let p = self.take(name)?;
        parse_real(&p.text).ok_or_else(|| {
            syntax(
                p.line,
                format!(
                    "{name} of the entity at DE {de} is `{}`, not a finite real number",
                    p.text
                ),
            )
        })
    }

    pub(super) fn point(&mut self, name: &str) -> Result<DVec3, IoError> {
        Ok(DVec3::new(
            self.real(name)?,
            self.real(name)?,
            self.real(name)?,
        ))
    }

    pub(super) fn row(&mut self) -> Result<[f64; 4], IoError> {
        let name = "transformation matrix entry";
        Ok([
            self.real(name)?,
            self.real(name)?,
            self.real(name)?,
            self.real(name)?,
        ])
    }

    /// `count` non-decreasing knots.
    pub(super) fn knots(&mut self, count: usize, name: &str) -> Result<Vec<f64>, IoError> {
        let mut knots: Vec<f64> = Vec::with_capacity(count);
        for _ in 0..count {
            let line = self.line();
            let k = self.real(&format!("{name} knot"))?;
            if knots.last().is_some_and(|&last| k < last) {
                return Err(syntax(
                    line,
                    format!(
                        "entity 128 at DE {}: {name} knot {k} is below the one before it",
                        self.de
                    ),
                ));
            }
            knots.push(k);
        }
        Ok(knots)
    }
}

/// An IGES real (`1.5`, `-2.`, `.5`, `1.5E3`, `1.5D-3`, `7`), if it is one and finite.
fn parse_real(text: &str) -> Option<f64> {
    let valid = !text.is_empty()
        && text.bytes().all(|b| {
            b.is_ascii_digit() || matches!(b, b'+' | b'-' | b'.' | b'E' | b'e' | b'D' | b'd')
        });
    if !valid {
        return None;
    }
    let x: f64 = text.replace(['D', 'd'], "E").parse().ok()?;
    x.is_finite().then_some(x)
}
