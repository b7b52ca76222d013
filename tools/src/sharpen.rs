//! `swm sharpen IN -o OUT [--bend N] [--json]`: Sharpen&Bend on any mesh
//! (thesis §8.5 applies it to marching-cubes and scanned meshes as well
//! as to SwingWrapper's). The input is cleaned first, as the encoder
//! cleans it, since EdgeSharpener needs an oriented manifold.

use crate::error::CliError;
use std::path::PathBuf;
use std::time::Instant;

#[derive(clap::Args)]
pub struct Args {
    /// The mesh to sharpen (.obj, .ply, .off, .stl, .gltf, .glb).
    input: PathBuf,
    /// The mesh file to write; its extension picks the format.
    #[arg(short, long)]
    output: PathBuf,
    /// Bender steps after sharpening (four times the triangles per step).
    #[arg(long, value_name = "N", default_value_t = 0)]
    bend: u32,
    /// Print what was done as JSON.
    #[arg(long)]
    json: bool,
}

pub fn run(args: &Args) -> Result<(), CliError> {
    crate::same_file::refuse_same_file(&args.input, &args.output)?;
    swm::io::MeshFormat::from_path(&args.output).map_err(|e| CliError::usage(&args.output, e))?;
    let err = |e| CliError::new(&args.input, e);
    let mesh = swm::io::read_mesh(&args.input).map_err(err)?;
    let cleaned = swm::clean(&mesh, &swm::CleanOptions::default()).map_err(err)?;
    let start = Instant::now();
    let sharpened = swm::sharpen(&cleaned.mesh, &swm::SharpenOptions::default()).map_err(err)?;
    let limits = swm::Limits::default();
    let out = swm::bend(&sharpened.mesh, &sharpened.sharp, args.bend, &limits).map_err(err)?;
    let seconds = start.elapsed().as_secs_f64();
    swm::io::write_mesh(&args.output, &out.mesh).map_err(|e| CliError::new(&args.output, e))?;
    let r = &sharpened.report;
    if args.json {
        let v = serde_json::json!({
            "input_faces": cleaned.mesh.face_count(),
            "output_vertices": out.mesh.vertex_count(),
            "output_faces": out.mesh.face_count(),
            "chamfer_edges": r.chamfer_edges,
            "corners": r.corners,
            "snapped": r.snapped,
            "sharp_edges": out.sharp.len(),
            "bend_steps": args.bend,
            "seconds": seconds,
        });
        crate::report::print_json(&v);
    } else {
        crate::report::print_written(&args.input, &args.output, &out.mesh, seconds);
        say!(
            "sharpened: {} chamfer edges, {} corners, {} vertices snapped, {} sharp edges{}",
            r.chamfer_edges,
            r.corners,
            r.snapped,
            sharpened.sharp.len(),
            if args.bend > 0 {
                format!(", then {} Bender steps", args.bend)
            } else {
                String::new()
            }
        );
    }
    Ok(())
}
