//! Global topology of a manifold mesh: connected components, boundary
//! loops, Euler characteristic and genus.
//!
//! Per component, with V vertices, E edges, F faces and b boundary loops,
//! the Euler characteristic is chi = V - E + F = 2 - 2g - b, which gives the
//! genus g. E is (3F + B) / 2 where B counts boundary half-edges.

use crate::prelude::*;

use super::{CornerId, CornerTable, FaceId, TriMesh, VertexId};

/// One connected component (connected through shared edges).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Component {
    /// Its lowest-numbered face.
    pub first_face: FaceId,
    /// Faces.
    pub faces: u64,
    /// Distinct vertices.
    pub vertices: u64,
    /// Undirected edges.
    pub edges: u64,
    /// Boundary loops.
    pub boundary_loops: u64,
    /// V - E + F.
    pub euler: i64,
    /// (2 - b - chi) / 2.
    pub genus: i64,
}

/// Summary of a mesh, as `swm info` prints it.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MeshStats {
    /// Vertices referenced by at least one face.
    pub vertices: u64,
    /// Triangles.
    pub faces: u64,
    /// Connected components.
    pub components: u64,
    /// Boundary loops over all components.
    pub boundary_loops: u64,
    /// Sum of the components' genus.
    pub genus: i64,
    /// Bounding-box diagonal length.
    pub bbox_diagonal: f64,
    /// Surface area.
    pub area: f64,
}

impl CornerTable {
    /// The face labels of the connected components, in order of each
    /// component's lowest face, and the number of components.
    pub fn component_labels(&self) -> (Vec<u32>, u32) {
        let nf = self.face_count();
        let mut label = vec![u32::MAX; nf];
        let mut stack = Vec::new();
        let mut count = 0u32;
        for f0 in 0..nf {
            if label[f0] != u32::MAX {
                continue;
            }
            label[f0] = count;
            stack.push(f0 as u32);
            while let Some(f) = stack.pop() {
                for k in 0..3 {
                    let o = self.opposite(FaceId(f).corner(k));
                    if o.is_some() && label[o.face().idx()] == u32::MAX {
                        label[o.face().idx()] = count;
                        stack.push(o.face().0);
                    }
                }
            }
            count += 1;
        }
        (label, count)
    }

    /// The boundary loops, each as the list of its boundary corners (the
    /// corner facing each boundary edge), in loop order. The loop runs
    /// along the edges `V[n(c)] -> V[p(c)]`, keeping the surface on its left.
    pub fn boundary_loops(&self) -> Vec<Vec<CornerId>> {
        let nc = self.corner_count();
        let mut seen = vec![false; nc];
        let mut loops = Vec::new();
        for c0 in 0..nc {
            if seen[c0] || self.opposite(CornerId(c0 as u32)).is_some() {
                continue;
            }
            let mut lp = Vec::new();
            let mut c = CornerId(c0 as u32);
            while !seen[c.idx()] {
                seen[c.idx()] = true;
                lp.push(c);
                c = self.next_boundary_corner(c);
            }
            loops.push(lp);
        }
        loops
    }

    /// The boundary corner whose edge starts where `c`'s boundary edge ends.
    pub fn next_boundary_corner(&self, c: CornerId) -> CornerId {
        // Rotate around the edge's end vertex until the next free edge.
        let mut x = c.next();
        for _ in 0..self.corner_count() {
            let y = self.opposite(x);
            if y.is_none() {
                return x;
            }
            x = y.next();
        }
        x
    }

    /// Per-component topology, in order of each component's lowest face.
    pub fn components(&self) -> Vec<Component> {
        let (label, count) = self.component_labels();
        let mut comps: Vec<Component> = (0..count)
            .map(|_| Component {
                first_face: FaceId::NONE,
                faces: 0,
                vertices: 0,
                edges: 0,
                boundary_loops: 0,
                euler: 0,
                genus: 0,
            })
            .collect();
        let mut boundary_half_edges = vec![0u64; count as usize];
        for (f, &l) in label.iter().enumerate() {
            let comp = &mut comps[l as usize];
            if comp.first_face.is_none() {
                comp.first_face = FaceId(f as u32);
            }
            comp.faces += 1;
            for k in 0..3 {
                if self.opposite(FaceId(f as u32).corner(k)).is_none() {
                    boundary_half_edges[l as usize] += 1;
                }
            }
        }
        for v in 0..self.vertex_count() {
            let c = self.vertex_corner(VertexId(v as u32));
            if c.is_some() {
                comps[label[c.face().idx()] as usize].vertices += 1;
            }
        }
        for lp in self.boundary_loops() {
            comps[label[lp[0].face().idx()] as usize].boundary_loops += 1;
        }
        for (comp, b) in comps.iter_mut().zip(boundary_half_edges) {
            comp.edges = (3 * comp.faces + b) / 2;
            comp.euler = comp.vertices as i64 - comp.edges as i64 + comp.faces as i64;
            comp.genus = (2 - comp.boundary_loops as i64 - comp.euler) / 2;
        }
        comps
    }

    /// Summary statistics of the mesh this table was built from.
    pub fn stats(&self, mesh: &TriMesh) -> MeshStats {
        let comps = self.components();
        MeshStats {
            vertices: (0..self.vertex_count())
                .filter(|&v| self.vertex_corner(VertexId(v as u32)).is_some())
                .count() as u64,
            faces: self.face_count() as u64,
            components: comps.len() as u64,
            boundary_loops: comps.iter().map(|c| c.boundary_loops).sum(),
            genus: comps.iter().map(|c| c.genus).sum(),
            bbox_diagonal: mesh.bbox_diagonal(),
            area: mesh.area(),
        }
    }
}
