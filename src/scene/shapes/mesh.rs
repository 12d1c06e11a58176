//! `[[meshes]]`: a triangle mesh from an OBJ or PLY file or inline arrays,
//! placed by `translate`, `scale` and `rotation` (docs/scene-format.md,
//! docs/rendering-model.md "Triangle meshes").

use std::path::{Path, PathBuf};
use std::sync::Arc;

use glam::DVec3;
use serde::{Deserialize, Serialize};

use super::{AxisScale, Choices, Context, Placement, Shape};
use crate::scene::NamedOption;
use crate::scene::key_path::KeyPath;
use crate::scene::mesh_file::{self, Geometry};
use crate::scene::validate::{Check, Issue};

/// A mesh's own keys: where its triangles come from and how they are
/// shaded. Its placement (`scale` a number or `[x, y, z]`, like a cube's
/// size) is a `Placement<AxisScale>` beside it in the [`super::Instance`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Mesh {
    /// An OBJ or PLY file, relative to the scene file; kept as written, so
    /// that a saved scene refers to the same file.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub file: Option<PathBuf>,
    /// Inline geometry (without `file`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub positions: Vec<DVec3>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub triangles: Vec<[u32; 3]>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub normals: Vec<DVec3>,
    #[serde(default)]
    pub smooth: bool,
    /// The geometry, loaded and checked by validation; shared between
    /// copies of the scene, so moving a mesh keeps it (and its BVH).
    #[serde(skip)]
    pub geometry: Loaded,
}

crate::named_option! {
    /// The ray-triangle tests the renderers offer (docs/rendering-model.md,
    /// "Triangle meshes"): the same hits in exact arithmetic, different
    /// rounding, speed and behaviour on shared edges. `triangles` in
    /// `[render]` picks one for both renderers.
    #[derive(Serialize, Deserialize)]
    #[serde(rename_all = "kebab-case")]
    pub enum TriangleTest {
        /// Cramer's rule with signed volumes (determinants; Shirley and
        /// Marschner, "Fundamentals of Computer Graphics", 4.4.2).
        Cramer = "cramer",
        /// Möller and Trumbore 1997.
        MollerTrumbore = "moller-trumbore",
        /// Woop, Benthin and Wald 2013, as in pbrt-v4: no ray slips between
        /// two triangles that share an edge.
        #[default]
        Watertight = "watertight",
    }
}

impl TriangleTest {
    pub fn is_watertight(&self) -> bool {
        *self == TriangleTest::Watertight
    }
}

/// A mesh's key in `[render]`: `triangles`, the ray-triangle test of every
/// mesh in both renderers, a lecture switch (docs/rendering-model.md,
/// "Lecture switches"). Written to a file only when not watertight.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct MeshSettings {
    #[serde(skip_serializing_if = "TriangleTest::is_watertight")]
    pub triangles: TriangleTest,
}

/// The loaded geometry of a mesh (empty before validation). Two are equal
/// when they are the same load or hold the same triangles.
#[derive(Debug, Clone, Default)]
pub struct Loaded(pub Arc<Geometry>);

impl PartialEq for Loaded {
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.0, &other.0) || self.0 == other.0
    }
}

impl Mesh {
    /// An inline mesh with its geometry loaded (flat shaded, unplaced).
    pub fn inline(positions: &[DVec3], triangles: &[[u32; 3]]) -> Result<Mesh, String> {
        let geometry = mesh_file::from_arrays(positions, triangles, &[], false)?;
        Ok(Mesh {
            positions: positions.to_vec(),
            triangles: triangles.to_vec(),
            ..Mesh::with_geometry(geometry)
        })
    }

    /// `geometry`, flat shaded, with no source yet.
    fn with_geometry(geometry: Geometry) -> Mesh {
        Mesh {
            file: None,
            positions: Vec::new(),
            triangles: Vec::new(),
            normals: Vec::new(),
            smooth: false,
            geometry: Loaded(Arc::new(geometry)),
        }
    }

    /// Reads the mesh's file again (it changed on disk). On an error the
    /// geometry in use is kept: a bad save in another program never leaves
    /// the mesh without triangles.
    pub fn reload(&mut self, base: Option<&Path>) -> Result<(), String> {
        let full = self.file_read(base).ok_or("an inline mesh has no file")?;
        let geometry = mesh_file::load_file(&full, self.smooth)?;
        self.geometry = Loaded(Arc::new(geometry));
        Ok(())
    }

    /// Where the geometry is loaded from, for messages and the panel.
    fn load(&self, path: &KeyPath, context: &Context) -> Result<Geometry, Issue> {
        let inline = !self.positions.is_empty() || !self.triangles.is_empty();
        match (&self.file, inline) {
            (Some(_), true) => Err(Issue::new(
                &path.key("file"),
                "give either a file or inline positions and triangles, not both".to_owned(),
            )),
            (None, false) => Err(Issue::new(
                path,
                "needs a file or inline positions and triangles".to_owned(),
            )),
            (Some(file), false) => context
                .files
                .read(file)
                .and_then(|(name, bytes)| mesh_file::load_bytes(&name, &bytes, self.smooth))
                .map_err(|message| Issue::new(&path.key("file"), message)),
            (None, true) => {
                mesh_file::from_arrays(&self.positions, &self.triangles, &self.normals, self.smooth)
                    .map_err(|message| Issue::new(path, message))
            }
        }
    }
}

impl Choices for Mesh {
    /// The ray-triangle test.
    type Options = TriangleTest;
    type Settings = MeshSettings;

    /// The scene's `triangles` in `[render]`.
    fn options(scene: &crate::scene::Scene) -> TriangleTest {
        scene.render.meshes.triangles
    }

    const FLAG: Option<(&'static str, &'static str)> = Some((
        "triangles",
        "The ray-triangle test of meshes: cramer (Cramer's rule), moller-trumbore, or \
         watertight (Woop, Benthin and Wald). Default: the scene's `triangles` in \
         `[render]`, else watertight",
    ));

    fn options_named(name: &str) -> Result<TriangleTest, String> {
        TriangleTest::from_name(name)
    }
}

impl Shape for Mesh {
    fn file(&self) -> Option<&Path> {
        self.file.as_deref()
    }

    fn file_mut(&mut self) -> Option<&mut PathBuf> {
        self.file.as_mut()
    }

    /// OBJ and PLY (docs/scene-format.md, `[[meshes]]`).
    const FILE_EXTENSIONS: &[&str] = &["obj", "ply"];

    /// Flat shaded; the file is read again when it changes.
    fn from_file(file: PathBuf, base: Option<&Path>) -> Result<Mesh, String> {
        let mut mesh = Mesh {
            file: Some(file),
            ..Mesh::with_geometry(Geometry::default())
        };
        mesh.reload(base)?;
        Ok(mesh)
    }

    /// Flat shaded, its geometry written inline (`positions`,
    /// `triangles`), so that the scene's text and a link to it carry it.
    fn from_bytes(name: &str, bytes: &[u8]) -> Result<Mesh, String> {
        let geometry = mesh_file::load_bytes(name, bytes, false)?;
        Ok(Mesh {
            positions: geometry.positions.clone(),
            triangles: geometry.triangles.clone(),
            ..Mesh::with_geometry(geometry)
        })
    }

    fn parts(&self) -> Option<(usize, &'static str)> {
        Some((self.geometry.0.triangles.len(), "triangles"))
    }

    /// One read per shading (`smooth` changes the normals), shared.
    fn read_again(shapes: &mut [&mut Mesh], base: Option<&Path>) -> Result<(), String> {
        let mut fresh: Vec<Mesh> = Vec::new();
        for mesh in shapes.iter() {
            if !fresh.iter().any(|f| f.smooth == mesh.smooth) {
                let mut copy = (**mesh).clone();
                copy.reload(base)?;
                fresh.push(copy);
            }
        }
        for mesh in shapes.iter_mut() {
            if let Some(new) = fresh.iter().find(|f| f.smooth == mesh.smooth) {
                mesh.geometry = new.geometry.clone();
            }
        }
        Ok(())
    }

    /// Loads the geometry (file or inline) and keeps it; degenerate
    /// triangles dropped are reported as a warning.
    fn validate(&mut self, path: &KeyPath, context: &Context) -> Check {
        let geometry = self.load(path, context)?;
        if geometry.dropped > 0 {
            log::warn!(
                "{path}: {} degenerate triangles (zero area) dropped",
                geometry.dropped
            );
        }
        self.geometry = Loaded(Arc::new(geometry));
        Ok(())
    }

    type Placement = Placement<AxisScale>;

    /// The world box of the transformed vertices.
    fn bounds(&self, placement: &Placement<AxisScale>) -> [DVec3; 2] {
        let m = placement.linear();
        self.geometry.0.positions.iter().fold(
            [DVec3::INFINITY, DVec3::NEG_INFINITY],
            |[lo, hi], &p| {
                let w = placement.translate + m * p;
                [lo.min(w), hi.max(w)]
            },
        )
    }
}
