//! `swm info MESH [--json]`: what a mesh is made of, after cleaning.
//!
//! Counts are taken after merging coincident vertices (so an STL file or
//! an OBJ with split texture seams reports its real vertex count), and
//! components join faces through any shared edge, as in the file; boundary
//! loops and genus are those of the cleaned, manifold mesh the encoder
//! would see.

use crate::CliError;
use std::path::PathBuf;

#[derive(clap::Args)]
pub struct Args {
    /// A mesh file (.obj, .ply, .off, .stl).
    file: PathBuf,
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
}

pub fn run(args: &Args) -> Result<(), CliError> {
    let err = |e: swm::Error| CliError::new(&args.file, e);
    let mesh = swm::io::read_mesh(&args.file).map_err(err)?;
    let cleaned = swm::clean(&mesh, &swm::CleanOptions::default()).map_err(err)?;
    let stats = cleaned.table.stats(&cleaned.mesh);
    let r = &cleaned.report;
    if args.json {
        let v = serde_json::json!({
            "vertices": cleaned.distinct_vertices,
            "faces": r.input_faces,
            "components": r.input_components,
            "boundary_loops": stats.boundary_loops,
            "genus": stats.genus,
            "non_manifold_edges": r.non_manifold_edges,
            "non_manifold_vertices": r.non_manifold_vertices,
            "degenerate_faces": r.degenerate_faces(),
            "bbox_diagonal": stats.bbox_diagonal,
            "area": stats.area,
        });
        println!(
            "{}",
            serde_json::to_string_pretty(&v).expect("JSON of numbers")
        );
        return Ok(());
    }
    println!("{}", args.file.display());
    println!("  vertices              {}", cleaned.distinct_vertices);
    println!("  faces                 {}", r.input_faces);
    println!("  components            {}", r.input_components);
    println!("  boundary loops        {}", stats.boundary_loops);
    println!("  genus                 {}", stats.genus);
    println!("  bbox diagonal         {}", stats.bbox_diagonal);
    println!("  area                  {}", stats.area);
    if r.is_clean() {
        println!("  cleaning              nothing to repair");
    } else {
        println!("  cleaning:");
        let rows = [
            ("coincident vertices merged", r.merged_vertices),
            ("unreferenced vertices removed", r.unreferenced_vertices),
            (
                "faces with a repeated vertex dropped",
                r.repeated_index_faces,
            ),
            ("zero-area faces dropped", r.zero_area_faces),
            ("duplicate faces dropped", r.duplicate_faces),
            ("faces flipped to match their component", r.flipped_faces),
            ("non-manifold edges cut", r.non_manifold_edges),
            ("non-manifold vertices split", r.non_manifold_vertices),
            ("vertices added by splitting", r.split_vertices_added),
        ];
        for (what, n) in rows.iter().filter(|r| r.1 > 0) {
            println!("    {what:<40} {n}");
        }
        println!(
            "  after cleaning        {} vertices, {} faces, {} components",
            cleaned.mesh.vertex_count(),
            cleaned.mesh.face_count(),
            stats.components
        );
    }
    Ok(())
}
