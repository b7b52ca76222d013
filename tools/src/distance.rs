//! `swm distance A B [--samples N] [--sampling metro|faces] [--texcoords
//! [--texture-size N]] [--json]`: how far mesh B lies from mesh A, as Metro
//! measures it (see `swm::metrics`), and with `--texcoords` how far B's
//! texture coordinates are from A's, in texels (`swm::metrics::texcoord`).
//!
//! A is the reference: relative values divide by A's bounding-box
//! diagonal, and "forward" means samples on A measured against B
//! ("backward" the other way). L2 and Hausdorff are the larger of the two
//! one-sided RMS and maximum distances. Samples follow Metro: every
//! vertex, points along every edge, and area-proportional face samples —
//! by default ten per face of the larger mesh, or N per surface with
//! `--samples N`. The meshes are measured as read, without cleaning:
//! distance is a property of the surfaces, whatever their connectivity.

use crate::error::CliError;
use serde_json::json;
use std::path::PathBuf;
use swm::metrics::{DistanceOptions, OneSided, Surface};

#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum Sampling {
    /// Every vertex, points along every edge, area-proportional faces.
    Metro,
    /// Area-proportional face samples only.
    Faces,
}

#[derive(clap::Args)]
pub struct Args {
    /// The reference mesh (.obj, .ply, .off, .stl, .gltf, .glb).
    reference: PathBuf,
    /// The mesh measured against it.
    other: PathBuf,
    /// Area-proportional face samples on each surface (default: ten per
    /// face of the larger mesh, as Metro).
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..))]
    samples: Option<u64>,
    /// Which samples: `metro` (vertices, edges and faces, Metro's
    /// default) or `faces` (area-uniform face samples only: the thesis's
    /// L2, and MeshLab's Hausdorff filter with face sampling).
    #[arg(long, value_enum, default_value = "metro")]
    sampling: Sampling,
    /// Print JSON: l2, hausdorff, mean, l2_relative, hausdorff_relative,
    /// diagonal, and the one-sided forward (A to B) and backward (B to A)
    /// samples, mean, rms and max.
    #[arg(long)]
    json: bool,
    /// Also measure B's texture coordinates (set 0) against A's, in texels
    /// of a square texture (`--texture-size`): at points over B's surface,
    /// B's coordinate against A's at the nearest point of A. Both meshes
    /// must have texture coordinates.
    #[arg(long)]
    texcoords: bool,
    /// The side of the square texture, in texels, the `--texcoords` error
    /// is stated in.
    #[arg(long, default_value_t = 1024, requires = "texcoords",
          value_parser = clap::value_parser!(u32).range(1..))]
    texture_size: u32,
}

/// The texture coordinate error of `--texcoords`, at the asked texture size.
struct Texcoords {
    rms_texels: f64,
    max_texels: f64,
    texture_size: u32,
    samples: u64,
}

pub fn run(args: &Args) -> Result<(), CliError> {
    // Each file is read and prepared on its own so an error names it. With
    // `--texcoords` the attribute streams are kept; the mesh is the same
    // one either way (`swm::io::read_attributed_mesh_with`).
    let prepare = |path: &PathBuf| -> Result<(Surface, Option<swm::AttributedMesh>), CliError> {
        let err = |e| CliError::new(path, e);
        if args.texcoords {
            let limits = swm::Limits::default();
            let (m, _) = swm::io::read_attributed_mesh_with(path, None, &limits).map_err(err)?;
            if m.stream(swm::AttributeKind::TexCoord(0)).is_none() {
                return Err(crate::error::fail(
                    path,
                    "no texture coordinates (--texcoords needs them in both meshes)",
                ));
            }
            let surface = Surface::new(&m.mesh).map_err(err)?;
            Ok((surface, Some(m)))
        } else {
            let m = swm::io::read_mesh(path).map_err(err)?;
            Ok((Surface::new(&m).map_err(err)?, None))
        }
    };
    let (a, b) = rayon::join(|| prepare(&args.reference), || prepare(&args.other));
    let ((a, a_mesh), (b, b_mesh)) = (a?, b?);
    let texcoords = match (&a_mesh, &b_mesh) {
        (Some(am), Some(bm)) => {
            let e = swm::metrics::texcoord::texcoord_error(am, &a, bm).ok_or_else(|| {
                crate::error::fail(
                    &args.other,
                    "texture coordinates not comparable with the reference's \
                     (different component counts, or no faces measured)",
                )
            })?;
            // The library states texels at a fixed size
            // (`swm::metrics::texcoord::TEXTURE_SIZE`, 1024, carried in
            // `texture_size`): the error in texture-coordinate units times
            // the size, so another size scales it by N / that size.
            let scale = f64::from(args.texture_size) / e.texture_size;
            Some(Texcoords {
                rms_texels: e.rms_texels * scale,
                max_texels: e.max_texels * scale,
                texture_size: args.texture_size,
                samples: e.samples,
            })
        }
        _ => None,
    };
    let metro = args.sampling == Sampling::Metro;
    let options = DistanceOptions {
        face_samples: args.samples,
        vertex_samples: metro,
        edge_samples: metro,
        ..Default::default()
    };
    let d = swm::metrics::distance_between(&a, &b, &options)
        .map_err(|e| CliError::new(&args.reference, e))?;
    if args.json {
        let side = |s: &OneSided| json!({ "samples": s.samples, "mean": s.mean, "rms": s.rms, "max": s.max });
        let mut v = json!({
            "l2": d.l2(),
            "hausdorff": d.hausdorff(),
            "mean": d.mean(),
            "l2_relative": d.l2_relative(),
            "hausdorff_relative": d.hausdorff_relative(),
            "diagonal": d.diagonal,
            "forward": side(&d.forward),
            "backward": side(&d.backward),
        });
        if let Some(t) = &texcoords {
            v["texcoords"] = json!({
                "rms_texels": t.rms_texels,
                "max_texels": t.max_texels,
                "texture_size": t.texture_size,
                "samples": t.samples,
            });
        }
        crate::report::print_json(&v);
        return Ok(());
    }
    let (ra, rb) = (args.reference.display(), args.other.display());
    // Scientific notation where plain digits would run long.
    let diagonal = if (1e-3..1e6).contains(&d.diagonal) {
        format!("{}", d.diagonal)
    } else {
        format!("{:e}", d.diagonal)
    };
    say!("reference {ra}, bbox diagonal {diagonal}");
    say!(
        "  L2         {:<14.6e} ({})",
        d.l2(),
        of_diagonal(d.l2_relative())
    );
    say!(
        "  Hausdorff  {:<14.6e} ({})",
        d.hausdorff(),
        of_diagonal(d.hausdorff_relative())
    );
    say!("  mean       {:<14.6e}", d.mean());
    for (label, s) in [
        (format!("{ra} -> {rb}"), &d.forward),
        (format!("{rb} -> {ra}"), &d.backward),
    ] {
        say!(
            "  {label}: {} samples, mean {:.6e}, rms {:.6e}, max {:.6e}",
            s.samples,
            s.mean,
            s.rms,
            s.max
        );
    }
    if let Some(t) = &texcoords {
        say!(
            "  texture coordinates: RMS {:.3} texels, max {:.3} texels (at {n}x{n}, {} points)",
            t.rms_texels,
            t.max_texels,
            t.samples,
            n = t.texture_size
        );
    }
    Ok(())
}

/// A distance relative to the diagonal, in units of 1e-4 as the thesis
/// reports them, or in scientific notation when that would take more
/// digits than it says (meshes far apart or of very different sizes).
fn of_diagonal(relative: f64) -> String {
    if relative < 1e-2 {
        format!("{:.4} x 1e-4 of the diagonal", 1e4 * relative)
    } else {
        format!("{relative:.4e} times the diagonal")
    }
}
