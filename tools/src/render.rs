//! `swm render IN -o OUT.svg [--view X,Y,Z] [--size PX]`: a picture of a
//! mesh (any format the CLI reads) or of a `.swm` file (decoded first),
//! as an SVG of flat-shaded triangles, so that the README can show a
//! before and after made by the project's own tool (issue 23).
//!
//! How it draws:
//! - orthographic projection along the view direction (the direction
//!   from the mesh towards the eye), world +Y up on the screen; along
//!   the Y axis, where +Y cannot be up, +X stays to the right (looking
//!   down from +Y shows +Z towards the bottom, as a map);
//! - back faces culled: a triangle is drawn when its corners turn
//!   counter-clockwise as seen from the eye, the outward orientation the
//!   codec keeps; a mesh whose triangles face inward shows its inside;
//! - flat shading: one grey per triangle from its normal and a light
//!   fixed relative to the eye (above, left, in front), so that every
//!   view is lit the same way;
//! - painter's algorithm: triangles sorted far to near by the depth of
//!   their centroid, ties by face index, so the output is the same bytes
//!   on every run;
//! - the picture's bounding box fitted to the canvas, its longer side
//!   `--size` pixels, coordinates rounded to 0.1 px.
//!
//! Limits: the painter's algorithm has no depth buffer, so intersecting
//! triangles, or triangles that overlap cyclically or whose centroids
//! order them wrongly (long thin ones next to small ones), may draw in
//! the wrong order. That is fine for a picture of a closed surface, not
//! for measuring anything; `swm distance` is the measure. The SVG holds
//! one path of about 50 bytes per front face, so a million-triangle mesh
//! makes tens of MB: draw a decoded or simplified version of it instead.

use crate::error::CliError;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// The default view: a three-quarter view from the front right, a little
/// above (for a mesh modelled with +Y up and facing +Z).
const DEFAULT_VIEW: [f64; 3] = [1.0, 0.6, 1.4];

/// The light's direction in the eye's frame (right, up, towards the eye):
/// from above left and in front, so that most front faces are lit and
/// the shading reads as relief, the same in every view.
const LIGHT: [f64; 3] = [-0.4, 0.6, 0.7];

/// Grey of a triangle edge-on to the light (ambient) and the range the
/// diffuse term adds on top: dark enough that silhouettes stand out on a
/// white page, never pure white so that facing triangles keep a contour
/// against it.
const AMBIENT: f64 = 40.0;
const DIFFUSE: f64 = 200.0;

/// Width of the stroke each triangle gets in its own grey: it covers the
/// hairline cracks anti-aliasing leaves between neighbours, and is thin
/// enough not to thicken the silhouette visibly.
const STROKE: &str = "0.5";

/// Blank border around the picture, in pixels.
const MARGIN: f64 = 4.0;

#[derive(clap::Args)]
pub struct Args {
    /// The mesh to draw (.obj, .ply, .off, .stl, .gltf, .glb), or a .swm
    /// file, which is decoded first.
    input: PathBuf,
    /// The SVG file to write.
    #[arg(short, long)]
    output: PathBuf,
    /// Direction from the mesh towards the eye, three numbers not all
    /// zero (default 1,0.6,1.4: front right, a little above).
    #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true)]
    view: Option<String>,
    /// Length of the picture's longer side in pixels, 16 to 16384.
    #[arg(
        long,
        value_name = "PX",
        default_value_t = 512,
        value_parser = clap::value_parser!(u32).range(16..=16384)
    )]
    size: u32,
}

pub fn run(args: &Args) -> Result<(), CliError> {
    crate::same_file::refuse_same_file(&args.input, &args.output)?;
    let is_svg = args
        .output
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("svg"));
    if !is_svg {
        // A slip such as `-o spot.obj` would otherwise replace a mesh
        // with a picture; bad usage, as encode's mesh-named outputs.
        let e = std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            "the output of render is an SVG file; name it .svg",
        );
        return Err(CliError::usage(&args.output, e));
    }
    // Checked here rather than by a clap value parser so that a bad view
    // gives the one-line `swm: error:` of every other failure.
    let view = match &args.view {
        None => DEFAULT_VIEW,
        Some(s) => parse_view(s).map_err(|msg| {
            let e = std::io::Error::new(std::io::ErrorKind::InvalidInput, msg);
            CliError::usage(Path::new("--view"), e)
        })?,
    };
    let mesh = read(&args.input)?;
    let picture = draw(&mesh, view, args.size).map_err(|e| CliError::new(&args.input, e))?;
    swm::io::write_bytes(&args.output, picture.svg.as_bytes())
        .map_err(|e| CliError::new(&args.output, e))?;
    say!(
        "{} -> {}: {} of {} triangles drawn, {}x{} px, {} bytes",
        args.input.display(),
        args.output.display(),
        picture.drawn,
        mesh.face_count(),
        picture.width,
        picture.height,
        picture.svg.len()
    );
    Ok(())
}

/// The mesh in `path`: a `.swm` file decoded with the default options
/// (what `swm decode` writes, without Sharpen&Bend), or a mesh file.
fn read(path: &Path) -> Result<swm::TriMesh, CliError> {
    let err = |e| CliError::new(path, e);
    let is_swm = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("swm"));
    if is_swm {
        let bytes = swm::io::read_file(path).map_err(err)?;
        return swm::decode(&bytes, &swm::DecodeOptions::default()).map_err(err);
    }
    let mesh = swm::io::read_mesh(path).map_err(err)?;
    // The readers check this already; drawing indexes positions by the
    // triangles' indices, so make sure rather than panic on a bad mesh.
    mesh.validate().map_err(|e| err(e.into()))?;
    Ok(mesh)
}

/// `X,Y,Z`: three finite numbers, not all zero.
fn parse_view(s: &str) -> Result<[f64; 3], String> {
    let bad =
        || format!("{s:?} is not a view direction: expected X,Y,Z, three numbers not all zero");
    let parts: Vec<f64> = s
        .split(',')
        .map(|p| p.trim().parse::<f64>().map_err(|_| bad()))
        .collect::<Result<_, _>>()?;
    let v: [f64; 3] = parts.try_into().map_err(|_| bad())?;
    if v.iter().any(|x| !x.is_finite()) || v.iter().all(|&x| x == 0.0) {
        return Err(bad());
    }
    Ok(v)
}

/// A drawn picture.
struct Picture {
    svg: String,
    /// Triangles drawn (the front faces).
    drawn: usize,
    width: u32,
    height: u32,
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn normalize(a: [f64; 3]) -> [f64; 3] {
    let l = dot(a, a).sqrt();
    [a[0] / l, a[1] / l, a[2] / l]
}

/// The eye's frame for the view direction `d` (towards the eye): right,
/// up and `d` itself, normalized, right-handed.
fn eye_frame(d: [f64; 3]) -> [[f64; 3]; 3] {
    let d = normalize(d);
    // World +Y up, unless the view is (nearly) along Y, where it would
    // leave no right vector; then Z, its sign chosen so that +X stays to
    // the right (looking down from +Y, +Z is towards the bottom).
    let up = if d[1].abs() > 0.999 {
        [0.0, 0.0, -d[1].signum()]
    } else {
        [0.0, 1.0, 0.0]
    };
    let right = normalize(cross(up, d));
    let up = cross(d, right);
    [right, up, d]
}

/// Draws `mesh` seen from `view` (see the module header).
fn draw(mesh: &swm::TriMesh, view: [f64; 3], size: u32) -> Result<Picture, swm::Error> {
    if mesh.triangles.is_empty() {
        return Err(swm::TopologyError::NoTriangles.into());
    }
    let [right, up, toward] = eye_frame(view);
    let light = normalize([
        LIGHT[0] * right[0] + LIGHT[1] * up[0] + LIGHT[2] * toward[0],
        LIGHT[0] * right[1] + LIGHT[1] * up[1] + LIGHT[2] * toward[1],
        LIGHT[0] * right[2] + LIGHT[1] * up[2] + LIGHT[2] * toward[2],
    ]);
    let point = |v: u32| {
        let p = mesh.positions[v as usize];
        [p[0] as f64, p[1] as f64, p[2] as f64]
    };
    // Eye coordinates of a point: (right, up, depth), depth growing
    // towards the eye.
    let eye = |p: [f64; 3]| [dot(p, right), dot(p, up), dot(p, toward)];

    // The picture's bounding box: of the triangles' corners only, so that
    // a stray unreferenced vertex does not shrink the mesh to a dot.
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for t in &mesh.triangles {
        for &v in t {
            let e = eye(point(v));
            for k in 0..2 {
                lo[k] = lo[k].min(e[k]);
                hi[k] = hi[k].max(e[k]);
            }
        }
    }
    let extent = (hi[0] - lo[0]).max(hi[1] - lo[1]);
    let inner = size as f64 - 2.0 * MARGIN;
    // A mesh seen edge-on (all in one line or point) keeps scale 1 and is
    // centred; its triangles are all culled anyway.
    let scale = if extent > 0.0 { inner / extent } else { 1.0 };
    let width = ((hi[0] - lo[0]) * scale + 2.0 * MARGIN).ceil().max(1.0) as u32;
    let height = ((hi[1] - lo[1]) * scale + 2.0 * MARGIN).ceil().max(1.0) as u32;
    // SVG's y grows downwards: flip the eye's up.
    let to_px = |e: [f64; 3]| {
        [
            MARGIN + (e[0] - lo[0]) * scale,
            MARGIN + (hi[1] - e[1]) * scale,
        ]
    };

    // Front faces with their depth and grey.
    let mut faces: Vec<(f64, u32, u8)> = Vec::new();
    for (f, t) in mesh.triangles.iter().enumerate() {
        let [a, b, c] = t.map(point);
        let n = cross(sub(b, a), sub(c, a));
        // Counter-clockwise from the eye: the normal points towards it.
        // Degenerate triangles (n = 0) cover nothing and are skipped too.
        if dot(n, toward) <= 0.0 {
            continue;
        }
        let lit = dot(normalize(n), light).max(0.0);
        let grey = (AMBIENT + DIFFUSE * lit).round().clamp(0.0, 255.0) as u8;
        let depth = (eye(a)[2] + eye(b)[2] + eye(c)[2]) / 3.0;
        faces.push((depth, f as u32, grey));
    }
    // Far to near; equal depths by face index, so the order (and the
    // bytes) never depend on the sort's stability or the platform.
    faces.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));

    let mut svg = String::with_capacity(64 + faces.len() * 48);
    // Each path sets `color`; fill and stroke take it through
    // `currentColor`, which writes each grey once instead of twice.
    let _ = writeln!(
        svg,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}\" height=\"{height}\" \
         viewBox=\"0 0 {width} {height}\">"
    );
    let _ = writeln!(
        svg,
        "<g fill=\"currentColor\" stroke=\"currentColor\" stroke-width=\"{STROKE}\" \
         stroke-linejoin=\"round\">"
    );
    for &(_, f, grey) in &faces {
        let [a, b, c] = mesh.triangles[f as usize].map(|v| to_px(eye(point(v))));
        let _ = writeln!(
            svg,
            "<path color=\"#{grey:02x}{grey:02x}{grey:02x}\" d=\"M{} {} {} {} {} {}z\"/>",
            px(a[0]),
            px(a[1]),
            px(b[0]),
            px(b[1]),
            px(c[0]),
            px(c[1])
        );
    }
    svg.push_str("</g>\n</svg>\n");
    Ok(Picture {
        svg,
        drawn: faces.len(),
        width,
        height,
    })
}

/// A coordinate rounded to 0.1 px, without a trailing `.0` and never
/// `-0`, to keep the file small.
fn px(x: f64) -> String {
    let tenths = (x * 10.0).round() as i64;
    if tenths % 10 == 0 {
        format!("{}", tenths / 10)
    } else {
        format!(
            "{}{}.{}",
            if tenths < 0 { "-" } else { "" },
            (tenths / 10).abs(),
            (tenths % 10).abs()
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coordinates_round_to_a_tenth() {
        let cases = [
            (0.0, "0"),
            (-0.04, "0"),
            (12.34, "12.3"),
            (12.36, "12.4"),
            (7.96, "8"),
            (-0.3, "-0.3"),
            (-1.25, "-1.3"),
        ];
        for (x, s) in cases {
            assert_eq!(px(x), s, "{x}");
        }
    }

    #[test]
    fn views_refused_and_accepted() {
        for bad in ["0,0,0", "1,2", "1,2,3,4", "x,1,1", "nan,1,1", "inf,0,0", ""] {
            assert!(parse_view(bad).is_err(), "{bad}");
        }
        assert_eq!(parse_view(" -1, 0.5 ,2"), Ok([-1.0, 0.5, 2.0]));
    }

    /// One triangle, counter-clockwise seen from +Z: drawn from the front,
    /// culled from behind, and the eye frame is right-handed in every
    /// view, the special case along Y included.
    #[test]
    fn culling_follows_the_winding() {
        let mesh = swm::TriMesh::new(
            vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
            vec![[0, 1, 2]],
        );
        assert_eq!(draw(&mesh, [0.0, 0.0, 1.0], 64).unwrap().drawn, 1);
        assert_eq!(draw(&mesh, [0.2, 0.1, -1.0], 64).unwrap().drawn, 0);
        for d in [
            [0.0, 1.0, 0.0],
            [0.0, -2.0, 0.0],
            [1.0, 0.6, 1.4],
            [0.0, 0.0, -1.0],
        ] {
            let [r, u, t] = eye_frame(d);
            let c = cross(r, u);
            for k in 0..3 {
                assert!((c[k] - t[k]).abs() < 1e-12, "{d:?}");
            }
        }
    }
}
