//! Reading accessors with every bound checked. The gltf crate's own reader slices with
//! `count - 1` (an underflow for `count: 0`), asserts the element size in debug builds (a
//! POSITION declared SCALAR panics) and unwraps sparse values: a hostile file must give an
//! error naming the accessor instead, so the bytes are read here.

use ::gltf::accessor::sparse::IndexType;
use ::gltf::accessor::{Accessor, DataType, Dimensions};

/// The most elements one accessor may have (a view-less accessor allocates `count` zeros, so
/// its count is not bounded by the file's size).
const MAX_ELEMENTS: usize = 1 << 27;

/// As many elements as a view-less accessor may always have: at most 8 MiB even as MAT4.
const SMALL_VIEWLESS: usize = 1 << 16;

/// The bytes of every buffer, by buffer index, each cut to its declared `byteLength`, and the
/// most elements an accessor without a bufferView may have.
#[derive(Debug, Default)]
pub(super) struct Buffers {
    pub(super) data: Vec<Vec<u8>>,
    /// The longest run of elements the file's bytes hold: the largest count of an accessor with
    /// a bufferView or of a sparse substitution, each at most its view's byte length, and at
    /// least `SMALL_VIEWLESS`. A
    /// view-less accessor (zeros, perhaps with sparse values) is filled to its count, which
    /// nothing else bounds: a few bytes of JSON must not allocate gigabytes.
    pub(super) longest_with_data: usize,
}

impl Buffers {
    pub(super) fn new(gltf: &::gltf::Gltf, data: Vec<Vec<u8>>) -> Self {
        let with_data = gltf.accessors().flat_map(|a| {
            let viewed = a.view().map(|v| a.count().min(v.length()));
            let sparse = a.sparse().map(|s| s.count().min(s.indices().view().length()));
            viewed.into_iter().chain(sparse)
        });
        // A short run costs nothing whatever backs it (3 zeros and 2 sparse values are valid glTF).
        Self { data, longest_with_data: with_data.max().unwrap_or(0).max(SMALL_VIEWLESS) }
    }
}

/// What an accessor must hold to be read as a given attribute.
#[derive(Clone, Copy, Debug)]
pub(super) enum Expect {
    /// VEC3 of FLOAT, or of bytes or shorts, normalised or not (POSITION, NORMAL and their
    /// morph displacements; the integers are KHR_mesh_quantization's).
    Vec3,
    /// SCALAR of UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT (indices).
    Index,
    /// VEC2 of FLOAT, or normalised UNSIGNED_BYTE / UNSIGNED_SHORT (TEXCOORD_n).
    Vec2Uv,
    /// MAT4 of FLOAT (a skin's inverseBindMatrices).
    Mat4F32,
    /// VEC4 of UNSIGNED_BYTE or UNSIGNED_SHORT (JOINTS_n).
    Joints,
    /// VEC4 of FLOAT, or normalised UNSIGNED_BYTE / UNSIGNED_SHORT (WEIGHTS_n).
    Weights,
    /// VEC3 or VEC4 of FLOAT, or of normalised UNSIGNED_BYTE / UNSIGNED_SHORT (COLOR_n).
    Colour,
    /// VEC4 of FLOAT, or of normalised BYTE / SHORT (an instance's ROTATION quaternion).
    Rotation,
}

impl Expect {
    fn allows(self, dims: Dimensions, ty: DataType, normalized: bool) -> bool {
        match self {
            Self::Vec3 => dims == Dimensions::Vec3 && ty != DataType::U32,
            Self::Index => dims == Dimensions::Scalar && matches!(ty, DataType::U8 | DataType::U16 | DataType::U32),
            // Unnormalised and signed integers are KHR_mesh_quantization's.
            Self::Vec2Uv => dims == Dimensions::Vec2 && ty != DataType::U32,
            Self::Mat4F32 => dims == Dimensions::Mat4 && ty == DataType::F32,
            Self::Joints => dims == Dimensions::Vec4 && !normalized && matches!(ty, DataType::U8 | DataType::U16),
            Self::Weights => {
                dims == Dimensions::Vec4
                    && (ty == DataType::F32 || (normalized && matches!(ty, DataType::U8 | DataType::U16)))
            }
            Self::Colour => {
                matches!(dims, Dimensions::Vec3 | Dimensions::Vec4)
                    && (ty == DataType::F32 || (normalized && matches!(ty, DataType::U8 | DataType::U16)))
            }
            Self::Rotation => {
                dims == Dimensions::Vec4
                    && (ty == DataType::F32 || (normalized && matches!(ty, DataType::I8 | DataType::I16)))
            }
        }
    }

    fn wanted(self) -> &'static str {
        match self {
            Self::Vec3 => "VEC3 of FLOAT, BYTE, UNSIGNED_BYTE, SHORT or UNSIGNED_SHORT",
            Self::Index => "SCALAR of UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT",
            Self::Vec2Uv => "VEC2 of FLOAT, BYTE, UNSIGNED_BYTE, SHORT or UNSIGNED_SHORT",
            Self::Mat4F32 => "MAT4 of FLOAT",
            Self::Joints => "VEC4 of UNSIGNED_BYTE or UNSIGNED_SHORT",
            Self::Weights => "VEC4 of FLOAT or normalized UNSIGNED_BYTE/UNSIGNED_SHORT",
            Self::Colour => "VEC3 or VEC4 of FLOAT or normalized UNSIGNED_BYTE/UNSIGNED_SHORT",
            Self::Rotation => "VEC4 of FLOAT or normalized BYTE/SHORT",
        }
    }
}

fn component_size(ty: DataType) -> usize {
    match ty {
        DataType::I8 | DataType::U8 => 1,
        DataType::I16 | DataType::U16 => 2,
        DataType::U32 | DataType::F32 => 4,
    }
}

fn dimension_count(d: Dimensions) -> usize {
    match d {
        Dimensions::Scalar => 1,
        Dimensions::Vec2 => 2,
        Dimensions::Vec3 => 3,
        Dimensions::Vec4 | Dimensions::Mat2 => 4,
        Dimensions::Mat3 => 9,
        Dimensions::Mat4 => 16,
    }
}

/// One component as f64: floats as stored, integers as themselves or, where `normalized`,
/// mapped to [0, 1] as the glTF spec defines for unsigned types.
fn component(bytes: &[u8], ty: DataType, normalized: bool) -> f64 {
    let int = |v: f64, max: f64| if normalized { v / max } else { v };
    match ty {
        DataType::F32 => f64::from(f32::from_le_bytes([bytes[0], bytes[1], bytes[2], bytes[3]])),
        DataType::U8 => int(f64::from(bytes[0]), 255.0),
        DataType::I8 => int(f64::from(i8::from_le_bytes([bytes[0]])), 127.0).max(-1.0),
        DataType::U16 => int(f64::from(u16::from_le_bytes([bytes[0], bytes[1]])), 65535.0),
        DataType::I16 => int(f64::from(i16::from_le_bytes([bytes[0], bytes[1]])), 32767.0).max(-1.0),
        DataType::U32 => f64::from(u32::from_le_bytes([bytes[0], bytes[1], bytes[2], bytes[3]])),
    }
}

/// The bytes of `view` (a bufferView), checked against its buffer's real length.
pub(super) fn view_bytes<'b>(view: &::gltf::buffer::View<'_>, buffers: &'b Buffers) -> Result<&'b [u8], String> {
    let buffer = &buffers.data[view.buffer().index()];
    let end = view.offset().checked_add(view.length());
    end.and_then(|end| buffer.get(view.offset()..end)).ok_or_else(|| {
        format!(
            "bufferViews[{}] spans bytes {}..{}+{} of buffers[{}], which has {} bytes",
            view.index(),
            view.offset(),
            view.offset(),
            view.length(),
            view.buffer().index(),
            buffer.len()
        )
    })
}

/// `count` elements of `size` bytes from `data` at `offset` with `stride`, each as a slice.
fn strided(data: &[u8], offset: usize, stride: usize, size: usize, count: usize) -> Option<Vec<&[u8]>> {
    let last = stride.checked_mul(count.checked_sub(1)?)?.checked_add(offset)?;
    let end = last.checked_add(size)?;
    if end > data.len() {
        return None;
    }
    Some((0..count).map(|i| &data[offset + i * stride..offset + i * stride + size]).collect())
}

/// Every element of `accessor` as `N` f64 components, sparse substitutions applied, after
/// checking that the accessor is of the kind `expect` names and lies inside its buffers.
fn read<const N: usize>(accessor: &Accessor<'_>, buffers: &Buffers, expect: Expect) -> Result<Vec<[f64; N]>, String> {
    let (dims, ty, normalized) = (accessor.dimensions(), accessor.data_type(), accessor.normalized());
    if !expect.allows(dims, ty, normalized) || dimension_count(dims) != N {
        return Err(format!(
            "accessors[{}] holds {dims:?} of {ty:?}{}; wanted {}",
            accessor.index(),
            if normalized { " (normalized)" } else { "" },
            expect.wanted()
        ));
    }
    let count = accessor.count();
    if count == 0 || count > MAX_ELEMENTS {
        return Err(format!("accessors[{}].count is {count}; allowed 1..={MAX_ELEMENTS}", accessor.index()));
    }
    let csize = component_size(ty);
    let size = csize * N;
    let decode = |bytes: &[u8]| -> [f64; N] { std::array::from_fn(|k| component(&bytes[k * csize..], ty, normalized)) };
    let mut out = match accessor.view() {
        Some(view) => {
            let stride = view.stride().unwrap_or(size);
            if stride < size {
                return Err(format!(
                    "bufferViews[{}].byteStride {stride} is smaller than the {size}-byte elements of accessors[{}]",
                    view.index(),
                    accessor.index()
                ));
            }
            // glTF 2.0 §3.6.2.4: components start at multiples of their size. Read from a
            // misaligned offset, floats came out as garbage that was refused for another cause
            // ("the model's largest side is 3.559e-43"; a tester).
            let start = view.offset() + accessor.offset();
            if !accessor.offset().is_multiple_of(csize) || !start.is_multiple_of(csize) {
                return Err(format!(
                    "accessors[{}].byteOffset {} (byte {start} of buffers[{}] with bufferViews[{}].byteOffset {}) is \
                     not a multiple of its {csize}-byte components, as glTF 2.0 requires (§3.6.2.4, data alignment)",
                    accessor.index(),
                    accessor.offset(),
                    view.buffer().index(),
                    view.index(),
                    view.offset()
                ));
            }
            if !stride.is_multiple_of(csize) {
                return Err(format!(
                    "bufferViews[{}].byteStride {stride} is not a multiple of the {csize}-byte components of \
                     accessors[{}], as glTF 2.0 requires",
                    view.index(),
                    accessor.index()
                ));
            }
            let data = view_bytes(&view, buffers)?;
            strided(data, accessor.offset(), stride, size, count)
                .ok_or_else(|| {
                    format!(
                        "accessors[{}]: {count} elements of {size} bytes from byteOffset {} with stride {stride} \
                         do not fit in the {} bytes of bufferViews[{}]",
                        accessor.index(),
                        accessor.offset(),
                        data.len(),
                        view.index()
                    )
                })?
                .into_iter()
                .map(decode)
                .collect()
        }
        None if count > buffers.longest_with_data => {
            return Err(format!(
                "accessors[{}] has no bufferView and a count of {count}; an accessor without data may have at \
                 most {} elements (as many as the longest one with data in this file, and {SMALL_VIEWLESS} at least)",
                accessor.index(),
                buffers.longest_with_data
            ));
        }
        None => vec![[0.0; N]; count],
    };
    if let Some(sparse) = accessor.sparse() {
        let n = sparse.count();
        let where_ = || format!("accessors[{}].sparse", accessor.index());
        if n == 0 || n > count {
            return Err(format!("{}.count is {n}; allowed 1..={count}", where_()));
        }
        let indices = sparse.indices();
        let isize = match indices.index_type() {
            IndexType::U8 => 1,
            IndexType::U16 => 2,
            IndexType::U32 => 4,
        };
        let idata = view_bytes(&indices.view(), buffers)?;
        let index_slices = strided(idata, indices.offset(), isize, isize, n)
            .ok_or_else(|| format!("{}.indices do not fit in bufferViews[{}]", where_(), indices.view().index()))?;
        let values = sparse.values();
        let vdata = view_bytes(&values.view(), buffers)?;
        let value_slices = strided(vdata, values.offset(), size, size, n)
            .ok_or_else(|| format!("{}.values do not fit in bufferViews[{}]", where_(), values.view().index()))?;
        for (ib, vb) in index_slices.into_iter().zip(value_slices) {
            let i = match isize {
                1 => usize::from(ib[0]),
                2 => usize::from(u16::from_le_bytes([ib[0], ib[1]])),
                _ => u32::from_le_bytes([ib[0], ib[1], ib[2], ib[3]]) as usize,
            };
            let slot = out.get_mut(i).ok_or_else(|| format!("{}: index {i} is beyond count {count}", where_()))?;
            *slot = decode(vb);
        }
    }
    Ok(out)
}

/// POSITION or NORMAL: VEC3 of FLOAT widened exactly to f64, or quantised integers (their
/// values, or mapped to [−1, 1] / [0, 1] where normalised).
pub(super) fn read_vec3(accessor: &Accessor<'_>, buffers: &Buffers) -> Result<Vec<[f64; 3]>, String> {
    read::<3>(accessor, buffers, Expect::Vec3)
}

/// TEXCOORD_n: VEC2 of FLOAT or integers (normalised ones mapped to [0, 1] or [−1, 1]).
pub(super) fn read_uv(accessor: &Accessor<'_>, buffers: &Buffers) -> Result<Vec<[f64; 2]>, String> {
    read::<2>(accessor, buffers, Expect::Vec2Uv)
}

/// A skin's inverseBindMatrices: MAT4 of FLOAT, column-major as glTF stores them.
pub(super) fn read_mat4(accessor: &Accessor<'_>, buffers: &Buffers) -> Result<Vec<glint_scene::Mat4>, String> {
    let matrices = read::<16>(accessor, buffers, Expect::Mat4F32)?;
    Ok(matrices
        .into_iter()
        .map(|m| glint_scene::Mat4(std::array::from_fn(|c| std::array::from_fn(|r| m[4 * c + r]))))
        .collect())
}

/// JOINTS_n: four joint indices a vertex.
pub(super) fn read_joints(accessor: &Accessor<'_>, buffers: &Buffers) -> Result<Vec<[u32; 4]>, String> {
    // Exact: unsigned integers of at most 16 bits.
    Ok(read::<4>(accessor, buffers, Expect::Joints)?.into_iter().map(|j| j.map(|v| v as u32)).collect())
}

/// WEIGHTS_n: four joint weights a vertex (normalised integers mapped to [0, 1]).
pub(super) fn read_weights(accessor: &Accessor<'_>, buffers: &Buffers) -> Result<Vec<[f64; 4]>, String> {
    read::<4>(accessor, buffers, Expect::Weights)
}

/// COLOR_n: linear RGB, from VEC3 or VEC4 of FLOAT or normalised integers. A VEC4's alpha is
/// left out, as baseColorFactor's is: Glint's surfaces are opaque.
pub(super) fn read_colours(accessor: &Accessor<'_>, buffers: &Buffers) -> Result<Vec<[f64; 3]>, String> {
    if accessor.dimensions() == Dimensions::Vec4 {
        return Ok(read::<4>(accessor, buffers, Expect::Colour)?.into_iter().map(|[r, g, b, _]| [r, g, b]).collect());
    }
    read::<3>(accessor, buffers, Expect::Colour)
}

/// An instance's ROTATION: quaternions (x, y, z, w), normalised integers mapped to [−1, 1].
pub(super) fn read_rotations(accessor: &Accessor<'_>, buffers: &Buffers) -> Result<Vec<[f64; 4]>, String> {
    read::<4>(accessor, buffers, Expect::Rotation)
}

/// Indices as u32.
pub(super) fn read_indices(accessor: &Accessor<'_>, buffers: &Buffers) -> Result<Vec<u32>, String> {
    // Exact: the values are unsigned integers of at most 32 bits.
    Ok(read::<1>(accessor, buffers, Expect::Index)?.into_iter().map(|[v]| v as u32).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strided_refuses_what_does_not_fit_and_never_underflows() {
        let data = [0u8; 24];
        assert_eq!(strided(&data, 0, 12, 12, 2).map(|v| v.len()), Some(2));
        assert!(strided(&data, 1, 12, 12, 2).is_none(), "one byte past the end");
        assert!(strided(&data, 0, 12, 12, 0).is_none(), "count 0");
        assert!(strided(&data, 0, usize::MAX, 12, 3).is_none(), "overflowing stride");
    }

    #[test]
    fn normalized_components_map_to_unit_range() {
        assert_eq!(component(&[255], DataType::U8, true), 1.0);
        assert_eq!(component(&[0xff, 0xff], DataType::U16, true), 1.0);
        assert_eq!(component(&[0x80], DataType::I8, true), -1.0, "-128 clamps to -1 as the spec says");
        assert_eq!(component(&7u32.to_le_bytes(), DataType::U32, false), 7.0);
    }
}
