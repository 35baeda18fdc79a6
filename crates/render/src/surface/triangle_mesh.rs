//! [`TriangleMesh`]: the triangles of a Wavefront OBJ file (`Type = MESH`), each a
//! [`Polygon`] (flat) or a [`SmoothPolygon`] (vertex normals interpolated), under the
//! tracer's one [`Bvh`] — the same hierarchy as the scene's and a Bézier mesh's.
//!
//! Scene syntax:
//! ```text
//! #object
//! Type = MESH
//! File Name = model.obj     // read relative to the scene (`scene::parse_obj`)
//! ```
//!
//! The mesh is one object of the scene: one material, one placement (`Scale`, `Rotate`,
//! `Translate`), one box in the scene's hierarchy, and its own hierarchy over its triangles
//! inside. Triangles of zero area have no surface and are left out.

use std::ops::Range;

use super::{Hit, Polygon, SmoothPolygon, Surface, SurfaceGeometry, SurfaceKind};
use crate::aggregate::Bvh;
use crate::geometry::{Bounds3, Ray};
use crate::scene::MeshData;
use crate::workspace::Workspace;

/// One triangle of the mesh.
#[derive(Debug)]
enum Face {
    Flat(Polygon),
    Smooth(SmoothPolygon),
}

impl Face {
    fn surface(&self) -> &dyn Surface {
        match self {
            Face::Flat(p) => p,
            Face::Smooth(s) => s,
        }
    }
}

/// A triangle mesh under a bounding-volume hierarchy.
#[derive(Debug)]
pub struct TriangleMesh {
    faces: Vec<Face>,
    bvh: Bvh,
    bounds: Bounds3,
}

impl TriangleMesh {
    /// The mesh of `data` (checked by [`MeshData::validate`]): `None` when it is invalid or
    /// none of its triangles has an area.
    pub fn new(data: &MeshData) -> Option<Self> {
        data.validate().ok()?;
        let faces: Vec<Face> = data
            .triangles
            .iter()
            .zip(&data.triangle_normals)
            .filter_map(|(t, n)| {
                let v = t.map(|i| data.positions[i as usize]);
                match n {
                    None => Polygon::new(&v).map(Face::Flat),
                    Some(n) => {
                        let n = n.map(|i| data.normals[i as usize]);
                        SmoothPolygon::new(&v, &n).map(Face::Smooth)
                    }
                }
            })
            .collect();
        let boxes: Vec<Bounds3> = faces
            .iter()
            .map(|f| f.surface().bounds())
            .collect::<Option<_>>()?;
        let bounds = boxes.iter().copied().reduce(|a, b| a.union(&b))?;
        Some(TriangleMesh {
            bvh: Bvh::new(&boxes),
            faces,
            bounds,
        })
    }

    /// Triangles with an area (those traced).
    pub fn len(&self) -> usize {
        self.faces.len()
    }

    /// Whether no triangle is traced (never, for a constructed mesh).
    pub fn is_empty(&self) -> bool {
        self.faces.is_empty()
    }
}

impl Surface for TriangleMesh {
    fn kind(&self) -> SurfaceKind {
        SurfaceKind::Mesh
    }

    fn bounds(&self) -> Option<Bounds3> {
        Some(self.bounds)
    }

    fn intersect(&self, ray: &Ray, t_range: Range<f64>, ws: &mut Workspace) -> Option<Hit> {
        let mut visits = 0;
        let found = self
            .bvh
            .nearest(ray, t_range.clone(), &mut visits, |item, _| {
                let hit =
                    self.faces[item as usize]
                        .surface()
                        .intersect(ray, t_range.clone(), ws)?;
                Some((hit.t, hit))
            });
        ws.stats.bvh_node_visits += visits;
        // The triangle's own tag is 0 (a polygon uses none): the mesh's names the triangle.
        found.map(|(item, _, hit)| Hit { tag: item, ..hit })
    }

    fn occluded(&self, ray: &Ray, t_range: Range<f64>, ws: &mut Workspace) -> bool {
        let mut visits = 0;
        let blocked = self.bvh.any(ray, t_range.clone(), &mut visits, |item| {
            self.faces[item as usize]
                .surface()
                .intersect(ray, t_range.clone(), ws)
                .is_some()
        });
        ws.stats.bvh_node_visits += visits;
        blocked
    }

    fn shading(&self, hit: &Hit) -> SurfaceGeometry {
        let face = &self.faces[(hit.tag as usize).min(self.faces.len() - 1)];
        face.surface().shading(&Hit { tag: 0, ..*hit })
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;
    use rand::{Rng, SeedableRng};

    use super::*;
    use crate::scene::parse_obj;

    /// An octahedron of radius 1 about the origin, flat or with its vertex normals (the
    /// vertices' directions).
    fn octahedron(smooth: bool) -> MeshData {
        let mut text = String::from(
            "v 1 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1\n\
             vn 1 0 0\nvn -1 0 0\nvn 0 1 0\nvn 0 -1 0\nvn 0 0 1\nvn 0 0 -1\n",
        );
        for (a, b) in [(1, 3), (3, 2), (2, 4), (4, 1)] {
            for c in [5, 6] {
                let (a, b) = if c == 5 { (a, b) } else { (b, a) };
                if smooth {
                    text += &format!("f {a}//{a} {b}//{b} {c}//{c}\n");
                } else {
                    text += &format!("f {a} {b} {c}\n");
                }
            }
        }
        parse_obj(&text).expect("an octahedron")
    }

    /// The mesh's nearest hit and shadow verdict are those of a loop over its triangles as
    /// separate polygons, on 2 000 random rays through and around the octahedron (many pass
    /// through its edges and vertices, where triangles meet); the hit's shading is its
    /// triangle's.
    #[test]
    fn hits_are_the_nearest_of_the_triangles() {
        for smooth in [false, true] {
            let data = octahedron(smooth);
            let mesh = TriangleMesh::new(&data).expect("a mesh");
            assert_eq!(mesh.len(), 8);
            let faces: Vec<Polygon> = data
                .triangles
                .iter()
                .map(|t| Polygon::new(&t.map(|i| data.positions[i as usize])).unwrap())
                .collect();
            let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
            let mut ws = Workspace::new();
            let mut hits = 0;
            for k in 0..2000 {
                let o = DVec3::new(
                    rng.gen_range(-3.0..3.0),
                    rng.gen_range(-3.0..3.0),
                    rng.gen_range(-3.0..3.0),
                );
                // Aim at a vertex, an edge's midpoint or a random point near the body.
                let target = match k % 3 {
                    0 => data.positions[rng.gen_range(0..6)],
                    1 => {
                        let t = data.triangles[rng.gen_range(0..8)];
                        0.5 * (data.positions[t[0] as usize] + data.positions[t[1] as usize])
                    }
                    _ => DVec3::new(
                        rng.gen_range(-1.2..1.2),
                        rng.gen_range(-1.2..1.2),
                        rng.gen_range(-1.2..1.2),
                    ),
                };
                let ray = Ray::new(o, target - o);
                let range = 1e-9..f64::INFINITY;
                let brute = faces
                    .iter()
                    .filter_map(|f| f.intersect(&ray, range.clone(), &mut ws))
                    .map(|h| h.t)
                    .fold(None, |b: Option<f64>, t| Some(b.map_or(t, |b| b.min(t))));
                let got = mesh.intersect(&ray, range.clone(), &mut ws);
                assert_eq!(got.map(|h| h.t), brute, "ray {k} (smooth {smooth})");
                assert_eq!(
                    mesh.occluded(&ray, range.clone(), &mut ws),
                    brute.is_some(),
                    "shadow verdict of ray {k}"
                );
                if let Some(h) = got {
                    hits += 1;
                    let g = mesh.shading(&h);
                    let own = faces[h.tag as usize].shading(&Hit { tag: 0, ..h });
                    assert_eq!(g.p, own.p, "ray {k}: the point of its triangle");
                    let n = g.normal.expect("a normal");
                    if smooth {
                        // Interpolated between the vertex directions: within the face's
                        // corner normals' cone, and (at the hit point p) close to p/|p|
                        // only at the vertices; always on the outward side.
                        assert!(n.dot(g.p) > 0.0, "ray {k}: outward smooth normal {n}");
                    } else {
                        assert_eq!(Some(n), own.normal, "ray {k}: the flat face's normal");
                    }
                }
            }
            assert!(hits > 500, "only {hits} hits (smooth {smooth})");
        }
    }

    /// A zero-area triangle is left out; a mesh of nothing else is refused.
    #[test]
    fn zero_area_triangles_are_left_out() {
        let data = parse_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 3\nf 1 2 4\n").unwrap();
        assert_eq!(TriangleMesh::new(&data).map(|m| m.len()), Some(1));
        let flat = parse_obj("v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n").unwrap();
        assert!(TriangleMesh::new(&flat).is_none());
    }
}
