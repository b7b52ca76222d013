//! `swm rd`: the rate-distortion harness.
//!
//! ```text
//! swm rd MESH... [--rates 0.5,1,2,4,8] [--configs lossless,baseline,swing]
//!        [--samples N] [--out DIR] [--name rd] [--json] [--quiet]
//! swm rd --check TABLE.csv [--only MESH]... [--configs C,...] [--tolerance 0.01] [--out DIR] [--json] [--quiet]
//! ```
//!
//! For every mesh, rate and configuration, code the mesh into
//! ⌊rate × V / 8⌋ bytes (V = vertices of the mesh as read, the unit of the
//! thesis's tables), decode it, and measure the file and the distance of
//! the decoded mesh from the input (L2 and Hausdorff, area-uniform samples
//! on both surfaces, in 1e-4 of the input's bbox diagonal). A
//! configuration that cannot fit the budget gives an `infeasible` row, one
//! whose encoder gives up a `failed` row, and one that does not take the
//! mesh at all (`swing` on a mesh with holes) an `n/a` row; the reasons go
//! to stderr (once per mesh and configuration for `n/a`) after a
//! successful run.
//! With `--out DIR` it writes `DIR/NAME.csv` (see [`table`]), `NAME.md`
//! and one plot per mesh, `NAME-MESH.svg` (see [`plot`]), each atomically.
//!
//! Jobs (mesh × rate × configuration) run in parallel; every number but
//! the times is a pure function of the inputs, and rows come out in
//! (mesh, rate, configuration) order, so a table is reproducible bit for
//! bit. That is what lets `--check` ([`check`]) act as a ratchet.

mod baseline;
mod case;
mod check;
mod code;
mod config;
mod measure;
mod plot;
mod source;
mod table;

use crate::error::{fail, CliError};
use case::Case;
use config::Config;
use rayon::prelude::*;
use source::Source;
use std::path::{Path, PathBuf};
use table::{Outcome, Row};

/// Face samples per direction of a row's final distance, unless `--samples`
/// says otherwise: the count of the shared corpus's peer figures.
const DEFAULT_SAMPLES: u64 = 300_000;

#[derive(clap::Args)]
#[command(after_long_help = HELP)]
pub struct Args {
    /// Meshes: mesh files, `generated:NAME` (a mesh of swm-corpus, built in
    /// memory) or `shared:FILE` (a file of ../shared/corpus).
    #[arg(required_unless_present = "check", conflicts_with = "check")]
    meshes: Vec<String>,
    /// Target rates in bits per vertex of the mesh as read.
    #[arg(long, value_delimiter = ',', default_value = "0.5,1,2,4,8", value_parser = parse_rate, conflicts_with = "check")]
    rates: Vec<f64>,
    /// Configurations to run (default: all but the ablation rows
    /// swing-on-surface and swing-adaptive). With --check: only the rows
    /// of these are re-run and compared; the others are kept as the
    /// table has them (and written so with --out), which refreshes the
    /// rows of a configuration whose encoder changed.
    #[arg(long, value_enum, value_delimiter = ',')]
    configs: Vec<Config>,
    /// Area-uniform face samples per surface for each row's distance (the
    /// encoder compares its own candidates with 30,000).
    #[arg(long, default_value_t = DEFAULT_SAMPLES, value_parser = clap::value_parser!(u64).range(1..), conflicts_with = "check")]
    samples: u64,
    /// Write NAME.csv, NAME.md and NAME-MESH.svg into this folder (with
    /// --check: the fresh results, written before they are compared).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Base name of the files written by --out.
    #[arg(long, default_value = "rd", value_parser = parse_name)]
    name: String,
    /// Re-run the rows of this table and compare; exit 1 if any regressed.
    #[arg(long, value_name = "TABLE")]
    check: Option<PathBuf>,
    /// With --check: only the rows of this mesh (its table name or short
    /// name, e.g. `fandisk`). Repeatable.
    #[arg(long, requires = "check", value_name = "MESH")]
    only: Vec<String>,
    /// With --check: relative growth of l2_rel or hausdorff_rel tolerated.
    #[arg(long, default_value_t = 0.01, value_parser = parse_tolerance)]
    tolerance: f64,
    /// Print the rows (with --check: rows and verdicts) as JSON.
    #[arg(long)]
    json: bool,
    /// No progress bar. It is drawn on standard error only when that is a
    /// terminal and the run takes over a second (one step per mesh, rate
    /// and configuration), never on standard output.
    #[arg(short, long)]
    quiet: bool,
}

const HELP: &str = "\
Rates: the byte budget is floor(rate x V / 8), V = vertices of the mesh as read.
Configurations:
  lossless  swm's lossless mode, the largest qp (6..24) that fits
  baseline  quadric edge collapse (swm's), then the lossless mode,
            at the face count and qp (6..16) with the lowest L2 that fits
            (swm encode --mode lossless --size B)
  auto      swm encode --effort max: swing, baseline or a method per
            component, whichever the encoder measures closer to the input
            (the files the automatic mode wrote before effort levels)
  auto-default  swm encode with no flag (--effort default): baseline,
            swing where its retiling fits the level's work budget, and
            displaced subdivision at low rates (files of at most one byte
            per seven input triangles)
  auto-fast  swm encode --effort fast: meshoptimizer's simplifier, then the
            lossless mode, with a short search
            (the CSV's effort column: max, default, fast; empty for the
            other configurations)
  swing     SwingWrapper as swm encode --mode swing runs it (angle bits
            chosen by rate control, approximating tips), asked for the
            budget and capped at it, decoded as swm decode does by
            default (following the file's post-processing hint)
  swing-plain  the swing file decoded plain, whatever its hint says
  swing+sharpen, swing+sharpen+bend  the swing file decoded with
            EdgeSharpener (and one Bender step)
  swing-on-surface, swing-adaptive  swing with every tip on the input
            surface (the thesis's placement) or with --adaptive; not run
            by default, for ablation
A configuration that cannot fit a budget gives a row with status infeasible;
one whose encoder gives up, failed; one that does not take the mesh, n/a.
The reasons are printed on stderr.
Distances: L2 (larger one-sided RMS) and Hausdorff, from area-uniform face
samples on both surfaces, in units of 1e-4 of the input's bbox diagonal.

--check TABLE re-runs every row of TABLE (same mesh, rate, configuration and
samples) and prints one verdict per row. A row regresses when its file grows
by one byte or more, when l2_rel or hausdorff_rel grows by more than
--tolerance (relative; default 0.01 = 1%) plus 1e-7 of the diagonal, or when
it no longer fits its budget; any regression makes the exit status 1. Rows
that were infeasible and stay so pass.

Tables name meshes so that a fresh clone can check them: generated:NAME,
shared:FILE (found in $SWM_SHARED_CORPUS, else in the shared/corpus folder of
the nearest ancestor of the table's folder or of the current folder), or a
path relative to the table's folder.";

fn parse_rate(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(r) if r.is_finite() && r > 0.0 && r <= 1e6 => Ok(r),
        _ => Err(format!(
            "`{s}` is not a rate (a positive number of bits per vertex)"
        )),
    }
}

fn parse_tolerance(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(t) if t.is_finite() && t >= 0.0 => Ok(t),
        _ => Err(format!(
            "`{s}` is not a tolerance (a non-negative fraction, e.g. 0.01)"
        )),
    }
}

fn parse_name(s: &str) -> Result<String, String> {
    let ok = !s.is_empty()
        && s.chars()
            .all(|c| c.is_ascii_alphanumeric() || matches!(c, '-' | '_' | '.'));
    if ok {
        Ok(s.to_string())
    } else {
        Err(format!(
            "`{s}` is not a file base name (letters, digits, - _ .)"
        ))
    }
}

/// One row to compute.
#[derive(Clone)]
struct Job {
    case: usize,
    rate: f64,
    config: Config,
    samples: u64,
}

pub fn run(args: &Args) -> Result<(), CliError> {
    match &args.check {
        Some(table) => run_check(args, table),
        None => run_fresh(args),
    }
}

/// `swm rd --check TABLE`: re-runs the rows (those of `--only` meshes),
/// prints a verdict per row, and fails naming the first regression.
fn run_check(args: &Args, table_path: &Path) -> Result<(), CliError> {
    // Regular files only, within `max_input_bytes`, as every input.
    let bytes = swm::io::read_file(table_path).map_err(|e| CliError::new(table_path, e))?;
    let text = std::str::from_utf8(&bytes).map_err(|e| {
        CliError::new(
            table_path,
            std::io::Error::new(std::io::ErrorKind::InvalidData, e),
        )
    })?;
    let mut old = table::from_csv(text).map_err(|e| CliError::new(table_path, e))?;
    let table_dir = table_path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let short = |cell: &str| Source::from_table(cell, table_dir).short_name();
    for only in &args.only {
        if !old
            .iter()
            .any(|r| &r.mesh == only || &short(&r.mesh) == only)
        {
            return Err(fail(
                table_path,
                format!("no row is for the mesh `{only}` (--only)"),
            ));
        }
    }
    if !args.only.is_empty() {
        old.retain(|r| {
            args.only
                .iter()
                .any(|o| *o == r.mesh || *o == short(&r.mesh))
        });
    }
    if old.is_empty() {
        return Err(fail(table_path, "the table has no rows"));
    }
    let mut named: Vec<(Source, String)> = Vec::new();
    for r in &old {
        if !named.iter().any(|(_, n)| *n == r.mesh) {
            named.push((Source::from_table(&r.mesh, table_dir), r.mesh.clone()));
        }
    }
    let cases = load(named, Some(table_dir))?;
    let jobs: Vec<Job> = old
        .iter()
        .map(|r| Job {
            case: cases
                .iter()
                .position(|c| c.table_name == r.mesh)
                .expect("loaded"),
            rate: r.rate_bpv,
            config: r.config,
            samples: r.samples,
        })
        .collect();
    // `--configs`: the other rows are kept as they are, not re-run.
    let rerun = |r: &Row| args.configs.is_empty() || args.configs.contains(&r.config);
    let (picked, kept): (Vec<usize>, Vec<usize>) = (0..old.len()).partition(|&i| rerun(&old[i]));
    let picked_jobs: Vec<Job> = picked.iter().map(|&i| jobs[i].clone()).collect();
    let ran = run_jobs(&cases, &picked_jobs, args.quiet)?;
    let mut all: Vec<Option<Row>> = vec![None; old.len()];
    for (&i, r) in picked.iter().zip(ran) {
        all[i] = Some(r);
    }
    for &i in &kept {
        all[i] = Some(old[i].clone());
    }
    let all: Vec<Row> = all.into_iter().map(|r| r.expect("every row")).collect();
    write_outputs(args, &cases, &all)?;
    let old: Vec<Row> = picked.iter().map(|&i| old[i].clone()).collect();
    let fresh: Vec<Row> = picked.iter().map(|&i| all[i].clone()).collect();

    let mut worse = Vec::new();
    let mut json_rows = Vec::new();
    for (o, n) in old.iter().zip(&fresh) {
        let regressions = check::compare(o, n, args.tolerance);
        let line = check::verdict_line(o, n, &regressions);
        if args.json {
            let mut v = n.to_json();
            v["verdict"] = if regressions.is_empty() {
                "pass"
            } else {
                "worse"
            }
            .into();
            v["regressions"] = regressions
                .iter()
                .map(|r| r.to_string())
                .collect::<Vec<_>>()
                .into();
            json_rows.push(v);
        } else {
            say!("{line}");
        }
        if !regressions.is_empty() {
            worse.push(line);
        }
    }
    if args.json {
        crate::report::print_json(&json_rows.into());
    } else {
        say!(
            "{} rows checked, {} regressed (tolerance {}%)",
            old.len(),
            worse.len(),
            100.0 * args.tolerance
        );
    }
    match worse.first() {
        None => Ok(()),
        Some(first) => Err(fail(
            table_path,
            format!(
                "{} of {} rows regressed; first: {}",
                worse.len(),
                old.len(),
                first.trim_start_matches("WORSE").trim_start()
            ),
        )),
    }
}

fn run_fresh(args: &Args) -> Result<(), CliError> {
    let table_dir = args.out.clone().unwrap_or_else(|| PathBuf::from("."));
    let mut sources: Vec<Source> = Vec::new();
    for m in &args.meshes {
        let s = Source::from_arg(m);
        if !sources.contains(&s) {
            sources.push(s);
        }
    }
    let named = sources
        .into_iter()
        .map(|s| {
            let name = s.table_name(&table_dir);
            (s, name)
        })
        .collect();
    let cases = load(named, None)?;
    let mut rates = args.rates.clone();
    rates.sort_by(f64::total_cmp);
    rates.dedup();
    let mut configs = if args.configs.is_empty() {
        Config::default_set()
    } else {
        args.configs.clone()
    };
    configs.sort();
    configs.dedup();
    let mut jobs = Vec::new();
    for case in 0..cases.len() {
        for &rate in &rates {
            for &config in &configs {
                jobs.push(Job {
                    case,
                    rate,
                    config,
                    samples: args.samples,
                });
            }
        }
    }
    let rows = run_jobs(&cases, &jobs, args.quiet)?;
    write_outputs(args, &cases, &rows)?;
    explain(&rows);
    if args.json {
        let v: Vec<_> = rows.iter().map(Row::to_json).collect();
        crate::report::print_json(&v.into());
    } else {
        for r in &rows {
            say!("{}", summary(r));
        }
    }
    Ok(())
}

/// Reads and prepares every mesh, in parallel; refuses two meshes that
/// would share a plot file.
fn load(named: Vec<(Source, String)>, base: Option<&Path>) -> Result<Vec<Case>, CliError> {
    let cases: Vec<Case> = named
        .into_par_iter()
        .map(|(source, name)| {
            let mesh = source.load(base)?;
            Case::new(source, name, mesh)
        })
        .collect::<Result<_, _>>()?;
    for (i, a) in cases.iter().enumerate() {
        if let Some(b) = cases[..i]
            .iter()
            .find(|b| b.source.short_name() == a.source.short_name())
        {
            return Err(fail(
                a.label(),
                format!(
                    "has the same short name as {} ({}): their plots would collide",
                    b.label().display(),
                    a.source.short_name()
                ),
            ));
        }
    }
    Ok(cases)
}

/// Runs every job in parallel, with a progress bar over the (mesh, rate,
/// configuration) cells on a terminal (see `progress`); rows come back in
/// job order.
fn run_jobs(cases: &[Case], jobs: &[Job], quiet: bool) -> Result<Vec<Row>, CliError> {
    let bar = crate::progress::Progress::bar(jobs.len() as u64, quiet).prefix("swm rd");
    bar.phase("cells");
    let rows = jobs
        .par_iter()
        .map(|job| {
            let case = &cases[job.case];
            let vertices = case.vertices();
            let budget = (job.rate * vertices as f64 / 8.0).floor() as u64;
            let outcome = job.config.run(case, budget, job.samples)?;
            bar.inc();
            Ok(Row {
                mesh: case.table_name.clone(),
                rate_bpv: job.rate,
                config: job.config,
                vertices,
                budget_bytes: budget,
                samples: job.samples,
                outcome,
            })
        })
        .collect::<Result<Vec<Row>, CliError>>();
    // Cleared before the rows, the reasons or an error are printed.
    drop(bar);
    rows
}

/// Says on stderr why rows have no file: once per mesh and configuration
/// for one that does not apply (the reason is the same at every rate),
/// once per row for an encoder that gave up. (`--check` says it in the
/// verdict of a row that regressed so.)
fn explain(rows: &[Row]) {
    let mut told: Vec<(&str, Config)> = Vec::new();
    for r in rows {
        match &r.outcome {
            Outcome::NotApplicable { why } if !told.contains(&(r.mesh.as_str(), r.config)) => {
                told.push((&r.mesh, r.config));
                eprintln!(
                    "swm rd: {}: {} does not apply: {why}",
                    r.mesh,
                    r.config.name()
                );
            }
            Outcome::Failed { why } => eprintln!("swm rd: {}: failed: {why}", r.key()),
            _ => {}
        }
    }
}

/// `--out DIR`: the CSV, the Markdown and one plot per mesh.
fn write_outputs(args: &Args, cases: &[Case], rows: &[Row]) -> Result<(), CliError> {
    let Some(dir) = &args.out else {
        return Ok(());
    };
    std::fs::create_dir_all(dir).map_err(|e| CliError::new(dir, e))?;
    let short = |mesh: &str| {
        cases
            .iter()
            .find(|c| c.table_name == mesh)
            .map_or_else(|| mesh.to_string(), |c| c.source.short_name())
    };
    let write = |file: String, text: String| {
        let path = dir.join(file);
        swm::io::write_bytes(&path, text.as_bytes()).map_err(|e| CliError::new(&path, e))
    };
    // Rows name meshes for the table they came from (`--check`); the new
    // table names them for its own folder.
    let rows: Vec<Row> = rows
        .iter()
        .map(|r| {
            let case = cases.iter().find(|c| c.table_name == r.mesh);
            let mesh = case.map_or_else(|| r.mesh.clone(), |c| c.source.table_name(dir));
            Row { mesh, ..r.clone() }
        })
        .collect();
    let rows = &rows[..];
    write(format!("{}.csv", args.name), table::to_csv(rows))?;
    write(
        format!("{}.md", args.name),
        table::to_markdown(&args.name, rows, short),
    )?;
    for case in cases {
        let mine: Vec<&Row> = rows.iter().filter(|r| r.mesh == case.table_name).collect();
        let name = case.source.short_name();
        let title = format!("{name}: L2 error against rate");
        let file = format!("{}-{name}.svg", args.name);
        let svg = plot::svg(&title, &mine).map_err(|e| fail(dir.join(&file), e))?;
        write(file, svg)?;
    }
    Ok(())
}

/// One line per row for the terminal.
fn summary(r: &Row) -> String {
    match (r.coded(), r.bpv()) {
        (Some(c), Some(bpv)) => format!(
            "{}: {} B ({bpv:.3} bpv), {} faces, {}, L2 {:.3}, Hausdorff {:.2} (1e-4 of the diagonal), encode {:.3} s, decode {:.4} s",
            r.key(),
            c.bytes,
            c.faces,
            match r.config {
                Config::Swing
                | Config::SwingPlain
                | Config::SwingOnSurface
                | Config::SwingAdaptive
                | Config::SwingSharpen
                | Config::SwingSharpenBend => {
                    format!("{} angle bits", c.qp)
                }
                _ => format!("qp {}", c.qp),
            },
            c.l2_rel,
            c.hausdorff_rel,
            c.encode_s,
            c.decode_s
        ),
        _ => format!("{}: {} (budget {} B)", r.key(), r.status(), r.budget_bytes),
    }
}
