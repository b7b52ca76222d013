//! `swm decode IN.swm -o OUT.(obj|ply|off|stl|glb) [--format F]
//! [--sharpen | --no-sharpen] [--bend N] [--max-level N] [--max-vertices N] [--max-faces N] [--max-alloc BYTES]
//! [--max-input BYTES] [--json]`. IN and OUT may be `-` (standard input
//! and output, see `pipe`).

use crate::error::CliError;
use std::ops::Deref;
use std::path::PathBuf;
use std::time::Instant;

#[derive(clap::Args)]
pub struct Args {
    /// The .swm file to decode, or - for standard input; or a glTF scene
    /// (.glb, .gltf) whose SWM_mesh_compression primitives are expanded
    /// into a plain .glb or .gltf.
    input: PathBuf,
    /// The mesh file to write; its extension picks the format: .obj, .ply,
    /// .off, .stl, or .glb (glTF 2.0 binary, with vertex normals). Or -
    /// for standard output, with --format (reports then go to standard
    /// error).
    #[arg(short, long)]
    output: PathBuf,
    /// The output's format when its name does not say (standard output,
    /// no extension): obj, ply, off, stl or glb.
    #[arg(long, value_parser = crate::pipe::parse_format)]
    format: Option<swm::io::MeshFormat>,
    /// Restore sharp edges and corners after decoding (EdgeSharpener),
    /// whatever the file's hint says. Without --sharpen or --no-sharpen,
    /// the hint decides (`swm info` shows it; plain without one).
    #[arg(long, conflicts_with = "no_sharpen")]
    sharpen: bool,
    /// Do not run EdgeSharpener, whatever the file's hint says.
    #[arg(long)]
    no_sharpen: bool,
    /// Bender steps after that: crease-preserving butterfly subdivision,
    /// four times the triangles per step [default: the file's hint, 0
    /// without one].
    #[arg(long, value_name = "N")]
    bend: Option<u32>,
    /// Decode at most N subdivision levels of a displaced-subdivision
    /// file (0: its base mesh); `swm info` lists them. Other modes
    /// ignore it [default: every level].
    #[arg(long, value_name = "N")]
    max_level: Option<u8>,
    /// Refuse files whose mesh (after Bender) has more vertices than this.
    #[arg(long, value_name = "N")]
    max_vertices: Option<u64>,
    /// Refuse files whose mesh (after Bender) has more triangles than this.
    #[arg(long, value_name = "N")]
    max_faces: Option<u64>,
    /// Refuse files that would make the decoder allocate more than this
    /// many bytes at once.
    #[arg(long, value_name = "BYTES")]
    max_alloc: Option<u64>,
    /// Refuse input files longer than this many bytes (default 16 GiB).
    #[arg(long, value_name = "BYTES")]
    max_input: Option<u64>,
    /// Print statistics as JSON.
    #[arg(long)]
    json: bool,
}

/// The decoder's limits, as the arguments set them.
fn limits(args: &Args) -> swm::Limits {
    let default = swm::Limits::default();
    swm::Limits {
        max_vertices: args.max_vertices.unwrap_or(default.max_vertices),
        max_faces: args.max_faces.unwrap_or(default.max_faces),
        max_alloc_bytes: args.max_alloc.unwrap_or(default.max_alloc_bytes),
        max_input_bytes: args.max_input.unwrap_or(default.max_input_bytes),
    }
}

pub fn run(args: &Args) -> Result<(), CliError> {
    if crate::scene::is_scene_input(&args.input) {
        return crate::scene::decode(&args.input, &args.output, limits(args), args.json);
    }
    crate::same_file::refuse_same_file(&args.input, &args.output)?;
    crate::pipe::data_on_stdout(&args.output);
    // Refuse an unknown or unwritable output format before doing any
    // work (bad usage).
    let format = crate::pipe::output_format(&args.output, args.format)?;
    let limits = limits(args);
    // Mapped when large: the decoder reads the file once, front to back.
    let bytes: Box<dyn Deref<Target = [u8]>> = if crate::pipe::is_stdio(&args.input) {
        crate::pipe::read_stdin(limits.max_input_bytes).map(|b| Box::new(b) as Box<_>)
    } else {
        swm::io::read_file_with(&args.input, &limits).map(|b| Box::new(b) as Box<_>)
    }
    .map_err(|e| CliError::new(&args.input, e))?;
    let sharpen = match (args.sharpen, args.no_sharpen) {
        (true, _) => Some(true),
        (_, true) => Some(false),
        _ => None,
    };
    let options = swm::DecodeOptions {
        sharpen,
        bend_steps: args.bend,
        max_level: args.max_level,
        limits,
    };
    let start = Instant::now();
    // With its attribute streams, when the file has them (`ATTR` of a
    // lossless or displaced file); a file without any decodes to the
    // plain mesh. Post-processing asked for by name changes the mesh the
    // streams were coded over: the mesh is post-processed, and the
    // streams are not written; the warning says so.
    let streams = options.post_processing_asked()
        && swm::container::parse_container(&bytes, &options.limits)
            .is_ok_and(|f| f.find(swm::container::Tag::ATTR).is_some());
    if streams {
        eprintln!(
            "swm: warning: {}: the file's attributes are not written (--sharpen and --bend change the mesh they were coded over)",
            args.input.display()
        );
    }
    // The library's rule: post-processing asked for runs, and then the
    // mesh comes without its streams.
    let attributed =
        swm::decode_attributed(&bytes, &options).map_err(|e| CliError::new(&args.input, e))?;
    let seconds = start.elapsed().as_secs_f64();
    let report = if crate::pipe::is_stdio(&args.output) {
        let mut out = Vec::new();
        swm::io::write_attributed_mesh_to(&mut out, format, &attributed)
            .and_then(|r| crate::pipe::write_stdout(&out).map(|()| r))
    } else {
        swm::io::write_attributed_mesh_as(&args.output, format, &attributed)
    }
    .map_err(|e| CliError::new(&args.output, e))?;
    let unwritten: Vec<&str> = report.unwritten.names().collect();
    if !unwritten.is_empty() {
        eprintln!(
            "swm: warning: {}: the file's {} are not written ({} cannot hold them)",
            args.output.display(),
            unwritten.join(" and "),
            format.name()
        );
    }
    let mesh = attributed.mesh;
    if args.json {
        let info =
            swm::inspect(&bytes, &options.limits).map_err(|e| CliError::new(&args.input, e))?;
        let mut v = match &info.swing {
            Some(s) => crate::report::swing_json(s),
            None => crate::report::lossless_json(&info.stats, info.qp),
        };
        v["decode_seconds"] = seconds.into();
        // `vertices` and `triangles` are the file's (of a swing file, the
        // retiled part); these count everything written, the lossless
        // REST, Sharpen&Bend included, as the text line does.
        v["decoded_vertices"] = mesh.vertex_count().into();
        v["decoded_triangles"] = mesh.face_count().into();
        crate::report::print_json(&v);
    } else {
        crate::report::print_written(&args.input, &args.output, &mesh, seconds);
    }
    Ok(())
}
