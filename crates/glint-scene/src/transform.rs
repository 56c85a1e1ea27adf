//! Transforms composed in f64: glTF node hierarchies and a scene's model placements (the
//! stored f32 values widened exactly), so a deep hierarchy rounds once, when the vertices are
//! stored as f32 (relative to the scene's storage origin), not once a level.

/// A 4×4 affine matrix, column-major as glTF writes it: `m[column][row]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mat4(pub [[f64; 4]; 4]);

/// The length of the quaternion [x, y, z, w] where it is no rotation: not finite, or farther
/// than 1e-3 from 1 (within it, exporters' f32 rounding, it is read normalised). A scene file's
/// `quaternion` and a glTF node's `rotation` are held to it alike.
pub fn not_unit_quaternion(q: [f64; 4]) -> Option<f64> {
    let len = q.iter().map(|c| c * c).sum::<f64>().sqrt();
    (!(len.is_finite() && (len - 1.0).abs() < 1e-3)).then_some(len)
}

impl Mat4 {
    pub const IDENTITY: Self =
        Self([[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]]);

    /// The rotation of the quaternion [x, y, z, w] (normalised here first).
    pub fn from_quaternion(q: [f64; 4]) -> Self {
        let len = q.iter().map(|c| c * c).sum::<f64>().sqrt();
        let [x, y, z, w] = q.map(|c| c / len);
        Self([
            [1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y + z * w), 2.0 * (x * z - y * w), 0.0],
            [2.0 * (x * y - z * w), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z + x * w), 0.0],
            [2.0 * (x * z + y * w), 2.0 * (y * z - x * w), 1.0 - 2.0 * (x * x + y * y), 0.0],
            [0.0, 0.0, 0.0, 1.0],
        ])
    }

    /// `self · rhs`.
    pub fn mul(&self, rhs: &Self) -> Self {
        Self(std::array::from_fn(|c| std::array::from_fn(|r| (0..4).map(|k| self.0[k][r] * rhs.0[c][k]).sum())))
    }

    pub fn point(&self, p: [f64; 3]) -> [f64; 3] {
        std::array::from_fn(|r| self.0[0][r] * p[0] + self.0[1][r] * p[1] + self.0[2][r] * p[2] + self.0[3][r])
    }

    pub fn vector(&self, v: [f64; 3]) -> [f64; 3] {
        std::array::from_fn(|r| self.0[0][r] * v[0] + self.0[1][r] * v[1] + self.0[2][r] * v[2])
    }

    /// The determinant of the upper 3×3: negative for a mirroring transform, whose triangles
    /// change winding.
    pub fn determinant3(&self) -> f64 {
        let m = |c: usize, r: usize| self.0[c][r];
        m(0, 0) * (m(1, 1) * m(2, 2) - m(2, 1) * m(1, 2)) - m(1, 0) * (m(0, 1) * m(2, 2) - m(2, 1) * m(0, 2))
            + m(2, 0) * (m(0, 1) * m(1, 2) - m(1, 1) * m(0, 2))
    }

    /// The inverse transpose of the upper 3×3, up to a positive factor (the cofactor matrix):
    /// normals transformed by it and renormalised are exact for any invertible transform,
    /// non-uniform scale included; the determinant's sign keeps them on the same side.
    pub fn normal(&self, n: [f64; 3]) -> [f64; 3] {
        let m = |c: usize, r: usize| self.0[c][r];
        let cof = |r: usize, c: usize| {
            let (r1, r2) = ((r + 1) % 3, (r + 2) % 3);
            let (c1, c2) = ((c + 1) % 3, (c + 2) % 3);
            m(c1, r1) * m(c2, r2) - m(c2, r1) * m(c1, r2)
        };
        let sign = if self.determinant3() < 0.0 { -1.0 } else { 1.0 };
        std::array::from_fn(|r| sign * (0..3).map(|c| cof(r, c) * n[c]).sum::<f64>())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: [f64; 3], b: [f64; 3]) -> bool {
        a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-12)
    }

    #[test]
    fn normals_use_the_inverse_transpose_and_mirrors_flip_the_determinant() {
        let stretch = Mat4([[4.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]]);
        // The plane x + y = 0 has normal (1, 1, 0); stretched 4× in x it is x/4 + y = 0, normal (1, 4, 0).
        let n = stretch.normal([1.0, 1.0, 0.0]);
        assert!((n[1] / n[0] - 4.0).abs() < 1e-12 && n[2] == 0.0, "{n:?}");
        let mirror = Mat4([[-1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]]);
        assert!(mirror.determinant3() < 0.0);
        assert!(close(mirror.normal([1.0, 0.0, 0.0]), [-1.0, 0.0, 0.0]));
        assert_eq!(Mat4::IDENTITY.mul(&stretch), stretch);
    }
}
