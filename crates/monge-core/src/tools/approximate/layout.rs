//! The layout of an approximation by several patches (§4.7): how many patches along
//! guide_u and along guide_v.

use std::fmt;
use std::str::FromStr;

/// `u × v` patches: `u` along guide_u (rows of patches), `v` along guide_v (§4.7).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub struct PatchLayout {
    /// Patches along guide_u.
    pub u: usize,
    /// Patches along guide_v.
    pub v: usize,
}

impl PatchLayout {
    /// The number of patches, `u · v`.
    pub fn count(&self) -> usize {
        self.u * self.v
    }
}

impl fmt::Display for PatchLayout {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}x{}", self.u, self.v)
    }
}

/// `UxV` (e.g. `2x3`: 2 patches along guide_u, 3 along guide_v), or `K` for `Kx1`.
///
/// ```
/// use monge_core::approximate::PatchLayout;
/// assert_eq!("2x3".parse(), Ok(PatchLayout { u: 2, v: 3 }));
/// assert_eq!("3".parse(), Ok(PatchLayout { u: 3, v: 1 }));
/// assert!("0x2".parse::<PatchLayout>().is_err());
/// ```
impl FromStr for PatchLayout {
    type Err = String;

    fn from_str(text: &str) -> Result<Self, String> {
        let count = |s: &str| match s.trim().parse::<usize>() {
            Ok(n) if n >= 1 => Ok(n),
            _ => Err(format!(
                "`{s}` in `{text}` is not a number of patches (a whole number, at least 1); \
                 give K or UxV, e.g. 3 or 2x2"
            )),
        };
        match text.split_once(['x', 'X', '×']) {
            Some((u, v)) => Ok(PatchLayout {
                u: count(u)?,
                v: count(v)?,
            }),
            None => Ok(PatchLayout {
                u: count(text)?,
                v: 1,
            }),
        }
    }
}
