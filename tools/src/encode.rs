//! `swm encode IN -o OUT.swm [--mode auto|swing|lossless] [--size B | --bpv X |
//! --edge-length L] [--angle-bits K] [--max-size B] [--qp N] [--format F]
//! [--json] [--verbose] [--force] [--strict] [--quiet]`. Options a mode
//! does not use are refused, not ignored, and so is an output named like
//! a mesh file (without `--force`). The file is decoded and measured
//! against the input before it is written (see `fidelity`; `--strict`
//! makes a failed check an error), and a spinner shows the phase on a
//! terminal (see `progress`). What the report says goes to stdout (stderr
//! with `-o -`); warnings, what cleaning changed and each component's
//! fate go to stderr. IN and OUT may be `-` (standard input and output, see `pipe`).
//! A glTF input to a `.glb` or `.gltf` output is a whole scene (`scene`).

use crate::error::CliError;
use std::path::PathBuf;
use std::time::Instant;

#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum ModeArg {
    /// Both SwingWrapper and simplify-then-lossless at the requested size;
    /// the one the encoder measures closer to the input is written (a
    /// failed retiling falls back).
    Auto,
    /// SwingWrapper: retile into near-equilateral triangles, one dihedral
    /// angle per vertex. Holes are masked, handles kept while L is below
    /// their thickness, and parts too small for L kept losslessly.
    Swing,
    /// Keep the input's exact triangles, positions quantized to --qp bits;
    /// with --size or --bpv, quadric-simplify first to fit the size.
    Lossless,
    /// Displaced subdivision (format 1.2): a quadric-simplified base coded
    /// losslessly, levels of 1-to-4 subdivision, one quantized scalar per
    /// new vertex along its predicted normal; needs --size or --bpv.
    Displaced,
}

#[derive(clap::Args)]
pub struct Args {
    /// The mesh to encode (.obj, .ply, .off, .stl, .gltf, .glb), or - for
    /// standard input (with --format).
    pub(crate) input: PathBuf,
    /// The .swm file to write, or - for standard output (reports then go
    /// to standard error).
    #[arg(short, long)]
    pub(crate) output: PathBuf,
    /// The input's format when its name does not say (standard input, no
    /// extension): obj, ply, off, stl, glb or gltf (a .gltf on standard
    /// input must embed its buffers).
    #[arg(long, value_parser = crate::pipe::parse_format)]
    pub(crate) format: Option<swm::io::MeshFormat>,
    /// The codec.
    #[arg(long, value_enum, default_value = "auto")]
    pub(crate) mode: ModeArg,
    /// How hard the encoder works (as Draco's -cl and zstd's levels):
    /// `fast` simplifies with a short search (about a lossless encode's
    /// time plus one simplification); `default` measures the simplified
    /// file against SwingWrapper where retiling fits its work budget and
    /// displaced subdivision at low rates; `max` runs every method's
    /// whole search (minutes on large inputs at high rates).
    #[arg(long, value_enum, default_value_t = EffortArg::Default)]
    pub(crate) effort: EffortArg,
    /// Target file size in bytes (met within 3%; lossless: simplify to fit).
    #[arg(long, conflicts_with_all = ["bpv", "edge_length", "max_error", "max_error_units"], value_parser = crate::args::positive_bytes, allow_negative_numbers = true)]
    pub(crate) size: Option<u64>,
    /// Target bits per input vertex (auto and swing: default 2 when no
    /// target is given; lossless: simplify to fit).
    #[arg(long, conflicts_with_all = ["edge_length", "max_error", "max_error_units"], value_parser = crate::args::positive_finite, allow_negative_numbers = true)]
    pub(crate) bpv: Option<f64>,
    /// The smallest file whose L2 distance to the input is at most E,
    /// relative to the input's bounding-box diagonal as `swm distance`
    /// reports it (2e-4 is "2 x 1e-4 of the diagonal"); auto and lossless
    /// modes.
    #[arg(long, value_name = "E", conflicts_with_all = ["edge_length", "max_error_units"], value_parser = crate::args::positive_finite, allow_negative_numbers = true)]
    pub(crate) max_error: Option<f64>,
    /// The same bound in the mesh's units.
    #[arg(long, value_name = "D", conflicts_with = "edge_length", value_parser = crate::args::positive_finite, allow_negative_numbers = true)]
    pub(crate) max_error_units: Option<f64>,
    /// Swing: the edge length L itself, in the mesh's units (auto: the
    /// simplified candidate gets the retiled file's size).
    #[arg(long, value_parser = crate::args::positive_finite, allow_negative_numbers = true)]
    pub(crate) edge_length: Option<f64>,
    /// Swing: bits per dihedral angle [default: chosen by rate control, 6
    /// or 5 (or 7 when 6 falls short of the size); 8 with --edge-length].
    #[arg(long, value_parser = clap::value_parser!(u8).range(4..=12))]
    pub(crate) angle_bits: Option<u8>,
    /// Swing: aim every new vertex at the input surface, as the thesis
    /// does, instead of off it by the offset that cancels the chord error,
    /// and send the angle nearest that aim instead of the one whose
    /// triangle fits the surface it covers best (for files to be decoded
    /// with --sharpen: EdgeSharpener fits the planes of flat regions
    /// through their vertices).
    #[arg(long)]
    pub(crate) on_surface: bool,
    /// Swing: shorter edges where the surface bends, is thin or creased,
    /// longer where it is flat, instead of one edge length everywhere
    /// (experimental; the file is then format 1.1).
    #[arg(long)]
    pub(crate) adaptive: bool,
    /// Swing: code the connectivity as format 1.0 does (`CLRS`, each
    /// symbol in the context of the previous one), for decoders older
    /// than 1.1, instead of with the shape of the front at each gate
    /// (`CLRF`), which takes about a fifth of the bits.
    #[arg(long)]
    pub(crate) plain_clers: bool,
    /// Swing: start every retiling inside its component, as format 1.0
    /// does, even on an open surface, instead of on its longest boundary
    /// loop (`LOOP`, format 1.1), where the hole's patch costs one fan of
    /// connectivity rather than a retiling the decoder drops.
    #[arg(long)]
    pub(crate) inside_start: bool,
    /// Swing: do not measure EdgeSharpener and Bender on the file nor
    /// record their best use in it (the `post` hint that `swm decode`
    /// follows by default), and do not try tips on the surface where
    /// EdgeSharpener helps; saves three decodes and measures (and, on
    /// sharp-edged parts, a second rate control).
    #[arg(long)]
    pub(crate) no_hint: bool,
    /// Swing: do not try tips on the input's sharp edges (radius codes,
    /// format 1.1; tried where the creases total at least the bounding
    /// box's diagonal, and kept when that file decodes closer).
    #[arg(long)]
    pub(crate) no_creases: bool,
    /// How the file's header and section table are laid out: `compact`
    /// (format 1.1: varints and one-byte tags, about 30 bytes fewer) or
    /// `fixed` (format 1.0's layout, for decoders older than 1.1).
    #[arg(long, value_enum, default_value_t = FramingArg::Compact)]
    pub(crate) framing: FramingArg,
    /// With --size or --bpv: when the request is below the smallest file
    /// that can hold the mesh, write that smallest file (and say so)
    /// instead of failing; never above --max-size.
    #[arg(long)]
    pub(crate) or_smallest: bool,
    /// Never write more than this many bytes (lossless: with --size or --bpv).
    #[arg(long, value_parser = crate::args::positive_bytes, allow_negative_numbers = true)]
    pub(crate) max_size: Option<u64>,
    /// Lossless without a size: bits per coordinate [default: 12].
    #[arg(long, value_parser = clap::value_parser!(u8).range(6..=24))]
    pub(crate) qp: Option<u8>,
    /// Lossless and auto: bits per texture coordinate, as Draco's -qt
    /// [default: 10].
    #[arg(long, value_parser = clap::value_parser!(u8).range(2..=24))]
    pub(crate) qt: Option<u8>,
    /// Lossless and auto: bits per octahedral coordinate of a normal, as
    /// Draco's -qn [default: 8].
    #[arg(long, value_parser = clap::value_parser!(u8).range(4..=16))]
    pub(crate) qn: Option<u8>,
    /// Auto: code the input's normals even where they follow the
    /// geometry (within 10 degrees RMS of its own), which by default are
    /// left to decoders to recompute.
    #[arg(long)]
    pub(crate) keep_normals: bool,
    /// Lossless and auto: bits per colour or generic component, as
    /// Draco's -qg [default: 8].
    #[arg(long, value_parser = clap::value_parser!(u8).range(2..=24))]
    pub(crate) qg: Option<u8>,
    /// Swing: stop with an error after this many steps of retiling work
    /// (walks and searches on the surface, over every run of rate
    /// control; bunny at 1 b/v takes about 10^8). Default: no cap.
    #[arg(long, value_name = "STEPS", value_parser = clap::value_parser!(u64).range(1..))]
    pub(crate) max_work: Option<u64>,
    /// Swing: stop with an error when the retiler's working meshes would
    /// hold more than this many bytes. Default: 8 GiB.
    #[arg(long, value_name = "BYTES", value_parser = clap::value_parser!(u64).range(1..))]
    pub(crate) max_memory: Option<u64>,
    /// Swing: stop with an error after this many seconds (checked between
    /// retiling steps; the bytes of a file that is written never depend
    /// on it). Default: no limit.
    #[arg(long, value_name = "SECONDS", value_parser = positive_seconds)]
    pub(crate) time_limit: Option<f64>,
    /// glTF scenes (IN .glb or .gltf, OUT .glb or .gltf): keep an
    /// uncompressed copy of each coded primitive's decoded mesh, so that
    /// viewers without swm still draw it (SWM_mesh_compression is then
    /// only in extensionsUsed, not extensionsRequired).
    #[arg(long)]
    pub(crate) gltf_fallback: bool,
    /// Print statistics as JSON.
    #[arg(long)]
    pub(crate) json: bool,
    /// Write OUT even when its extension names a mesh format (.obj, .ply,
    /// .off, .stl, .glb, .gltf): the file is a .swm file whatever its name
    /// (without it, a .glb or .gltf input to a .glb or .gltf output is
    /// compressed as a whole glTF scene).
    #[arg(long)]
    pub(crate) force: bool,
    /// List every component in the text report (by default a long list is
    /// cut after its first lines and summed up by fate).
    #[arg(long)]
    pub(crate) verbose: bool,
    /// No progress spinner. It is drawn on standard error only when that
    /// is a terminal and the run takes over a second (phases: reading,
    /// encoding, writing), never on standard output.
    #[arg(short, long)]
    pub(crate) quiet: bool,
    /// Exit 1 and write nothing when the check of the decoded mesh fails,
    /// or when an attribute stream of the input is not kept (otherwise a
    /// warning on standard error). The check decodes the
    /// file and measures it against the input (60,000 of Metro's samples
    /// each way, 20,000 at --effort fast, as swm distance takes them): it fails when the decoded
    /// surface area is under 10% of the input's, or the Hausdorff
    /// distance is over 10% of the input's bounding-box diagonal.
    #[arg(long)]
    pub(crate) strict: bool,
}

/// Components listed one per line before the text report sums the rest
/// up (all of them with `--verbose`; JSON always has them all).
const LISTED_COMPONENTS: usize = 10;

impl Args {
    /// The lossless mode's bits per coordinate.
    pub(crate) fn qp(&self) -> u8 {
        self.qp.unwrap_or(12)
    }

    /// The attribute quantization of --qt, --qn and --qg.
    fn attributes(&self) -> swm::AttributeQuantization {
        let d = swm::AttributeQuantization::default();
        swm::AttributeQuantization {
            normal_bits: self.qn.unwrap_or(d.normal_bits),
            texcoord_bits: self.qt.unwrap_or(d.texcoord_bits),
            color_bits: self.qg.unwrap_or(d.color_bits),
            generic_bits: self.qg.unwrap_or(d.generic_bits),
        }
    }

    /// Whether --qt, --qn or --qg was given.
    fn attribute_bits(&self) -> bool {
        self.qt.is_some() || self.qn.is_some() || self.qg.is_some()
    }

    /// The options given that do not apply to the chosen mode, as a usage
    /// error: they would be silently ignored otherwise.
    pub fn check_mode(&self) -> Result<(), String> {
        let bounded = self.max_error.is_some() || self.max_error_units.is_some();
        let sized = self.size.is_some() || self.bpv.is_some() || bounded;
        // The retiler's own options, which the other methods ignore.
        let retiler_only = [
            (self.edge_length.is_some(), "--edge-length"),
            (self.angle_bits.is_some(), "--angle-bits"),
            (self.on_surface, "--on-surface"),
            (self.adaptive, "--adaptive"),
            (self.plain_clers, "--plain-clers"),
            (self.inside_start, "--inside-start"),
            (self.no_hint, "--no-hint"),
            (self.no_creases, "--no-creases"),
            (self.max_work.is_some(), "--max-work"),
            (self.max_memory.is_some(), "--max-memory"),
            (self.time_limit.is_some(), "--time-limit"),
        ];
        let (mode, options): (&str, Vec<(bool, &str)>) = match self.mode {
            ModeArg::Swing => (
                "swing",
                vec![
                    (self.qp.is_some(), "--qp"),
                    (self.attribute_bits(), "--qt, --qn, --qg"),
                    (self.effort != EffortArg::Default, "--effort"),
                    (self.max_error.is_some(), "--max-error"),
                    (self.max_error_units.is_some(), "--max-error-units"),
                ],
            ),
            ModeArg::Auto => (
                "auto",
                vec![
                    (self.qp.is_some(), "--qp"),
                    (self.angle_bits.is_some(), "--angle-bits"),
                ],
            ),
            ModeArg::Displaced => (
                "displaced",
                vec![
                    (self.qp.is_some(), "--qp"),
                    (self.attribute_bits(), "--qt, --qn, --qg"),
                    (self.effort != EffortArg::Default, "--effort"),
                    (self.max_error.is_some(), "--max-error"),
                    (self.max_error_units.is_some(), "--max-error-units"),
                ]
                .into_iter()
                .chain(retiler_only)
                .collect(),
            ),
            ModeArg::Lossless => (
                "lossless",
                vec![
                    (self.qp.is_some() && sized, "--qp with --size or --bpv"),
                    (
                        self.effort != EffortArg::Default && !sized,
                        "--effort without --size, --bpv or --max-error",
                    ),
                    (
                        self.max_size.is_some() && !sized,
                        "--max-size without --size or --bpv",
                    ),
                ]
                .into_iter()
                .chain(retiler_only)
                .collect(),
            ),
        };
        let wrong: Vec<&str> = options
            .into_iter()
            .filter_map(|(given, name)| given.then_some(name))
            .collect();
        if wrong.is_empty() {
            return Ok(());
        }
        let verb = if wrong.len() == 1 { "does" } else { "do" };
        Err(format!(
            "{} {verb} not apply to --mode {mode}",
            wrong.join(", ")
        ))
    }
}

/// A positive, finite number of seconds.
fn positive_seconds(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(x) if x.is_finite() && x > 0.0 => Ok(x),
        _ => Err("expected a positive number of seconds, such as 30 or 0.5".into()),
    }
}

/// The codec options the arguments ask for (the mode, its target, the
/// tuning and limits); a scene splits the target between its primitives
/// (`scene`).
pub(crate) fn encode_options(args: &Args) -> swm::EncodeOptions {
    let bounded = args.max_error.is_some() || args.max_error_units.is_some();
    let target = match (args.size, args.bpv, args.edge_length) {
        (Some(b), _, _) => swm::SwingTarget::Bytes(b),
        (_, _, Some(l)) => swm::SwingTarget::EdgeLength(l),
        _ if args.max_error.is_some() || args.max_error_units.is_some() => {
            swm::SwingTarget::MaxError(match (args.max_error, args.max_error_units) {
                (Some(e), _) => swm::ErrorBound::Relative(e),
                (_, d) => swm::ErrorBound::Absolute(d.unwrap_or(f64::NAN)),
            })
        }
        (_, bpv, _) => swm::SwingTarget::BitsPerVertex(bpv.unwrap_or(2.0)),
    };
    let max_bytes = args.max_size;
    let mode = match args.mode {
        ModeArg::Lossless if args.size.is_none() && args.bpv.is_none() && !bounded => {
            swm::EncodeMode::Lossless { qp: args.qp() }
        }
        ModeArg::Lossless => swm::EncodeMode::Simplified { target, max_bytes },
        ModeArg::Auto => swm::EncodeMode::Auto { target, max_bytes },
        ModeArg::Displaced => swm::EncodeMode::Displaced { target, max_bytes },
        ModeArg::Swing => swm::EncodeMode::Swing {
            target,
            angle_bits: args.angle_bits,
            max_bytes,
        },
    };
    let defaults = swm::EncodeLimits::default();
    let limits = swm::EncodeLimits {
        max_work: args.max_work.unwrap_or(defaults.max_work),
        max_memory_bytes: args.max_memory.unwrap_or(defaults.max_memory_bytes),
        max_milliseconds: args
            .time_limit
            .map(|s| (s * 1000.0).ceil().min(u64::MAX as f64) as u64),
    };
    let options = swm::EncodeOptions {
        mode,
        limits,
        swing: swm::SwingTuning {
            approximate_tips: !args.on_surface,
            fit_tips: !args.on_surface,
            adaptive_density: args.adaptive,
            front_contexts: !args.plain_clers,
            loop_start: !args.inside_start,
            crease_tips: !args.no_creases,
            post_hint: !args.no_hint,
        },
        framing: match args.framing {
            FramingArg::Compact => swm::Framing::Compact,
            FramingArg::Fixed => swm::Framing::Fixed,
        },
        effort: args.effort.into(),
        attributes: args.attributes(),
        keep_smooth_normals: args.keep_normals,
        ..Default::default()
    };
    options
}

/// Encodes one mesh (a glTF scene in and out goes to `scene`, by `main`).
pub fn run(args: &Args) -> Result<(), CliError> {
    refuse_mesh_name(&args.output, args.force)?;
    crate::refuse_same_file(&args.input, &args.output)?;
    crate::pipe::data_on_stdout(&args.output);
    let format = crate::pipe::input_format(&args.input, args.format)?;
    let progress = crate::progress::Progress::spinner(args.quiet).prefix("swm encode");
    progress.phase("reading");
    let bounded = args.max_error.is_some() || args.max_error_units.is_some();
    // The lossless, automatic and simplified modes keep the input's
    // attributes (`ATTR`, format 1.2; the automatic mode weighs only the
    // methods that carry them), SwingWrapper and displaced files all but
    // texture coordinates: with those, they drop them with a warning.
    let (m, read) = crate::pipe::read_attributed_mesh(&args.input, format)?;
    let why = "not every face corner names them, or a value is malformed";
    let unattached = names_of(&read.dropped);
    progress.suspend(|| warn_dropped(&args.input, &unattached, why, args.strict))?;
    let mesh = m.mesh.clone();
    let uvs = (m.streams.iter()).any(|s| matches!(s.kind, swm::AttributeKind::TexCoord(_)));
    let attributed = match args.mode {
        ModeArg::Swing | ModeArg::Displaced if uvs => {
            let why = match args.mode {
                ModeArg::Swing => "the swing method's file cannot carry texture coordinates; --mode auto keeps them",
                _ => "the displaced method's file cannot carry texture coordinates; --mode auto keeps them",
            };
            let streams = names_of(&kinds_of(&m));
            progress.suspend(|| warn_dropped(&args.input, &streams, why, args.strict))?;
            None
        }
        _ => (!m.streams.is_empty()).then_some(m),
    };
    // No target given: the default rate is a convenience, not a request,
    // so a mesh too small for it gets its smallest file and a note.
    let defaulted = args.size.is_none()
        && args.bpv.is_none()
        && args.edge_length.is_none()
        && !bounded
        && args.mode != ModeArg::Lossless;
    let options = swm::EncodeOptions {
        // Allowed to write more than asked: the smallest file there is
        // (the encoder searches again in the same encode).
        or_smallest: args.or_smallest || defaulted,
        ..encode_options(args)
    };
    progress.phase("encoding");
    let start = Instant::now();
    let encoded = match attributed.as_ref() {
        Some(m) => swm::encode_attributed(m, &options),
        None => swm::encode(&mesh, &options),
    };
    let encoded = match encoded {
        // An explicit size below the smallest file: an error that says
        // how to get that file.
        Err(swm::Error::Size(e)) if !options.or_smallest => {
            return Err(crate::error::fail(
                &args.input,
                format!("{e} (--or-smallest writes it)"),
            ))
        }
        other => other.map_err(|e| CliError::new(&args.input, e))?,
    };
    if let Some(e) = &encoded.stats.smallest_instead {
        let why = if args.or_smallest {
            "--or-smallest"
        } else {
            "no size was given; the default is 2 bits per vertex"
        };
        eprintln!(
            "swm: note: {}: no file of {} bytes can hold this mesh; the smallest, {} bytes, was written ({why})",
            args.input.display(),
            e.requested,
            encoded.bytes.len()
        );
    }
    // Streams dropped for want of room, or normals that would crowd the
    // surface out: a loss, said on standard error (an error with
    // --strict).
    let lost = match encoded.stats.attributes.dropped_because {
        Some(why @ swm::AttributesDropped::NoRoom { .. }) => Some(why.to_string()),
        Some(why @ swm::AttributesDropped::CostlyNormals { .. }) => {
            Some(format!("{why}; --keep-normals keeps them"))
        }
        _ => None,
    };
    if let Some(why) = lost {
        let names: Vec<String> = (encoded.stats.attributes.dropped.iter())
            .map(|&k| crate::report::attribute_name(k))
            .collect();
        progress.suspend(|| warn_dropped(&args.input, &names, &why, args.strict))?;
    }
    let seconds = start.elapsed().as_secs_f64();
    // What a rate counts: the input's distinct positions, as the encoder
    // counts them.
    let positions = mesh.distinct_positions();
    // The lossless mode at a given qp keeps every triangle and moves each
    // vertex by at most half a quantization step: nothing to catch, and
    // on a million-triangle scan the check would cost several times the
    // encode. With a size it may coarsen the quantization, so it is
    // checked.
    let qp_only =
        args.mode == ModeArg::Lossless && args.size.is_none() && args.bpv.is_none() && !bounded;
    let (fidelity, warning) = if qp_only {
        (None, None)
    } else {
        check(args, encoded.stats.check.as_ref())?
    };
    progress.phase("writing");
    crate::pipe::write_bytes(&args.output, &encoded.bytes)
        .map_err(|e| CliError::new(&args.output, e))?;
    // Cleared before anything else is printed.
    drop(progress);
    if let Some(line) = warning {
        eprintln!("{line}");
    }
    let stats = &encoded.stats;
    if let Some(r) = stats.rate().filter(|r| !r.within_tolerance) {
        warn_missed_size(&args.input, r, encoded.bytes.len() as u64);
    }
    let (mut json, vertices, triangles) = match (stats.lossless(), stats.swing()) {
        (Some(l), _) => (
            crate::report::lossless_json(l, stats.simplified().map_or(args.qp(), |s| s.qp)),
            l.vertices,
            l.triangles,
        ),
        (_, Some(s)) => (crate::report::swing_json(s), s.vertices, s.triangles),
        _ => match (&stats.method, stats.check.as_ref()) {
            (swm::MethodStats::Displaced(d), check) => {
                let (v, t) = check.map_or((0, 0), |c| (c.decoded_vertices, c.decoded_triangles));
                let json = serde_json::json!({
                    "mode": "displaced",
                    "bytes": encoded.bytes.len(),
                    "base_faces": d.base_faces,
                    "levels": d.levels,
                    "qp": d.qp,
                    "base_bytes": d.base_bytes,
                    "level_bytes": d.level_bytes,
                    "misses": d.misses,
                    "vertices": v,
                    "triangles": t,
                });
                (json, v as u64, t as u64)
            }
            _ => (serde_json::json!({}), 0, 0),
        },
    };
    // The size asked for, when one was.
    let requested = match (args.size, args.bpv) {
        (Some(b), _) => Some(b),
        (_, Some(bpv)) => Some((bpv * positions as f64 / 8.0).round() as u64),
        _ => None,
    };
    let bytes = encoded.bytes.len() as u64;
    // The whole mesh at the simplified method's quantization, well short
    // of the request: nothing more to code (a note below, a flag in JSON).
    let whole_short = stats.simplified().is_some_and(|s| s.faces == s.input_faces)
        && requested.is_some_and(|r| bytes * 100 < r * 97);
    if args.json {
        if let Some(r) = requested {
            json["size"] = serde_json::json!({
                "requested": r,
                "within_tolerance": bytes * 100 >= r * 97 && bytes * 100 <= r * 103,
                "whole_mesh_short": whole_short,
            });
        }
        json["encode_seconds"] = seconds.into();
        json["input_vertices"] = positions.into();
        json["cleaning"] = crate::report::clean_json(&stats.clean);
        if let Some(r) = stats.rate() {
            json["rate_control"] = crate::report::rate_json(r);
        }
        if !stats.pieces().is_empty() {
            json["components"] = stats.pieces().iter().map(piece_json).collect();
        }
        if let Some(s) = stats.simplified() {
            json["simplified"] = serde_json::json!({
                "input_faces": s.input_faces, "faces": s.faces, "qp": s.qp,
            });
        }
        if !stats.candidates.is_empty() {
            json["method"] = crate::report::choice_json(stats, options.effort);
        }
        if let Some(h) = stats.hint() {
            json["hint"] = serde_json::json!({
                "sharpen": h.chosen.sharpen,
                "bend_steps": h.chosen.bend_steps,
                "plain_l2_relative": h.plain_l2,
                "sharpen_l2_relative": h.sharpen_l2,
                "sharpen_bend_l2_relative": h.bend_l2,
                "tips_on_surface": h.tips_on_surface,
                "crease_tips": h.crease_tips,
            });
        }
        if attributed.is_some() {
            json["attribute_report"] = crate::report::attributes_json(&stats.attributes);
        }
        json["check"] = fidelity.map_or(serde_json::Value::Null, |f| f.to_json());
        crate::report::print_json(&json);
        return Ok(());
    }
    // A swing file whose every component went to REST has no retiled
    // triangle to count bits against.
    let per_triangle = if triangles == 0 {
        "no bits/triangle (nothing retiled)".to_string()
    } else {
        format!(
            "{:.3} bits/triangle",
            8.0 * encoded.bytes.len() as f64 / triangles as f64
        )
    };
    say!(
        "{} -> {}: {} bytes ({:.3} bits/input vertex), {} vertices, {} triangles, {per_triangle}, {:.3} s",
        args.input.display(),
        args.output.display(),
        encoded.bytes.len(),
        8.0 * encoded.bytes.len() as f64 / positions.max(1) as f64,
        vertices,
        triangles,
        seconds
    );
    // The error of the file as a viewer decodes it, as `swm distance`
    // measures it (the encoder's check).
    if let Some(l2) = fidelity.as_ref().and_then(|f| f.l2_relative) {
        let h = fidelity
            .as_ref()
            .and_then(|f| f.hausdorff_relative)
            .unwrap_or(l2);
        say!("error to the input: L2 {:.3}, Hausdorff {:.3} (x 1e-4 of the diagonal, as swm distance measures it)", 1e4 * l2, 1e4 * h);
    }
    // The counts above are the file's (of a swing file, the retiled
    // mesh); what a decoder gets differs by what this file has of the
    // hole masks, the loops' fans, the lossless rest and the hint.
    if let Some(f) =
        fidelity.filter(|f| (f.vertices as u64, f.triangles as u64) != (vertices, triangles))
    {
        let why = stats
            .swing()
            .map(|s| crate::report::decoded_counts_why(s, stats.hint().map(|h| h.chosen)))
            .unwrap_or_default();
        say!(
            "decoded mesh: {} vertices, {} triangles{why}",
            f.vertices,
            f.triangles
        );
    }
    if !stats.candidates.is_empty() {
        say!(
            "{}",
            crate::report::choice_line(stats, options.effort, requested)
        );
    }
    if attributed.is_some() && !qp_only {
        say!("{}", crate::report::attributes_line(&stats.attributes));
    }
    if let Some(h) = stats.hint() {
        let chosen = match (h.chosen.sharpen, h.chosen.bend_steps) {
            (false, 0) => "plain decoding (no hint written)",
            (true, 0) => "EdgeSharpener",
            _ => "EdgeSharpener + 1 Bender step",
        };
        let mut tips = if h.tips_on_surface {
            "; tips aimed on the surface, where EdgeSharpener restores more"
        } else {
            ""
        }
        .to_string();
        if h.crease_tips {
            tips.push_str("; tips on the input's creases");
        }
        say!(
            "post-processing hint: {chosen} (L2 x 1e-4 of the diagonal: plain {:.3}, sharpened {:.3}, sharpened and bent {:.3}){tips}",
            1e4 * h.plain_l2,
            1e4 * h.sharpen_l2,
            1e4 * h.bend_l2
        );
    }
    if let swm::MethodStats::Displaced(d) = &stats.method {
        say!(
            "displaced subdivision: a base of {} faces at {} bits per coordinate ({} bytes), {} level{} of scalars ({:?} bytes)",
            d.base_faces,
            d.qp,
            d.base_bytes,
            d.levels,
            if d.levels == 1 { "" } else { "s" },
            d.level_bytes
        );
    }
    if let Some(s) = stats.simplified() {
        say!(
            "simplified from {} to {} faces, {} bits per coordinate",
            s.input_faces,
            s.faces,
            s.qp
        );
        // Never a silent miss: a request beyond what the whole mesh at
        // the finest quantization needs gets that file, and a note.
        if let Some(r) = requested.filter(|_| whole_short) {
            eprintln!(
                "swm: note: {}: the whole mesh at {} bits per coordinate takes {bytes} bytes, less than the {r} asked for; that file was written",
                args.input.display(),
                s.qp
            );
        }
    }
    if let Some(r) = stats.rate() {
        let failed = r.attempts.iter().filter(|a| a.outcome.is_err()).count();
        say!(
            "edge length {:.6} after {} retilings{}{}",
            r.edge_length,
            r.attempts.len(),
            if r.reduced {
                format!(" ({failed} failed: longer edges did not retile this shape, so the longest that did was used)")
            } else {
                String::new()
            },
            if r.within_tolerance {
                ""
            } else {
                "; the size could not be brought within 3% of the request"
            }
        );
    }
    // What cleaning changed and each component's fate are details of the
    // work, not its result: stderr, so that stdout holds the results.
    if !stats.clean.is_clean() {
        eprintln!("cleaning: {}", clean_summary(&stats.clean));
    }
    let plain = |p: &swm::PieceReport| {
        p.holes == 0 && matches!(p.outcome, swm::PieceOutcome::Retiled { .. })
    };
    let pieces = stats.pieces();
    if pieces.len() > 1 || !pieces.iter().all(plain) {
        let listed = if args.verbose {
            pieces.len()
        } else {
            LISTED_COMPONENTS
        };
        for (k, p) in pieces.iter().enumerate().take(listed) {
            eprintln!("component {k}: {}", piece_line(p));
        }
        if pieces.len() > listed {
            eprintln!(
                "... {} more components ({} in all: {}); --verbose lists them all",
                pieces.len() - listed,
                pieces.len(),
                fates(pieces)
            );
        }
    }
    Ok(())
}

/// Judges the encoder's measure of its file against the input (see
/// `fidelity`). What is wrong comes back as the warning line to print
/// once the progress is cleared; with `--strict` it is an error (exit 1,
/// nothing written). A file the encoder did not measure is a warning too
/// (an error with `--strict`), with no figures.
fn check(
    args: &Args,
    check: Option<&swm::Check>,
) -> Result<(Option<crate::fidelity::Fidelity>, Option<String>), CliError> {
    let (fidelity, what) = match check.map(crate::fidelity::Fidelity::of) {
        Some(f) => {
            let problems = f.problems();
            if problems.is_empty() {
                return Ok((Some(f), None));
            }
            let hint = if args.edge_length.is_some() {
                "a shorter --edge-length keeps more"
            } else {
                "a larger --size or --bpv keeps more"
            };
            (Some(f), format!("{}; {hint}", problems.join("; ")))
        }
        None => (
            None,
            "the encoder did not measure its file against the input".to_string(),
        ),
    };
    if args.strict {
        let e = std::io::Error::other(format!("--strict: {what}; nothing written"));
        return Err(CliError::new(&args.input, e));
    }
    let line = format!("swm: warning: {}: {what}", args.input.display());
    Ok((fidelity, Some(line)))
}

/// Refuses an output named like a mesh file (`-o x.obj`): `encode`
/// writes `.swm` whatever the name, and such a file would fool the next
/// program, or person, to open it. `--force` keeps the name; `-` and
/// every other name are fine. Bad usage (exit 2), before any work.
fn refuse_mesh_name(output: &std::path::Path, force: bool) -> Result<(), CliError> {
    if force || crate::pipe::is_stdio(output) {
        return Ok(());
    }
    let Ok(format) = swm::io::MeshFormat::from_path(output) else {
        return Ok(());
    };
    let e = std::io::Error::new(
        std::io::ErrorKind::InvalidInput,
        format!(
            "the name says {}, but encode writes a .swm file (`swm decode` writes meshes); name it .swm, or pass --force to keep this name",
            format.name()
        ),
    );
    Err(CliError::usage(output, e))
}

/// A size rate control could not bring within 3% of the request: a
/// warning on stderr, as the file may not be what the caller budgeted
/// for (the report on stdout says it too).
fn warn_missed_size(input: &std::path::Path, r: &swm::RateReport, bytes: u64) {
    let Some(requested) = r.requested_bytes else {
        return;
    };
    let off = 100.0 * (bytes as f64 - requested as f64) / requested.max(1) as f64;
    let side = if off >= 0.0 { "over" } else { "under" };
    eprintln!(
        "swm: warning: {}: the file is {bytes} bytes, {:.1}% {side} the {requested} requested; rate control could not land within 3%, and the nearest file it made was written",
        input.display(),
        off.abs()
    );
}

/// The one warning line for what the input carried that the file will
/// not hold, and `why`: on stderr whatever carries the report, as
/// warnings are not results (and `--json` on stdout stays the JSON
/// alone). A lossy mode keeps no attribute; the lossless mode keeps
/// every stream the reader could attach to the faces.
/// With `--strict` (`strict`) it is an error instead, before any work:
/// nothing is written (issue 47, item 6).
fn warn_dropped(
    input: &std::path::Path,
    names: &[String],
    why: &str,
    strict: bool,
) -> Result<(), CliError> {
    let listed = match names {
        [] => return Ok(()),
        [one] => one.clone(),
        [init @ .., last] => format!("{} and {last}", init.join(", ")),
    };
    // Every name is a plural: "are".
    let what = format!("the input's {listed} are not kept ({why})");
    if strict {
        let e = std::io::Error::other(format!("--strict: {what}; nothing written"));
        return Err(CliError::new(input, e));
    }
    eprintln!("swm: warning: {}: {what}", input.display());
    Ok(())
}

/// The reader's names of the streams `dropped` flags.
fn names_of(dropped: &swm::io::Attributes) -> Vec<String> {
    dropped.names().map(String::from).collect()
}

/// The reader's flags of the streams `m` carries: what a mode that
/// cannot keep them drops.
fn kinds_of(m: &swm::AttributedMesh) -> swm::io::Attributes {
    let mut a = swm::io::Attributes::default();
    for s in &m.streams {
        match s.kind {
            swm::AttributeKind::Normal => a.normals = true,
            swm::AttributeKind::TexCoord(_) => a.uv = true,
            swm::AttributeKind::Color(_) => a.colors = true,
            _ => a.generic = true,
        }
    }
    a
}

/// How many components met each fate, e.g. "3 retiled, 99997 kept by
/// lossless coding".
fn fates(pieces: &[swm::PieceReport]) -> String {
    let (mut retiled, mut lossless, mut simplified, mut other) = (0usize, 0usize, 0usize, 0usize);
    for p in pieces {
        match p.outcome {
            swm::PieceOutcome::Retiled { .. } => retiled += 1,
            swm::PieceOutcome::Lossless => lossless += 1,
            swm::PieceOutcome::Simplified { .. } => simplified += 1,
            _ => other += 1,
        }
    }
    [
        (retiled, "retiled"),
        (simplified, "simplified"),
        (lossless, "kept by lossless coding"),
        (other, "other"),
    ]
    .iter()
    .filter(|(n, _)| *n > 0)
    .map(|(n, what)| format!("{n} {what}"))
    .collect::<Vec<_>>()
    .join(", ")
}

/// What cleaning changed, as one line of the non-zero counts.
fn clean_summary(r: &swm::CleanReport) -> String {
    let counts = [
        (r.merged_vertices, "coincident vertices merged"),
        (r.unreferenced_vertices, "unreferenced vertices dropped"),
        (r.degenerate_faces(), "degenerate faces dropped"),
        (r.duplicate_faces, "duplicate faces dropped"),
        (r.flipped_faces, "faces reoriented"),
        (r.non_manifold_edges, "non-manifold edges cut"),
        (r.non_manifold_vertices, "non-manifold vertices split"),
    ];
    let parts: Vec<String> = counts
        .iter()
        .filter(|(n, _)| *n > 0)
        .map(|(n, what)| format!("{n} {what}"))
        .collect();
    parts.join(", ")
}

/// One component's fate, for the text report.
fn piece_line(p: &swm::PieceReport) -> String {
    let shape = format!("{} faces, {} holes, genus {}", p.faces, p.holes, p.genus);
    match &p.outcome {
        swm::PieceOutcome::Retiled {
            triangles,
            masked,
            lost_holes,
            loop_points,
        } => {
            let lost = if *lost_holes > 0 {
                format!(", {lost_holes} holes smaller than a triangle closed")
            } else {
                String::new()
            };
            let start = if *loop_points > 0 {
                format!(", started on a boundary loop of {loop_points} points")
            } else {
                String::new()
            };
            format!(
                "{shape}: retiled into {triangles} triangles ({masked} masked as holes){lost}{start}"
            )
        }
        swm::PieceOutcome::Lossless => {
            format!("{shape}: too small for this edge length, kept by lossless coding")
        }
        swm::PieceOutcome::Simplified { faces } => {
            format!("{shape}: simplified to {faces} triangles (closer than a retiling at its share of the size), kept by lossless coding")
        }
        _ => shape.to_string(),
    }
}

fn piece_json(p: &swm::PieceReport) -> serde_json::Value {
    let mut v = serde_json::json!({"faces": p.faces, "holes": p.holes, "genus": p.genus});
    match &p.outcome {
        swm::PieceOutcome::Retiled {
            triangles,
            masked,
            lost_holes,
            loop_points,
        } => {
            v["outcome"] = "retiled".into();
            v["triangles"] = (*triangles).into();
            v["masked_triangles"] = (*masked).into();
            v["lost_holes"] = (*lost_holes).into();
            v["loop_points"] = (*loop_points).into();
        }
        swm::PieceOutcome::Lossless => v["outcome"] = "lossless".into(),
        swm::PieceOutcome::Simplified { faces } => {
            v["outcome"] = "simplified".into();
            v["triangles"] = (*faces).into();
        }
        _ => v["outcome"] = "other".into(),
    }
    v
}

/// `--framing`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub(crate) enum FramingArg {
    Compact,
    Fixed,
}

/// `--effort` ([`swm::Effort`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum EffortArg {
    /// The simplified method with a short search.
    Fast,
    /// The simplified method's lean search (every promising quantization
    /// measured, each size search started where the last one predicts),
    /// SwingWrapper where its retiling fits the level's work budget, and
    /// displaced subdivision for files of at most one byte per seven
    /// input triangles or 3 KB, whichever is larger.
    Default,
    /// Every method's whole search.
    Max,
}

impl From<EffortArg> for swm::Effort {
    fn from(e: EffortArg) -> swm::Effort {
        match e {
            EffortArg::Fast => swm::Effort::Fast,
            EffortArg::Default => swm::Effort::Default,
            EffortArg::Max => swm::Effort::Max,
        }
    }
}
