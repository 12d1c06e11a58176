//! Triangle mesh geometry: read from an OBJ file (the `tobj` crate), a PLY
//! file (the `ply-rs-bw` crate) or inline arrays, then checked and prepared
//! as docs/rendering-model.md ("Triangle meshes") asks: polygons
//! fan-triangulated, degenerate triangles dropped and counted, and, for
//! smooth shading without file normals, area-weighted vertex normals.
//!
//! The crates parse; what they do not report (the line of an OBJ error,
//! NaN coordinates) is found by [`obj_problem`], a scan of the records the
//! mesh uses, so that every error names the file and the line (OBJ) or the
//! element (PLY).

use std::any::Any;
use std::path::Path;
use std::sync::{Arc, Mutex, MutexGuard};

use glam::DVec3;

/// A mesh in its own (local) coordinates, ready to trace.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Geometry {
    pub positions: Vec<DVec3>,
    /// Counter-clockwise seen from the front; no degenerate ones.
    pub triangles: Vec<[u32; 3]>,
    /// One unit normal per position for smooth shading (the file's, else
    /// area-weighted), empty for flat shading.
    pub normals: Vec<DVec3>,
    /// Degenerate (zero-area) triangles dropped on load.
    pub dropped: usize,
    /// What renderers derived from it ([`Geometry::derived`]).
    pub derived: Derived,
}

/// Values derived from a loaded geometry (its triangles' BVH, its packed
/// GPU data), made once on first use and owned by the geometry: every copy
/// of the scene shares one `Arc<Geometry>` (moving a mesh copies the scene
/// but not its triangles), so nothing derived is made twice, and what was
/// derived is dropped with the geometry, when no scene holds it any more
/// (docs/reliability.md, "Memory under live editing"). One value per type.
/// A clone of the geometry (to be changed) starts without any; equality
/// ignores them.
#[derive(Default)]
pub struct Derived(Mutex<Vec<Arc<dyn Any + Send + Sync>>>);

impl Derived {
    fn lock(&self) -> MutexGuard<'_, Vec<Arc<dyn Any + Send + Sync>>> {
        self.0.lock().unwrap_or_else(|e| e.into_inner())
    }

    fn find<T: Any + Send + Sync>(values: &[Arc<dyn Any + Send + Sync>]) -> Option<Arc<T>> {
        values
            .iter()
            .find_map(|value| Arc::clone(value).downcast::<T>().ok())
    }
}

impl Clone for Derived {
    fn clone(&self) -> Self {
        Derived::default()
    }
}

impl PartialEq for Derived {
    fn eq(&self, _: &Derived) -> bool {
        true
    }
}

impl std::fmt::Debug for Derived {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Derived({} values)", self.lock().len())
    }
}

impl Geometry {
    /// The value of type `T` derived from this geometry, made by `make` if
    /// there is none yet. `make` runs without the lock held (it may take a
    /// second on a large mesh); if two threads made one, the first stored
    /// wins.
    pub fn derived<T: Any + Send + Sync>(&self, make: impl FnOnce() -> T) -> Arc<T> {
        if let Some(value) = Derived::find(&self.derived.lock()) {
            return value;
        }
        let value = Arc::new(make());
        let mut values = self.derived.lock();
        if let Some(first) = Derived::find(&values) {
            return first;
        }
        values.push(Arc::clone(&value) as Arc<dyn Any + Send + Sync>);
        value
    }
}

/// What was read, before triangles are checked: positions, polygons as
/// triangles, and the file's normals (empty if none).
struct Raw {
    positions: Vec<DVec3>,
    triangles: Vec<[u32; 3]>,
    normals: Vec<DVec3>,
}

/// Reads `path` (`.obj` or `.ply`, by extension). Errors are messages that
/// start with the file and line or element: `bunny.obj:12: ...`.
pub fn load_file(path: &Path, smooth: bool) -> Result<Geometry, String> {
    let (name, bytes) = super::files::read_file(path)?;
    load_bytes(&name, &bytes, smooth)
}

/// Reads the `bytes` of a mesh file named `name` (`.obj` or `.ply`, by
/// extension), e.g. a file dropped on the web page, which has no path.
/// Errors start with `name` and the line or element, as [`load_file`]'s.
pub fn load_bytes(name: &str, bytes: &[u8], smooth: bool) -> Result<Geometry, String> {
    let extension = Path::new(name)
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let raw = match extension.as_deref() {
        Some("obj") => read_obj(bytes),
        Some("ply") => read_ply(bytes),
        _ => Err("unknown mesh format (the file name must end in .obj or .ply)".to_owned()),
    }
    .map_err(|e| format!("{name}:{e}"))?;
    prepare(raw, smooth).map_err(|e| format!("{name}: {e}"))
}

/// Inline `positions`, `triangles` and optional `normals`. An error names
/// the array and the index: `triangles[3]: index 7 out of range ...`.
pub fn from_arrays(
    positions: &[DVec3],
    triangles: &[[u32; 3]],
    normals: &[DVec3],
    smooth: bool,
) -> Result<Geometry, String> {
    for (i, p) in positions.iter().enumerate() {
        if !p.is_finite() {
            return Err(format!("positions[{i}]: must be finite, got {p}"));
        }
    }
    if !normals.is_empty() && normals.len() != positions.len() {
        let (n, p) = (normals.len(), positions.len());
        return Err(format!(
            "normals: one per position, got {n} for {p} positions"
        ));
    }
    let raw = Raw {
        positions: positions.to_vec(),
        triangles: triangles.to_vec(),
        normals: normals.to_vec(),
    };
    prepare(raw, smooth).map_err(|e| format!("triangles{e}"))
}

/// Checks indices and normals, drops degenerate triangles and makes the
/// smooth normals. An index error is `[i]: ...` (the triangle).
fn prepare(raw: Raw, smooth: bool) -> Result<Geometry, String> {
    let n = raw.positions.len();
    for (i, t) in raw.triangles.iter().enumerate() {
        if let Some(&bad) = t.iter().find(|&&v| v as usize >= n) {
            return Err(format!(
                "[{i}]: vertex index {bad} out of range ({n} positions)"
            ));
        }
    }
    if let Some((i, _)) = raw.normals.iter().enumerate().find(|(_, v)| !v.is_finite()) {
        return Err(format!("normal {i} is not finite"));
    }
    let before = raw.triangles.len();
    let triangles: Vec<[u32; 3]> = raw
        .triangles
        .into_iter()
        .filter(|&t| area_vector(&raw.positions, t) != DVec3::ZERO)
        .collect();
    let dropped = before - triangles.len();
    if triangles.is_empty() {
        return Err("no triangle with a non-zero area".to_owned());
    }
    let normals = match (smooth, raw.normals.is_empty()) {
        (false, _) => Vec::new(),
        (true, false) => raw
            .normals
            .iter()
            .map(|v| v.normalize_or(DVec3::Y))
            .collect(),
        (true, true) => area_weighted_normals(&raw.positions, &triangles),
    };
    Ok(Geometry {
        positions: raw.positions,
        triangles,
        normals,
        dropped,
        derived: Derived::default(),
    })
}

/// `cross(p1 - p0, p2 - p0)`: twice the area, along the geometric normal.
fn area_vector(positions: &[DVec3], [a, b, c]: [u32; 3]) -> DVec3 {
    let p = |i: u32| positions[i as usize];
    (p(b) - p(a)).cross(p(c) - p(a))
}

/// Each vertex's normal: the normalised sum of the area vectors of the
/// triangles that use it (docs/rendering-model.md, "Triangle meshes"). A
/// vertex used by no triangle, or whose sum cancels, gets +y.
fn area_weighted_normals(positions: &[DVec3], triangles: &[[u32; 3]]) -> Vec<DVec3> {
    let mut sums = vec![DVec3::ZERO; positions.len()];
    for &t in triangles {
        let w = area_vector(positions, t);
        for v in t {
            sums[v as usize] += w;
        }
    }
    sums.into_iter().map(|s| s.normalize_or(DVec3::Y)).collect()
}

/// An OBJ file through `tobj`: `v`, `vn` and `f` records, polygons
/// fan-triangulated, other records ignored. Errors start with the line.
fn read_obj(bytes: &[u8]) -> Result<Raw, String> {
    let text = as_text(bytes)?;
    if let Some((line, message)) = obj_problem(text) {
        return Err(format!("{line}: {message}"));
    }
    let options = tobj::LoadOptions {
        triangulate: false,
        single_index: false,
        ..Default::default()
    };
    let (models, _) = tobj::load_obj_buf(&mut text.as_bytes(), &options, |_| {
        Err(tobj::LoadError::OpenFileFailed)
    })
    .map_err(|e| format!("1: {e}"))?;
    let mut raw = Raw {
        positions: Vec::new(),
        triangles: Vec::new(),
        normals: Vec::new(),
    };
    let mut every_vertex_has_a_normal = true;
    for model in models {
        let normals = append_obj_model(&mut raw, &model.mesh);
        every_vertex_has_a_normal &= normals.is_some();
        raw.normals.extend(normals.unwrap_or_default());
    }
    if !every_vertex_has_a_normal {
        raw.normals.clear();
    }
    Ok(raw)
}

/// Appends one `tobj` model's positions and its faces fanned into
/// triangles; returns its normals indexed like its positions if every
/// vertex has one.
fn append_obj_model(raw: &mut Raw, mesh: &tobj::Mesh) -> Option<Vec<DVec3>> {
    let base = raw.positions.len() as u32;
    let triples = |v: &[f32]| -> Vec<DVec3> {
        v.chunks_exact(3)
            .map(|c| DVec3::new(c[0].into(), c[1].into(), c[2].into()))
            .collect()
    };
    let normals = triples(&mesh.normals);
    raw.positions.extend(triples(&mesh.positions));
    let arities = if mesh.face_arities.is_empty() {
        vec![3; mesh.indices.len() / 3]
    } else {
        mesh.face_arities.clone()
    };
    let mut start = 0;
    for arity in arities {
        let face = &mesh.indices[start..start + arity as usize];
        for k in 1..face.len().saturating_sub(1) {
            raw.triangles
                .push([face[0], face[k], face[k + 1]].map(|i| base + i));
        }
        start += arity as usize;
    }
    let mut per_vertex = vec![None; mesh.positions.len() / 3];
    for (&v, &n) in mesh.indices.iter().zip(&mesh.normal_indices) {
        per_vertex[v as usize] = normals.get(n as usize).copied();
    }
    per_vertex.into_iter().collect()
}

/// The first problem of an OBJ text that `tobj` would report without a
/// line, or would accept although the rendering model does not: a `v` or
/// `vn` record without three finite numbers, an `f` record with fewer than
/// three vertices, or one whose vertex index is not a number or refers to a
/// vertex that does not exist (1-based, or negative from the end).
pub(crate) fn obj_problem(text: &str) -> Option<(usize, String)> {
    let mut vertices: i64 = 0;
    for (i, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        let problem = match words.next() {
            Some("v") => {
                vertices += 1;
                three_finite(words, "vertex")
            }
            Some("vn") => three_finite(words, "normal"),
            Some("f") => face_problem(words, vertices),
            _ => None,
        };
        if let Some(message) = problem {
            return Some((i + 1, message));
        }
    }
    None
}

fn three_finite<'a>(words: impl Iterator<Item = &'a str>, what: &str) -> Option<String> {
    let numbers: Vec<Option<f64>> = words.take(3).map(|w| w.parse().ok()).collect();
    match numbers.as_slice() {
        [Some(x), Some(y), Some(z)] if x.is_finite() && y.is_finite() && z.is_finite() => None,
        [Some(_), Some(_), Some(_)] => Some(format!("{what} coordinates must be finite")),
        _ => Some(format!("a {what} needs three numbers")),
    }
}

fn face_problem<'a>(words: impl Iterator<Item = &'a str>, vertices: i64) -> Option<String> {
    let mut count = 0;
    for word in words {
        count += 1;
        let first = word.split('/').next().unwrap_or("");
        let Ok(index) = first.parse::<i64>() else {
            return Some(format!("face vertex {word:?} is not an index"));
        };
        let resolved = if index < 0 {
            vertices + index
        } else {
            index - 1
        };
        if index == 0 || resolved < 0 || resolved >= vertices {
            return Some(format!(
                "face vertex index {index} out of range ({vertices} vertices so far)"
            ));
        }
    }
    (count < 3).then(|| format!("a face needs at least three vertices, got {count}"))
}

/// A PLY file (ASCII or binary) through `ply-rs-bw`: the `vertex` element's
/// x, y, z (and nx, ny, nz if present), the `face` element's
/// `vertex_indices` (or `vertex_index`) lists, fan-triangulated. Errors
/// name the element: `vertex 12: ...`, `face 40: ...`.
fn read_ply(bytes: &[u8]) -> Result<Raw, String> {
    use ply_rs_bw::parser::Parser;
    use ply_rs_bw::ply::DefaultElement;
    as_text(ply_text_part(bytes))?;
    let ply = Parser::<DefaultElement>::new()
        .read_ply(&mut std::io::Cursor::new(bytes))
        .map_err(|e| format!(" {e}"))?;
    let vertices = ply.payload.get("vertex").map(Vec::as_slice).unwrap_or(&[]);
    let faces = ply.payload.get("face").map(Vec::as_slice).unwrap_or(&[]);
    let mut raw = Raw {
        positions: Vec::with_capacity(vertices.len()),
        triangles: Vec::with_capacity(faces.len()),
        normals: Vec::new(),
    };
    let has_normals = vertices.first().is_some_and(|v| v.contains_key("nx"));
    for (i, v) in vertices.iter().enumerate() {
        let p =
            ply_vector(v, ["x", "y", "z"]).ok_or(format!(" vertex {i}: needs numbers x, y, z"))?;
        if !p.is_finite() {
            return Err(format!(" vertex {i}: coordinates must be finite, got {p}"));
        }
        raw.positions.push(p);
        if has_normals {
            let n = ply_vector(v, ["nx", "ny", "nz"])
                .ok_or(format!(" vertex {i}: needs nx, ny, nz"))?;
            raw.normals.push(n);
        }
    }
    for (i, f) in faces.iter().enumerate() {
        let list = f
            .get("vertex_indices")
            .or_else(|| f.get("vertex_index"))
            .and_then(ply_list)
            .ok_or(format!(" face {i}: needs a list vertex_indices"))?;
        if list.len() < 3 {
            return Err(format!(" face {i}: needs at least three vertices"));
        }
        for k in 1..list.len() - 1 {
            let t = [list[0], list[k], list[k + 1]];
            if let Some(&bad) = t
                .iter()
                .find(|&&v| v < 0 || v as usize >= raw.positions.len())
            {
                let n = raw.positions.len();
                return Err(format!(
                    " face {i}: vertex index {bad} out of range ({n} vertices)"
                ));
            }
            raw.triangles.push(t.map(|v| v as u32));
        }
    }
    Ok(raw)
}

/// `bytes` as UTF-8 text, or an error naming the line of the first byte
/// that is not.
fn as_text(bytes: &[u8]) -> Result<&str, String> {
    std::str::from_utf8(bytes).map_err(|e| {
        let line = bytes[..e.valid_up_to()]
            .iter()
            .filter(|&&b| b == b'\n')
            .count()
            + 1;
        format!("{line}: not a text file (invalid UTF-8)")
    })
}

/// The part of a PLY file that must be text: the header, and the whole
/// file in the ASCII format (the parser's own UTF-8 error names no line).
fn ply_text_part(bytes: &[u8]) -> &[u8] {
    const END: &[u8] = b"end_header";
    let Some(end) = bytes.windows(END.len()).position(|w| w == END) else {
        return bytes;
    };
    let header = &bytes[..end];
    if header.windows(6).any(|w| w == b"binary") {
        header
    } else {
        bytes
    }
}

fn ply_scalar(p: &ply_rs_bw::ply::Property) -> Option<f64> {
    use ply_rs_bw::ply::Property as P;
    Some(match *p {
        P::Char(v) => v.into(),
        P::UChar(v) => v.into(),
        P::Short(v) => v.into(),
        P::UShort(v) => v.into(),
        P::Int(v) => v.into(),
        P::UInt(v) => v.into(),
        P::Float(v) => v.into(),
        P::Double(v) => v,
        _ => return None,
    })
}

fn ply_vector(e: &ply_rs_bw::ply::DefaultElement, keys: [&str; 3]) -> Option<DVec3> {
    let [x, y, z] = keys.map(|k| e.get(k).and_then(ply_scalar));
    Some(DVec3::new(x?, y?, z?))
}

fn ply_list(p: &ply_rs_bw::ply::Property) -> Option<Vec<i64>> {
    use ply_rs_bw::ply::Property as P;
    Some(match p {
        P::ListChar(v) => v.iter().map(|&x| x.into()).collect(),
        P::ListUChar(v) => v.iter().map(|&x| x.into()).collect(),
        P::ListShort(v) => v.iter().map(|&x| x.into()).collect(),
        P::ListUShort(v) => v.iter().map(|&x| x.into()).collect(),
        P::ListInt(v) => v.iter().map(|&x| x.into()).collect(),
        P::ListUInt(v) => v.iter().map(|&x| x.into()).collect(),
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_derived_value_is_made_once_per_geometry_and_dropped_with_it() {
        let geometry = Arc::new(Geometry::default());
        let made = std::cell::Cell::new(0);
        let make = || {
            made.set(made.get() + 1);
            vec![1u32, 2, 3]
        };
        let first = geometry.derived(make);
        let again = Arc::clone(&geometry).derived(make);
        assert!(Arc::ptr_eq(&first, &again));
        assert_eq!(made.get(), 1);
        // Another type is another value; a clone (to be changed) has none.
        assert_eq!(*geometry.derived(|| 7.5f64), 7.5);
        assert_eq!(made.get(), 1);
        let changed = (*geometry).clone();
        changed.derived(make);
        assert_eq!(made.get(), 2);
        assert_eq!(changed, *geometry, "equality ignores derived values");
        // The geometry owns them: dropping it drops them.
        let weak = Arc::downgrade(&first);
        drop((first, again, geometry));
        assert!(weak.upgrade().is_none());
    }
}
