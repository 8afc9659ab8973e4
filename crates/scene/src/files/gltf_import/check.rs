//! What the `gltf` crate's readers take on trust, checked before they run: they assert that an
//! element fits its stride and hit `unreachable!` on component types the specification forbids,
//! so a malformed file would end the process instead of being an error.

use gltf::accessor::{DataType, Dimensions};

/// The (component type, element type, normalized) triples an attribute may have.
pub(super) type Kinds = &'static [(DataType, Dimensions, bool)];

/// `POSITION` and `NORMAL`: three floats.
pub(super) const VEC3_FLOAT: Kinds = &[(DataType::F32, Dimensions::Vec3, false)];
/// `TEXCOORD_n`: two floats, or two normalized unsigned bytes or shorts.
pub(super) const TEXCOORD: Kinds = &[
    (DataType::F32, Dimensions::Vec2, false),
    (DataType::U8, Dimensions::Vec2, true),
    (DataType::U16, Dimensions::Vec2, true),
];
/// Indices: one unsigned byte, short or int.
pub(super) const INDEX: Kinds = &[
    (DataType::U8, Dimensions::Scalar, false),
    (DataType::U16, Dimensions::Scalar, false),
    (DataType::U32, Dimensions::Scalar, false),
];

/// Checks that `accessor` (the `what` of a primitive, e.g. `POSITION`) is of one of the `kinds`
/// and that its elements lie inside its buffer view, and the view inside its buffer, whose data is
/// `buffers`. Errors start with the accessor, for the caller to put the primitive in front.
pub(super) fn accessor(
    accessor: &gltf::Accessor<'_>,
    what: &str,
    kinds: Kinds,
    buffers: &[Vec<u8>],
) -> Result<(), String> {
    let name = format!("its {what} accessor (accessor {})", accessor.index());
    let kind = (accessor.data_type(), accessor.dimensions(), accessor.normalized());
    if !kinds.contains(&kind) {
        let allowed: Vec<String> = kinds.iter().map(|&(c, d, n)| describe(c, d, n)).collect();
        return Err(format!("{name} is {}; {what} must be {}", describe(kind.0, kind.1, kind.2), allowed.join(" or ")));
    }
    if accessor.sparse().is_some() {
        return Err(format!("{name} is sparse, which is not supported"));
    }
    let Some(view) = accessor.view() else {
        return Err(format!("{name} has no bufferView"));
    };
    let count = accessor.count();
    if count == 0 {
        return Err(format!("{name} has a count of 0"));
    }
    let element = accessor.size();
    let stride = view.stride().unwrap_or(element);
    if stride < element {
        return Err(format!(
            "{name}: its bufferView {} has a byteStride of {stride} bytes, less than the {element} bytes of one element",
            view.index()
        ));
    }
    let needed = (count - 1)
        .checked_mul(stride)
        .and_then(|n| n.checked_add(element))
        .and_then(|n| n.checked_add(accessor.offset()));
    if needed.is_none_or(|n| n > view.length()) {
        return Err(format!(
            "{name}: its {count} elements from byte {} do not fit in its bufferView {} of {} bytes",
            accessor.offset(),
            view.index(),
            view.length()
        ));
    }
    view_in_buffer(&view, buffers).map_err(|e| format!("{name}: {e}"))
}

/// Checks that `view` lies inside its buffer, whose data is `buffers`.
pub(super) fn view_in_buffer(view: &gltf::buffer::View<'_>, buffers: &[Vec<u8>]) -> Result<(), String> {
    let buffer = view.buffer().index();
    let size = buffers.get(buffer).map_or(0, Vec::len);
    match view.offset().checked_add(view.length()) {
        Some(end) if end <= size => Ok(()),
        _ => Err(format!(
            "its bufferView {} (byteOffset {}, byteLength {}) reaches past the end of buffer {buffer} ({size} bytes)",
            view.index(),
            view.offset(),
            view.length()
        )),
    }
}

/// `VEC3 of FLOAT`, `VEC2 of normalized UNSIGNED_BYTE`, in the specification's words.
fn describe(component: DataType, dimensions: Dimensions, normalized: bool) -> String {
    let component = match component {
        DataType::I8 => "BYTE",
        DataType::U8 => "UNSIGNED_BYTE",
        DataType::I16 => "SHORT",
        DataType::U16 => "UNSIGNED_SHORT",
        DataType::U32 => "UNSIGNED_INT",
        DataType::F32 => "FLOAT",
    };
    let dimensions = match dimensions {
        Dimensions::Scalar => "SCALAR",
        Dimensions::Vec2 => "VEC2",
        Dimensions::Vec3 => "VEC3",
        Dimensions::Vec4 => "VEC4",
        Dimensions::Mat2 => "MAT2",
        Dimensions::Mat3 => "MAT3",
        Dimensions::Mat4 => "MAT4",
    };
    let normalized = if normalized { "normalized " } else { "" };
    format!("{dimensions} of {normalized}{component}")
}
