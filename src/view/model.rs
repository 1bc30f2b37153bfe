//! The viewer's models: Keenan Crane's "Spot" (public domain, `assets/models/spot/`), an
//! analytic sphere, a procedural torus, and any OBJ (`tobj`) or glTF (`gltf`) file.
//!
//! Every model is placed as the scene says ([`crate::view::scene`]): its bounding box is
//! centred on the object's centre and scaled so that its largest half extent is
//! [`FIT_HALF_EXTENT`], then turned 180° about y. Meshes become triangle lists in world
//! space with one unit normal per corner: the file's normals where it has them, otherwise
//! each vertex's area-weighted average of its faces' normals (Max 1999 compares the
//! weightings; area weighting is the cross products' sum).

use std::path::Path;

use glam::{Mat3, Vec3};

use crate::view::scene::{FIT_HALF_EXTENT, OBJECT_CENTRE, OBJECT_TURN_DEG};
use crate::{Error, Result};

/// Spot's triangulated mesh (public domain; `assets/models/spot/README.txt`).
const SPOT_OBJ: &[u8] = include_bytes!("../../assets/models/spot/spot_triangulated.obj");

/// Segments of the procedural torus around its axis and around its tube.
const TORUS_SEGMENTS: [u32; 2] = [96, 48];
/// The torus's tube radius over its ring radius.
const TORUS_TUBE: f32 = 0.4;
/// The torus's tilt about x before placement, degrees, so its hole and its top both show.
const TORUS_TILT_DEG: f32 = 30.0;

/// A triangle list in world space: three corners per triangle.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// Corner positions.
    pub positions: Vec<Vec3>,
    /// Corner unit normals.
    pub normals: Vec<Vec3>,
}

/// What a model is drawn as.
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    /// The analytic sphere of radius [`FIT_HALF_EXTENT`] at the object's centre (exact
    /// normals at every pixel, as the preview's spheres).
    Sphere,
    /// Triangles.
    Mesh(Mesh),
}

/// A model with the name the HUD shows.
#[derive(Clone, Debug, PartialEq)]
pub struct Model {
    /// "spot", "sphere", "torus" or the file's name.
    pub name: String,
    /// Its geometry, placed.
    pub shape: Shape,
}

impl Model {
    /// Spot, placed.
    pub fn spot() -> Result<Model> {
        let mesh = read_obj(Path::new("spot_triangulated.obj"), SPOT_OBJ)?;
        Ok(Model {
            name: "spot".into(),
            shape: Shape::Mesh(place(mesh)),
        })
    }

    /// The analytic sphere.
    pub fn sphere() -> Model {
        Model {
            name: "sphere".into(),
            shape: Shape::Sphere,
        }
    }

    /// The procedural torus, placed.
    pub fn torus() -> Model {
        Model {
            name: "torus".into(),
            shape: Shape::Mesh(place(torus())),
        }
    }

    /// The model in `path` (.obj, .gltf, .glb), placed.
    pub fn load(path: &Path) -> Result<Model> {
        let ext = path
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase())
            .unwrap_or_default();
        let mesh = match ext.as_str() {
            "obj" => read_obj(path, &std::fs::read(path).map_err(|e| Error::io(path, e))?)?,
            "gltf" | "glb" => read_gltf(path)?,
            _ => {
                return Err(Error::UnsupportedInput {
                    path: path.into(),
                    message: "not a model: the viewer reads .obj, .gltf and .glb files".into(),
                })
            }
        };
        let name = path
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        Ok(Model {
            name,
            shape: Shape::Mesh(place(mesh)),
        })
    }

    /// The three bundled models: Spot, the sphere, the torus.
    pub fn bundled() -> Result<Vec<Model>> {
        Ok(vec![Model::spot()?, Model::sphere(), Model::torus()])
    }
}

fn decode_error(path: &Path, format: &'static str, message: impl Into<String>) -> Error {
    Error::Decode {
        path: path.into(),
        format,
        message: message.into(),
    }
}

/// Corners `tri` of `positions` with the file's normals (`normals[normal_index]`) or none.
fn push_triangles(
    mesh: &mut Mesh,
    positions: &[Vec3],
    indices: &[u32],
    normals: Option<(&[Vec3], &[u32])>,
) {
    let computed;
    let (normals, normal_indices) = match normals {
        Some(n) => n,
        None => {
            computed = vertex_normals(positions, indices);
            (computed.as_slice(), indices)
        }
    };
    for (tri, ntri) in indices.chunks_exact(3).zip(normal_indices.chunks_exact(3)) {
        let face = face_normal(tri.iter().map(|&i| positions[i as usize]));
        for (&i, &j) in tri.iter().zip(ntri) {
            mesh.positions.push(positions[i as usize]);
            let n = normals[j as usize];
            mesh.normals.push(if n.length_squared() > 0.0 {
                n.normalize()
            } else {
                face
            });
        }
    }
}

/// The unit normal of a triangle (zero for a degenerate one).
fn face_normal(mut corners: impl Iterator<Item = Vec3>) -> Vec3 {
    let (a, b, c) = (
        corners.next().unwrap_or_default(),
        corners.next().unwrap_or_default(),
        corners.next().unwrap_or_default(),
    );
    (b - a).cross(c - a).normalize_or_zero()
}

/// Per vertex, the sum of its faces' cross products (area-weighted normals), normalised.
pub fn vertex_normals(positions: &[Vec3], indices: &[u32]) -> Vec<Vec3> {
    let mut sums = vec![Vec3::ZERO; positions.len()];
    for tri in indices.chunks_exact(3) {
        let [a, b, c] = [0, 1, 2].map(|k| positions[tri[k] as usize]);
        let n = (b - a).cross(c - a);
        for &i in tri {
            sums[i as usize] += n;
        }
    }
    sums.into_iter().map(Vec3::normalize_or_zero).collect()
}

/// An OBJ file's triangles (faces with more corners are fanned by `tobj`).
fn read_obj(path: &Path, bytes: &[u8]) -> Result<Mesh> {
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: false,
        ignore_points: true,
        ignore_lines: true,
    };
    let (models, _) = tobj::load_obj_buf(&mut std::io::Cursor::new(bytes), &options, |_| {
        Err(tobj::LoadError::OpenFileFailed)
    })
    .map_err(|e| decode_error(path, "OBJ", e.to_string()))?;
    let mut mesh = Mesh::default();
    for m in &models {
        let m = &m.mesh;
        let positions: Vec<Vec3> = m.positions.chunks_exact(3).map(Vec3::from_slice).collect();
        if m.indices.iter().any(|&i| i as usize >= positions.len()) {
            return Err(decode_error(
                path,
                "OBJ",
                "a face names a vertex the file lacks",
            ));
        }
        let normals: Vec<Vec3> = m.normals.chunks_exact(3).map(Vec3::from_slice).collect();
        let with_normals = !m.normal_indices.is_empty()
            && m.normal_indices.len() == m.indices.len()
            && m.normal_indices
                .iter()
                .all(|&i| (i as usize) < normals.len());
        let file_normals =
            with_normals.then_some((normals.as_slice(), m.normal_indices.as_slice()));
        push_triangles(&mut mesh, &positions, &m.indices, file_normals);
    }
    finish(path, "OBJ", mesh)
}

/// Every triangle primitive of a glTF file's default scene (or first scene), with its
/// node's world transform.
fn read_gltf(path: &Path) -> Result<Mesh> {
    let gltf = gltf::Gltf::open(path).map_err(|e| decode_error(path, "glTF", e.to_string()))?;
    let base = path.parent().map(Path::to_path_buf);
    let buffers = gltf::import_buffers(&gltf.document, base.as_deref(), gltf.blob.clone())
        .map_err(|e| decode_error(path, "glTF", e.to_string()))?;
    let scene = gltf
        .document
        .default_scene()
        .or_else(|| gltf.document.scenes().next())
        .ok_or_else(|| decode_error(path, "glTF", "the file has no scene"))?;
    let mut mesh = Mesh::default();
    let mut stack: Vec<(gltf::Node, glam::Mat4)> =
        scene.nodes().map(|n| (n, glam::Mat4::IDENTITY)).collect();
    while let Some((node, parent)) = stack.pop() {
        let world = parent * glam::Mat4::from_cols_array_2d(&node.transform().matrix());
        stack.extend(node.children().map(|c| (c, world)));
        let Some(m) = node.mesh() else { continue };
        let normal_matrix = Mat3::from_mat4(world).inverse().transpose();
        for primitive in m.primitives() {
            if primitive.mode() != gltf::mesh::Mode::Triangles {
                continue;
            }
            let reader = primitive.reader(|b| buffers.get(b.index()).map(|d| &d.0[..]));
            let Some(positions) = reader.read_positions() else {
                continue;
            };
            let positions: Vec<Vec3> = positions
                .map(|p| world.transform_point3(Vec3::from(p)))
                .collect();
            let indices: Vec<u32> = match reader.read_indices() {
                Some(i) => i.into_u32().collect(),
                None => (0..positions.len() as u32).collect(),
            };
            if indices.iter().any(|&i| i as usize >= positions.len()) {
                return Err(decode_error(
                    path,
                    "glTF",
                    "an index names a vertex the mesh lacks",
                ));
            }
            let normals: Option<Vec<Vec3>> = reader
                .read_normals()
                .map(|n| n.map(|n| normal_matrix * Vec3::from(n)).collect())
                .filter(|n: &Vec<Vec3>| n.len() == positions.len());
            let file_normals = normals.as_deref().map(|n| (n, indices.as_slice()));
            push_triangles(&mut mesh, &positions, &indices, file_normals);
        }
    }
    finish(path, "glTF", mesh)
}

/// Refuses a file without triangles or with non-finite coordinates.
fn finish(path: &Path, format: &'static str, mesh: Mesh) -> Result<Mesh> {
    if mesh.positions.is_empty() {
        return Err(decode_error(path, format, "the file holds no triangles"));
    }
    if !mesh.positions.iter().all(|p| p.is_finite()) {
        return Err(decode_error(
            path,
            format,
            "a vertex position is not finite",
        ));
    }
    Ok(mesh)
}

/// The torus around z with ring radius 1 and tube [`TORUS_TUBE`], tilted about x.
fn torus() -> Mesh {
    let [nu, nv] = TORUS_SEGMENTS;
    let tilt = Mat3::from_rotation_x(TORUS_TILT_DEG.to_radians());
    let point = |i: u32, j: u32| {
        let (u, v) = (
            std::f32::consts::TAU * i as f32 / nu as f32,
            std::f32::consts::TAU * j as f32 / nv as f32,
        );
        let n = Vec3::new(u.cos() * v.cos(), u.sin() * v.cos(), v.sin());
        let p = Vec3::new(u.cos(), u.sin(), 0.0) + TORUS_TUBE * n;
        (tilt * p, tilt * n)
    };
    let mut mesh = Mesh::default();
    for i in 0..nu {
        for j in 0..nv {
            let quad = [
                point(i, j),
                point(i + 1, j),
                point(i + 1, j + 1),
                point(i, j + 1),
            ];
            for k in [0, 1, 2, 0, 2, 3] {
                mesh.positions.push(quad[k].0);
                mesh.normals.push(quad[k].1);
            }
        }
    }
    mesh
}

/// `mesh` centred on the object's centre, scaled to [`FIT_HALF_EXTENT`] and turned
/// [`OBJECT_TURN_DEG`] about y.
pub fn place(mut mesh: Mesh) -> Mesh {
    let (lo, hi) = mesh.positions.iter().fold(
        (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    );
    let centre = 0.5 * (lo + hi);
    let half = 0.5 * (hi - lo).max_element();
    let scale = if half > 0.0 {
        FIT_HALF_EXTENT / half
    } else {
        1.0
    };
    let turn = Mat3::from_rotation_y(OBJECT_TURN_DEG.to_radians());
    let centre_to = Vec3::from(OBJECT_CENTRE);
    for p in &mut mesh.positions {
        *p = turn * ((*p - centre) * scale) + centre_to;
    }
    for n in &mut mesh.normals {
        *n = (turn * *n).normalize_or_zero();
    }
    mesh
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Spot parses into its 5856 triangles, placed within the fitted box, with unit normals
    /// pointing out of the model (the mean of n·(p − centre) is positive).
    #[test]
    fn spot_is_placed() {
        let Shape::Mesh(m) = Model::spot().unwrap().shape else {
            panic!("spot is a mesh")
        };
        assert_eq!(m.positions.len(), 3 * 5856);
        let c = Vec3::from(OBJECT_CENTRE);
        let mut max_half = 0.0f32;
        let mut outward = 0.0;
        for (p, n) in m.positions.iter().zip(&m.normals) {
            max_half = max_half.max((*p - c).abs().max_element());
            assert!((n.length() - 1.0).abs() < 1e-4);
            outward += n.dot(*p - c);
        }
        assert!(
            (max_half - FIT_HALF_EXTENT).abs() < 0.05 * FIT_HALF_EXTENT,
            "{max_half}"
        );
        assert!(outward > 0.0);
    }

    /// Bad files are errors naming the file, never panics.
    #[test]
    fn bad_models_are_errors() {
        let dir = std::env::temp_dir().join(format!("splitsum-model-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let png = dir.join("picture.png");
        std::fs::write(&png, b"\x89PNG\r\n\x1a\n").unwrap();
        assert!(matches!(
            Model::load(&png),
            Err(Error::UnsupportedInput { .. })
        ));
        let empty = dir.join("empty.obj");
        std::fs::write(&empty, b"# nothing\n").unwrap();
        let e = Model::load(&empty).unwrap_err().to_string();
        assert!(e.contains("empty.obj") && e.contains("no triangles"), "{e}");
        let bad = dir.join("bad.obj");
        std::fs::write(&bad, b"v 0 0 0\nf 1 2 3\n").unwrap();
        assert!(Model::load(&bad).is_err());
        let gltf = dir.join("bad.gltf");
        std::fs::write(&gltf, b"{ not json").unwrap();
        let e = Model::load(&gltf).unwrap_err().to_string();
        assert!(e.contains("bad.gltf"), "{e}");
        std::fs::remove_dir_all(&dir).ok();
    }

    /// A quad without normals gets the face normal at every corner.
    #[test]
    fn normals_are_computed_where_missing() {
        let dir = std::env::temp_dir().join(format!("splitsum-quad-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let quad = dir.join("quad.obj");
        std::fs::write(&quad, b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n").unwrap();
        let Shape::Mesh(m) = Model::load(&quad).unwrap().shape else {
            panic!()
        };
        assert_eq!(m.positions.len(), 6);
        // +z turned 180° about y is −z.
        assert!(m.normals.iter().all(|n| (*n - Vec3::NEG_Z).length() < 1e-5));
        std::fs::remove_dir_all(&dir).ok();
    }
}
