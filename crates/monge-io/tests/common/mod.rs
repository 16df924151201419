//! Helpers shared by the integration tests.

pub mod iges;

use glam::DVec3;
use monge_core::QuadGrid;

/// A deterministic xorshift generator.
pub struct Rng(pub u64);

impl Rng {
    pub fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    /// A finite f64 with random bits: every exponent and mantissa, sign, subnormals.
    pub fn any_finite(&mut self) -> f64 {
        loop {
            let x = f64::from_bits(self.next_u64());
            if x.is_finite() {
                return x;
            }
        }
    }

    /// A value in [-scale, scale) with random low bits.
    pub fn uniform(&mut self, scale: f64) -> f64 {
        ((self.next_u64() >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0) * scale
    }
}

/// A `rows × cols` grid of random coordinates (mixed random bit patterns and
/// ordinary values) with unit normals if `normals`.
pub fn random_grid(rows: usize, cols: usize, normals: bool, seed: u64) -> QuadGrid {
    let mut rng = Rng(seed);
    let n = rows * cols;
    let vertices = (0..n)
        .map(|k| {
            if k % 3 == 0 {
                DVec3::new(rng.any_finite(), rng.any_finite(), rng.any_finite())
            } else {
                DVec3::new(rng.uniform(10.0), rng.uniform(1e-3), rng.uniform(1e6))
            }
        })
        .collect();
    let normals = if normals {
        (0..n)
            .map(|_| DVec3::new(rng.uniform(1.0), rng.uniform(1.0), 1.0).normalize())
            .collect()
    } else {
        Vec::new()
    };
    QuadGrid::new(rows, cols, vertices, normals)
}

/// Bitwise equality of two grids (so -0.0 and 0.0 differ).
pub fn assert_bits_eq(a: &QuadGrid, b: &QuadGrid) {
    assert_eq!((a.rows, a.cols), (b.rows, b.cols));
    let bits = |v: &[DVec3]| -> Vec<[u64; 3]> {
        v.iter().map(|p| p.to_array().map(f64::to_bits)).collect()
    };
    assert_eq!(bits(&a.vertices), bits(&b.vertices));
    assert_eq!(bits(&a.normals), bits(&b.normals));
}
